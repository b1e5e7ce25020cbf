// Tests of Kernels/Hydrology/MultiscalePitRemoval.cxx.
// Pit removal through a pyramid (the synthesis' --drainage): every cell
// drains, each method keeps its sign of change, and wide basins keep the
// surface's texture instead of becoming flat lakes.
#include "Core/Error.h"
#include "Core/HeightfieldIO.h"
#include "Hydrology/Flow.h"
#include "Hydrology/MultiscalePitRemoval.h"
#include "Hydrology/PitRemoval.h"
#include "TestData.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace tsynth;
using tsynth::test::bundledData;

namespace
{

Heightfield colorado()
{
  return readHeightfield((bundledData() / "dems" / "colorado.png").string());
}

// A closed bowl 200 m deep and 150 cells across with 5 m of seeded white
// noise on it: one wide depression and hundreds of small pits.
Heightfield noisyBowl()
{
  constexpr int kSide = 256;
  std::mt19937 random(7);
  std::uniform_real_distribution<double> noise(-5.0, 5.0);
  Heightfield hf(kSide, kSide);
  hf.cellX = hf.cellY = 30.0;
  for (int j = 0; j < kSide; ++j)
  {
    for (int i = 0; i < kSide; ++i)
    {
      const double r = std::hypot(i - kSide / 2.0, j - kSide / 2.0);
      hf.at(i, j) =
        static_cast<float>(1000.0 - 200.0 * std::exp(-r * r / (2.0 * 50.0 * 50.0)) + noise(random));
    }
  }
  return hf;
}

// Standard deviation of the 4-neighbour Laplacian over cells within `radius`
// of the centre: the surface's small-scale texture there.
double textureNearCentre(const Heightfield& hf, double radius)
{
  double sum = 0.0;
  double sum2 = 0.0;
  int n = 0;
  for (int j = 1; j + 1 < hf.height; ++j)
  {
    for (int i = 1; i + 1 < hf.width; ++i)
    {
      if (std::hypot(i - hf.width / 2.0, j - hf.height / 2.0) > radius)
      {
        continue;
      }
      const double l =
        hf.at(i + 1, j) + hf.at(i - 1, j) + hf.at(i, j + 1) + hf.at(i, j - 1) - 4.0 * hf.at(i, j);
      sum += l;
      sum2 += l * l;
      ++n;
    }
  }
  const double mean = sum / n;
  return std::sqrt(sum2 / n - mean * mean);
}

} // namespace

TEST(MultiscalePitRemoval, FillDrainsTheRealDemAndNeverLowersACell)
{
  Heightfield dem = colorado();
  const Heightfield before = dem;
  MultiscalePitRemovalOptions o;
  o.pitRemoval.method = PitRemovalMethod::Fill;
  const MultiscalePitRemovalReport r = removePitsMultiscale(dem, o);
  EXPECT_TRUE(drainsEverywhere(dem, nullptr));
  EXPECT_EQ(r.pitsBefore, countPits(before));
  EXPECT_GT(r.pitsBefore, 100u);
  EXPECT_EQ(r.pitsAfter, 0u);
  EXPECT_EQ(r.levels, 5); // 16, 8, 4, 2 and the cells
  for (std::size_t k = 0; k < dem.size(); ++k)
  {
    ASSERT_GE(dem.z[k], before.z[k]) << k;
  }
  EXPECT_EQ(r.loweredCells, 0u);
  EXPECT_GT(r.raisedCells, 1000u);
}

TEST(MultiscalePitRemoval, FactorOneIsThePlainMethod)
{
  Heightfield dem = colorado();
  MultiscalePitRemovalOptions o;
  o.pitRemoval.method = PitRemovalMethod::Fill;
  o.coarsestFactor = 1;
  const Heightfield plain = fillDepressions(dem);
  const MultiscalePitRemovalReport r = removePitsMultiscale(dem, o);
  EXPECT_EQ(r.levels, 1);
  EXPECT_EQ(dem.z, plain.z);
}

