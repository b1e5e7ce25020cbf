// Tests of Kernels/Distance/DistanceField.cxx: exact distance fields with the nearest seed,
// against a brute-force answer.
#include "Core/Error.h"
#include "Distance/DistanceField.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

using namespace tsynth;

namespace
{

struct SeedGrid
{
  int width;
  int height;
  double cellX;
  double cellY;
};

std::vector<std::uint8_t> randomSeeds(const SeedGrid& g, double density, unsigned seed)
{
  std::mt19937 rng(seed);
  std::bernoulli_distribution pick(density);
  std::vector<std::uint8_t> s(static_cast<std::size_t>(g.width) * g.height);
  for (auto& v : s)
  {
    v = pick(rng) ? 1 : 0;
  }
  return s;
}

// Squared metric distance between cells a and b (exact in double for these sizes).
double squaredMetres(const SeedGrid& g, std::size_t a, std::size_t b)
{
  const std::size_t w = static_cast<std::size_t>(g.width);
  const double dx = (static_cast<double>(a % w) - static_cast<double>(b % w)) * g.cellX;
  const double dy = (static_cast<double>(a / w) - static_cast<double>(b / w)) * g.cellY;
  return dx * dx + dy * dy;
}

// Every cell against every seed: the distance, and the seed the documented tie
// rule picks among those at that distance (lowest column, then lowest row).
struct BruteForce
{
  std::vector<double> squared;
  std::vector<std::int32_t> nearest;
};

BruteForce bruteForce(const std::vector<std::uint8_t>& seeds, const SeedGrid& g)
{
  const std::size_t n = seeds.size();
  const std::size_t w = static_cast<std::size_t>(g.width);
  BruteForce b;
  b.squared.assign(n, std::numeric_limits<double>::infinity());
  b.nearest.assign(n, -1);
  for (std::size_t c = 0; c < n; ++c)
  {
    for (std::size_t s = 0; s < n; ++s)
    {
      if (seeds[s] == 0)
      {
        continue;
      }
      const double d2 = squaredMetres(g, c, s);
      const std::size_t best = static_cast<std::size_t>(b.nearest[c]);
      const bool tieWins = b.nearest[c] >= 0 && d2 == b.squared[c] &&
        (s % w < best % w || (s % w == best % w && s / w < best / w));
      if (d2 < b.squared[c] || tieWins)
      {
        b.squared[c] = d2;
        b.nearest[c] = static_cast<std::int32_t>(s);
      }
    }
  }
  return b;
}

void expectMatchesBruteForce(const SeedGrid& g, double density, unsigned seed)
{
  const std::vector<std::uint8_t> seeds = randomSeeds(g, density, seed);
  const NearestSeeds fast = nearestSeeds(seeds, g.width, g.height, g.cellX, g.cellY);
  const BruteForce slow = bruteForce(seeds, g);
  ASSERT_EQ(fast.distance.size(), seeds.size());
  ASSERT_EQ(fast.nearest.size(), seeds.size());
  const bool any = std::count(seeds.begin(), seeds.end(), 1) > 0;
  EXPECT_EQ(fast.empty(), !any);
  for (std::size_t c = 0; c < seeds.size(); ++c)
  {
    const std::string where = std::to_string(g.width) + " x " + std::to_string(g.height) +
      ", cells " + std::to_string(g.cellX) + " x " + std::to_string(g.cellY) + ", density " +
      std::to_string(density) + ", cell " + std::to_string(c);
    if (!any)
    {
      ASSERT_TRUE(std::isinf(fast.distance[c])) << where;
      ASSERT_EQ(fast.nearest[c], -1) << where;
      continue;
    }
    ASSERT_EQ(fast.distance[c], static_cast<float>(std::sqrt(slow.squared[c]))) << where;
    const std::int32_t k = fast.nearest[c];
    ASSERT_GE(k, 0) << where;
    ASSERT_EQ(seeds[static_cast<std::size_t>(k)], 1) << where;
    ASSERT_EQ(squaredMetres(g, c, static_cast<std::size_t>(k)), slow.squared[c]) << where;
    ASSERT_EQ(k, slow.nearest[c]) << where << ": the tie rule";
  }
}

} // namespace

