// Tests of Kernels/Matching/NoiseVariance.cxx.
// The multi-resolution noise variance (Tasse's thesis, 4.3.1) read from
// summed-area tables must be the variance a direct count over the window
// gives, on clipped windows and around nodata too.
#include "Features/Ppa.h"
#include "Matching/NoiseVariance.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <random>
#include <vector>

using namespace tsynth;

namespace
{

// Rolling ridges with seeded noise: every band of the pyramid holds something.
Heightfield bumpyField()
{
  Heightfield hf(96, 80);
  hf.cellX = hf.cellY = 30.0;
  std::mt19937 rng(7);
  std::normal_distribution<float> noise(0.0f, 3.0f);
  for (int j = 0; j < hf.height; ++j)
  {
    for (int i = 0; i < hf.width; ++i)
    {
      hf.at(i, j) =
        static_cast<float>(200.0 * std::sin(i * 0.13) + 80.0 * std::cos(j * 0.21)) + noise(rng);
    }
  }
  return hf;
}

// The same with a block of nodata (NaN, masked).
Heightfield withHole(Heightfield hf)
{
  for (int j = 30; j < 45; ++j)
  {
    for (int i = 40; i < 60; ++i)
    {
      hf.at(i, j) = std::numeric_limits<float>::quiet_NaN();
    }
  }
  normaliseMask(hf);
  return hf;
}

// Variance of each band (blur at sigma 2^(l-1) minus blur at 2^l; level 0 the
// heights minus blur 1) over the valid cells of the window the kernel reads:
// `size` cells from round(c - size/2), clipped to the grid. Two passes, in double.
std::vector<double> directVariances(const Heightfield& hf, double cx, double cy, int size)
{
  std::vector<double> out;
  Heightfield finer = hf;
  for (int l = 0; l < kNoiseLevels; ++l)
  {
    const Heightfield coarser = gaussianSmooth(hf, std::pow(2.0, l));
    const int i0 = std::clamp(static_cast<int>(std::lround(cx - 0.5 * size)), 0, hf.width);
    const int j0 = std::clamp(static_cast<int>(std::lround(cy - 0.5 * size)), 0, hf.height);
    const int i1 = std::min(i0 + size, hf.width);
    const int j1 = std::min(j0 + size, hf.height);
    std::vector<double> band;
    for (int j = j0; j < j1; ++j)
    {
      for (int i = i0; i < i1; ++i)
      {
        if (hf.isValid(i, j))
        {
          band.push_back(static_cast<double>(finer.at(i, j)) - coarser.at(i, j));
        }
      }
    }
    double mean = 0.0;
    for (double b : band)
    {
      mean += b;
    }
    mean /= static_cast<double>(band.size());
    double variance = 0.0;
    for (double b : band)
    {
      variance += (b - mean) * (b - mean);
    }
    out.push_back(variance / static_cast<double>(band.size()));
    finer = coarser;
  }
  return out;
}

void expectDirect(const Heightfield& hf, double cx, double cy, int size)
{
  SCOPED_TRACE(::testing::Message() << "window " << size << " at (" << cx << ", " << cy << ")");
  const NoiseVariance tables(hf);
  const std::array<float, kNoiseLevels> fast = tables.window(cx, cy, size);
  const std::vector<double> direct = directVariances(hf, cx, cy, size);
  for (std::size_t l = 0; l < direct.size(); ++l)
  {
    ASSERT_GT(direct[l], 0.01) << "level " << l << " holds nothing to compare";
    // Float storage of the result; the tables' running sums cost a little more.
    EXPECT_NEAR(fast[l], direct[l], 1e-4 * direct[l]) << "level " << l;
  }
}

} // namespace

TEST(NoiseVariance, EachLevelIsTheVarianceOfItsBandOverTheWindow)
{
  const Heightfield hf = bumpyField();
  expectDirect(hf, 48.0, 40.0, 32); // inside
  expectDirect(hf, 3.0, 77.0, 24);  // clipped at the west and north edges
  expectDirect(hf, 95.0, 0.0, 64);  // clipped at two edges, most of it outside
}

TEST(NoiseVariance, NodataIsLeftOutOfTheVariance)
{
  const Heightfield hf = withHole(bumpyField());
  ASSERT_TRUE(hf.hasMask());
  expectDirect(hf, 50.0, 38.0, 32); // the hole inside the window
  expectDirect(hf, 60.0, 45.0, 16); // a corner of it
}

TEST(NoiseVariance, HeightsTwiceAsHighHaveFourTimesTheVariance)
{
  const Heightfield hf = bumpyField();
  Heightfield doubled = hf;
  for (float& z : doubled.z)
  {
    z *= 2.0f;
  }
  const std::array<float, kNoiseLevels> once = NoiseVariance(hf).window(48.0, 40.0, 40);
  const std::array<float, kNoiseLevels> twice = NoiseVariance(doubled).window(48.0, 40.0, 40);
  for (std::size_t l = 0; l < kNoiseLevels; ++l)
  {
    EXPECT_NEAR(twice[l], 4.0f * once[l], 1e-4f * twice[l]) << "level " << l;
  }
}

TEST(NoiseVariance, AWindowOfOneValidCellOrNoneHasNoVariance)
{
  const Heightfield hf = withHole(bumpyField());
  const NoiseVariance tables(hf);
  for (float v : tables.window(50.0, 37.0, 8)) // wholly inside the hole
  {
    EXPECT_EQ(v, 0.0f);
  }
  for (float v : tables.window(0.0, 0.0, 1)) // one cell
  {
    EXPECT_EQ(v, 0.0f);
  }
  for (float v : NoiseVariance().window(10.0, 10.0, 8)) // no tables at all
  {
    EXPECT_EQ(v, 0.0f);
  }
}