TEST(MultiscalePitRemoval, AWideBasinKeepsItsTextureWhereAPlainFillMakesALake)
{
  const Heightfield bowl = noisyBowl();
  const double original = textureNearCentre(bowl, 40.0);
  const Heightfield plain = fillDepressions(bowl);
  Heightfield multiscale = bowl;
  MultiscalePitRemovalOptions o;
  o.pitRemoval.method = PitRemovalMethod::Fill;
  o.coarsestFactor = 32;
  removePitsMultiscale(multiscale, o);
  EXPECT_TRUE(drainsEverywhere(multiscale, nullptr));
  // The plain fill floods the bowl flat: no texture left in it.
  EXPECT_LT(textureNearCentre(plain, 40.0), 0.01 * original);
  // Through the pyramid the basin is raised smoothly and keeps most of its noise.
  EXPECT_GT(textureNearCentre(multiscale, 40.0), 0.5 * original);
}

// 99.9th percentile of |4-neighbour Laplacian| (metres): where slots show.
double sharpest(const Heightfield& hf)
{
  std::vector<float> l;
  for (int j = 1; j + 1 < hf.height; ++j)
  {
    for (int i = 1; i + 1 < hf.width; ++i)
    {
      l.push_back(std::abs(hf.at(i + 1, j) + hf.at(i - 1, j) + hf.at(i, j + 1) + hf.at(i, j - 1) -
        4.0f * hf.at(i, j)));
    }
  }
  return percentile(l, 0.999);
}

TEST(MultiscalePitRemoval, BreachingCutsAValleyNotASlotAndFillsTheLastSmallPits)
{
  const Heightfield bowl = noisyBowl();
  // Breaching on the cells alone: a one-cell channel 200 m deep out of the bowl.
  const Heightfield plain = breachDepressions(bowl);
  Heightfield multiscale = bowl;
  MultiscalePitRemovalOptions o;
  o.pitRemoval.method = PitRemovalMethod::Breach;
  o.coarsestFactor = 32;
  const MultiscalePitRemovalReport r = removePitsMultiscale(multiscale, o);
  EXPECT_TRUE(drainsEverywhere(multiscale, nullptr));
  EXPECT_EQ(r.pitsAfter, 0u);
  // The bowl is opened by lowering (a valley), not by raising it to its rim:
  // what is raised is the noise's own few-cell pits, a few metres at most.
  EXPECT_GT(r.largestLowering, 150.0);
  EXPECT_LT(r.largestRaise, 10.0);
  // No slot: the sharpest curvature stays that of the noise, where the plain
  // breach's channel walls make it several times sharper.
  EXPECT_GT(sharpest(plain), 3.0 * sharpest(bowl));
  EXPECT_LT(sharpest(multiscale), 1.5 * sharpest(bowl));
}

TEST(MultiscalePitRemoval, TheFineGridIsFilledWhateverTheCoarseLevelsDo)
{
  // On the bundled synthesis sketches, breaching the fine grid too doubled the
  // seam index (one-cell slots); the contract is that it is filled.
  Heightfield dem = colorado();
  MultiscalePitRemovalOptions o;
  o.pitRemoval.method = PitRemovalMethod::Breach;
  o.coarsestFactor = 1; // the fine grid only
  removePitsMultiscale(dem, o);
  EXPECT_EQ(dem.z, fillDepressions(colorado()).z);
  o.finestMethod = PitRemovalMethod::Breach;
  dem = colorado();
  removePitsMultiscale(dem, o);
  EXPECT_EQ(dem.z, breachDepressions(colorado()).z);
}

TEST(MultiscalePitRemoval, UserSinksStayLakes)
{
  Heightfield bowl = noisyBowl();
  std::vector<std::uint8_t> sinks(bowl.size(), 0);
  const std::size_t centre = bowl.index(bowl.width / 2, bowl.height / 2);
  sinks[centre] = 1;
  MultiscalePitRemovalOptions o;
  o.pitRemoval.method = PitRemovalMethod::Fill;
  o.pitRemoval.sinks = &sinks;
  const MultiscalePitRemovalReport r = removePitsMultiscale(bowl, o);
  EXPECT_TRUE(drainsEverywhere(bowl, &sinks));
  // The bowl drains to its own bottom: it is not raised to its rim.
  EXPECT_LT(r.largestRaise, 30.0);
}

TEST(MultiscalePitRemoval, RefusesAFactorBelowOne)
{
  Heightfield dem = noisyBowl();
  MultiscalePitRemovalOptions o;
  o.coarsestFactor = 0;
  EXPECT_THROW(removePitsMultiscale(dem, o), Error);
}
