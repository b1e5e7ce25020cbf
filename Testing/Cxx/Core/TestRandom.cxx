// Tests of Kernels/Core/Random.h.
// The project's one seeded-randomness scheme (Core/Random.h): counter-based
// numbers per (seed, stream, index), and the indices drawn from them.
#include "Core/Random.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <set>

using namespace tsynth;

TEST(SeededUniform, DeterministicDistinctAndUniform)
{
  // Known at compile time, and the same at every call.
  static_assert(seededUniform(1, 2, 3) == seededUniform(1, 2, 3));
  constexpr int kDraws = 100000;
  constexpr int kBins = 20;
  std::array<int, kBins> bins{};
  double sum = 0.0;
  std::set<double> seen;
  for (int k = 0; k < kDraws; ++k)
  {
    const double u = seededUniform(42, 7, static_cast<std::uint64_t>(k));
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
    ++bins[static_cast<std::size_t>(u * kBins)];
    seen.insert(u);
  }
  EXPECT_EQ(seen.size(), static_cast<std::size_t>(kDraws)) << "53-bit draws do not repeat";
  // Mean of 1e5 uniforms: standard error 1 / sqrt(12e5) = 0.0009; 4 sigma.
  EXPECT_NEAR(sum / kDraws, 0.5, 0.0037);
  // Bin counts: 5000 expected, standard deviation sqrt(5000 * 0.95) = 69; 5 sigma.
  for (int b : bins)
  {
    EXPECT_NEAR(b, kDraws / kBins, 345) << "bin count";
  }
  // Changing the seed, the stream or the index changes the number.
  const double base = seededUniform(42, 7, 1000);
  EXPECT_NE(base, seededUniform(43, 7, 1000));
  EXPECT_NE(base, seededUniform(42, 8, 1000));
  EXPECT_NE(base, seededUniform(42, 7, 1001));
  // Seeds, streams and indices are not interchangeable.
  EXPECT_NE(seededUniform(1, 2, 3), seededUniform(2, 1, 3));
  EXPECT_NE(seededUniform(1, 2, 3), seededUniform(3, 2, 1));
  // Neighbouring seeds give unrelated sequences: correlation of the first 1e4 draws.
  constexpr int kPairs = 10000;
  double sxy = 0.0, sx = 0.0, sy = 0.0, sxx = 0.0, syy = 0.0;
  for (int k = 0; k < kPairs; ++k)
  {
    const double x = seededUniform(5, 0, static_cast<std::uint64_t>(k));
    const double y = seededUniform(6, 0, static_cast<std::uint64_t>(k));
    sx += x;
    sy += y;
    sxy += x * y;
    sxx += x * x;
    syy += y * y;
  }
  const double cov = sxy / kPairs - (sx / kPairs) * (sy / kPairs);
  const double r = cov /
    std::sqrt(
      (sxx / kPairs - std::pow(sx / kPairs, 2)) * (syy / kPairs - std::pow(sy / kPairs, 2)));
  EXPECT_LT(std::abs(r), 0.04) << "4 standard errors of a correlation over 1e4 pairs";
}

TEST(SeededIndex, InRangeUniformAndDeterministic)
{
  static_assert(seededIndex(1, 2, 3, 10) == seededIndex(1, 2, 3, 10));
  EXPECT_EQ(seededIndex(9, 5, 123, 1), 0u) << "one choice: always it";
  // Seven choices, 7e4 draws: 1e4 expected per choice, sd sqrt(1e4 * 6/7) = 93; 5 sigma.
  constexpr std::uint64_t kChoices = 7;
  constexpr int kDraws = 70000;
  std::array<int, kChoices> counts{};
  for (int k = 0; k < kDraws; ++k)
  {
    const std::uint64_t i = seededIndex(42, kStreamOutlet, static_cast<std::uint64_t>(k), kChoices);
    ASSERT_LT(i, kChoices);
    ++counts[i];
  }
  for (int c : counts)
  {
    EXPECT_NEAR(c, kDraws / static_cast<int>(kChoices), 465) << "choice count";
  }
  // The index follows the uniform number: the same decision, the same bucket.
  for (std::uint64_t k = 0; k < 1000; ++k)
  {
    const double u = seededUniform(3, kStreamChoice, k);
    EXPECT_EQ(seededIndex(3, kStreamChoice, k, 1000), static_cast<std::uint64_t>(u * 1000.0)) << k;
  }
}

TEST(SeededIndex, TheSynthesisStreamsAreDistinct)
{
  const std::set<std::uint64_t> streams = {
    kStreamGrid, kStreamFillOrder, kStreamChoice, kStreamSites, kStreamOutlet
  };
  EXPECT_EQ(streams.size(), 5u) << "two kinds of decision would draw the same numbers";
}
