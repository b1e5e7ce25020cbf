// Tests of Kernels/Features/Profiles.cxx: the profiles sampled along and across PPA's chains.
#include "Features/Ppa.h"
#include "Features/Profiles.h"
#include "FeaturesTestData.h"

#include <gtest/gtest.h>

#include <algorithm>

using namespace tsynth;
using tsynth::test::features::KnownRidges;

TEST(Ppa, ProfilesAcrossARidgeAreSymmetricAndPeakOnIt)
{
  const KnownRidges truth;
  const Heightfield hf = truth.surface(1.0);
  const FeatureExtraction r = extractFeatures(hf, FeatureType::Ridge, {});
  const auto profiles = sampleProfiles(r.graph, hf);
  const int root = r.graph.bfsOrder.front();
  for (const ChainProfile& p : profiles[static_cast<std::size_t>(root)])
  {
    ASSERT_EQ(p.across.size(), 17u);
    ASSERT_EQ(p.along.size(), 16u);
    const auto peak = std::max_element(p.across.begin(), p.across.end()) - p.across.begin();
    EXPECT_NEAR(static_cast<double>(peak), 8.0, 1.0);
    // 20 cells either side of a sigma-6 ridge: down by ~300 m on both sides (minus the tilt).
    EXPECT_GT(p.across[8] - p.across.front(), 250.0f);
    EXPECT_GT(p.across[8] - p.across.back(), 250.0f);
    for (float a : p.along)
    {
      EXPECT_GT(a, 1250.0f); // on the crest all the way to the circle
    }
  }
}
