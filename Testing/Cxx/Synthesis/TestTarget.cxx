// Tests of Kernels/Synthesis/Target.cxx: the target a DEM sketch makes.
#include "Core/Heightfield.h"
#include "Features/FeatureGraph.h"
#include "LandformTestData.h"
#include "Synthesis/Target.h"

#include <gtest/gtest.h>

#include <vector>

using namespace tsynth;
using tsynth::test::landform::terrain;

TEST(TargetFromHeights, PercentilesLandOnTheExemplarsSoTheReliefKeepsItsSize)
{
  // A DEM ramp from 0 to 1000 m: its 5th and 95th percentiles (50, 950 m)
  // land on the exemplars' (2000, 3800 m); the whole range maps beyond them,
  // as steep as the DEM asks (its full range onto theirs squeezed it).
  const Heightfield dem = terrain(200, 50, [](int i, int) { return 1000.0 * i / 199.0; });
  ExemplarStatistics stats;
  stats.low = 2000.0;
  stats.high = 3800.0;
  const SynthesisTarget t = targetFromHeights(dem, FeatureGraph{}, stats);
  std::vector<float> heights(t.field.z.begin(), t.field.z.end());
  EXPECT_NEAR(percentile(heights, 0.05), 2000.0, 15.0);
  EXPECT_NEAR(percentile(heights, 0.95), 3800.0, 15.0);
  EXPECT_NEAR(t.field.at(0, 10), 2000.0 - 50.0 * 1800.0 / 900.0, 15.0);
  EXPECT_NEAR(t.field.at(199, 10), 3800.0 + 50.0 * 1800.0 / 900.0, 15.0);
  EXPECT_TRUE(t.detailed);
  EXPECT_EQ(t.halfWidth.size(), t.field.size());
}