TEST(DistanceField, EqualsBruteForceOnRandomSeeds)
{
  const std::vector<SeedGrid> grids = { { 37, 23, 1.0, 1.0 },
    { 41, 29, 30.0, 90.0 },
    { 29, 41, 90.0, 30.0 },
    { 64, 1, 30.0, 90.0 },
    { 1, 57, 30.0, 90.0 },
    { 1, 1, 1.0, 1.0 } };
  // From a lone seed to a seed in every third cell.
  const std::array<double, 4> densities = { 0.002, 0.02, 0.1, 0.35 };
  unsigned seed = 1;
  for (const SeedGrid& g : grids)
  {
    for (double density : densities)
    {
      expectMatchesBruteForce(g, density, seed++);
      if (HasFatalFailure())
      {
        return;
      }
    }
  }
}

TEST(DistanceField, TiesAndSingleSeeds)
{
  // One seed: its own cell at 0, the far corner at the metric diagonal.
  std::vector<std::uint8_t> one(10 * 6, 0);
  one[2 * 10 + 3] = 1; // (3, 2)
  const NearestSeeds a = nearestSeeds(one, 10, 6, 30.0, 90.0);
  EXPECT_EQ(a.distance[2 * 10 + 3], 0.0f);
  EXPECT_FLOAT_EQ(a.distance[5 * 10 + 9], static_cast<float>(std::hypot(6 * 30.0, 3 * 90.0)));
  for (std::int32_t k : a.nearest)
  {
    EXPECT_EQ(k, 2 * 10 + 3);
  }
  // Seeds (1, 0) and (0, 1) are both one cell from (1, 1) and (0, 0): the one
  // in the lower column wins, though its index is the higher.
  std::vector<std::uint8_t> two(3 * 3, 0);
  two[1] = two[3] = 1;
  const NearestSeeds b = nearestSeeds(two, 3, 3);
  EXPECT_EQ(b.nearest[4], 3);
  EXPECT_EQ(b.nearest[0], 3);
  EXPECT_EQ(b.distance[4], 1.0f);
}

TEST(DistanceField, NoSeedsAndBadInput)
{
  const NearestSeeds none = nearestSeeds(std::vector<std::uint8_t>(12, 0), 4, 3, 30.0, 30.0);
  EXPECT_TRUE(none.empty());
  for (std::size_t c = 0; c < 12; ++c)
  {
    EXPECT_EQ(none.distance[c], std::numeric_limits<float>::infinity());
    EXPECT_EQ(none.nearest[c], -1);
  }
  EXPECT_THROW(nearestSeeds(std::vector<std::uint8_t>(11, 1), 4, 3), Error);
  EXPECT_THROW(nearestSeeds(std::vector<std::uint8_t>(13, 1), 4, 3), Error);
  EXPECT_THROW(distanceTransform(std::vector<std::uint8_t>(5, 1), 2, 2), Error);
}

TEST(DistanceField, DistancesOnlyEqualBruteForceInUnitCells)
{
  // distanceTransform keeps no nearest-seed plane (its own path through the
  // second pass), so it is checked against the brute force on its own,
  // including grids one cell wide or high and grids without any seed.
  const std::vector<SeedGrid> grids = {
    { 19, 13, 1.0, 1.0 }, { 40, 3, 1.0, 1.0 }, { 1, 33, 1.0, 1.0 }, { 35, 1, 1.0, 1.0 }
  };
  const std::array<double, 4> densities = { 0.0, 0.01, 0.05, 0.3 };
  unsigned seed = 99;
  for (const SeedGrid& g : grids)
  {
    for (double density : densities)
    {
      const std::vector<std::uint8_t> seeds = randomSeeds(g, density, seed++);
      const std::vector<float> d = distanceTransform(seeds, g.width, g.height);
      const BruteForce slow = bruteForce(seeds, g);
      ASSERT_EQ(d.size(), seeds.size());
      for (std::size_t c = 0; c < seeds.size(); ++c)
      {
        ASSERT_EQ(d[c], static_cast<float>(std::sqrt(slow.squared[c])))
          << g.width << " x " << g.height << ", density " << density << ", cell " << c;
      }
      EXPECT_EQ(d, nearestSeeds(seeds, g.width, g.height).distance);
    }
  }
}
