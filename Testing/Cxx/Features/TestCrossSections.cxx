// Tests of Kernels/Features/CrossSections.cxx: cross-sections and the land's own relief on
// analytic surfaces.
#include "Features/CrossSections.h"
#include "FeaturesTestData.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace tsynth;
using tsynth::test::features::rough;
using tsynth::test::features::surface;

TEST(CrossSections, AVShapedValleyStandsOutByHalfItsDepthAndAPlaneNotAtAll)
{
  // A V 300 m deep over 30 cells each side: smoothed at a third of the half
  // width its floor rises by about a quarter of the depth, its outer halves
  // average three quarters of the rim less what the smoothing at the section's
  // ends takes: a little over a third of the depth.
  std::vector<double> v(61), plane(61);
  for (int s = -30; s <= 30; ++s)
  {
    v[static_cast<std::size_t>(s + 30)] = 300.0 * std::abs(s) / 30.0;
    plane[static_cast<std::size_t>(s + 30)] = 5.0 * s;
  }
  const double valley = sectionProminence(v, -1.0);
  EXPECT_GT(valley, 0.3 * 300.0);
  EXPECT_LT(valley, 0.45 * 300.0);
  EXPECT_LT(sectionProminence(v, 1.0), 0.0); // no crest there
  EXPECT_NEAR(sectionRelief(plane), 0.0, 1e-9);
  // A tilted plane has one side higher than its middle: no ridge, no valley.
  EXPECT_LT(sectionProminence(plane, 1.0), 0.0);
  EXPECT_LT(sectionProminence(plane, -1.0), 0.0);
}

TEST(CrossSections, LandReliefGrowsWithRoughnessAndIsZeroOnAPlane)
{
  const Heightfield plane = surface(200, 200, [](int i, int j) { return 3.0 * i - 2.0 * j; });
  const Heightfield gentle = rough(200, 200, 10.0, 7);
  const Heightfield rugged = rough(200, 200, 40.0, 7);
  const LandRelief flat({ &plane });
  const LandRelief soft({ &gentle });
  const LandRelief hard({ &rugged });
  for (double h : { 4.0, 10.0, 30.0 })
  {
    EXPECT_NEAR(flat.at(h), 0.0, 1e-3) << h; // float rounding of the bilinear reads
    EXPECT_GT(soft.at(h), 0.0) << h;
    // Relief scales with the heights: four times the amplitude, four times the relief.
    EXPECT_NEAR(hard.at(h) / soft.at(h), 4.0, 1e-3) << h;
  }
  EXPECT_GT(soft.at(30.0), soft.at(4.0)); // wider sections see more of the relief
  // A plane's steepest sections run down its gradient: 3.6 m per cell.
  EXPECT_NEAR(flat.steepSlope(10.0), std::hypot(3.0, 2.0), 0.02);
  EXPECT_NEAR(hard.steepSlope(10.0) / soft.steepSlope(10.0), 4.0, 1e-3);
  EXPECT_EQ(LandRelief({ &gentle }).at(16.0), soft.at(16.0)); // a fixed seed
  EXPECT_EQ(LandRelief().at(16.0), 0.0);
}
