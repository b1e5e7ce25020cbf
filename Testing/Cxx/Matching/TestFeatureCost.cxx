// Tests of Kernels/Matching/FeatureCost.cxx: the feature cost term by term, its independence of
// the height unit, and the landform samples' misfit.
#include "Core/Constants.h"
#include "Features/Ppa.h"
#include "Matching/CandidatePool.h"
#include "Matching/FeatureCost.h"
#include "Matching/LandformTerm.h"
#include "MatchingTestData.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace tsynth;
using tsynth::test::matching::colorado;
using tsynth::test::matching::crop;
using tsynth::test::matching::handPool;
using tsynth::test::matching::handPoolWithLandform;
using tsynth::test::matching::handQuery;

TEST(FeatureCost, HandMadeCandidateHasTheExpectedCost)
{
  const CandidatePool pool = handPool();
  FeatureQuery q = handQuery();
  q.noise = { 50.0f, 0.0f, 0.0f }; // half the candidate's 100 m^2 at the first level
  const MatchWeights w;
  // c_f: profiles differ by 2 m, scale 10 m -> 0.04; c_a: both arms off by 0.1 rad
  // -> (0.1 / pi)^2; c_n: 50 m^2 asked, 100 found -> ((50 - 100) / 150)^2 = 1/9,
  // the levels asked as 0 left out; c_o: 5 m -> 0.25; c_l: one sample off by
  // 20 m with weight 0.5, over 25 samples, scale^2 100 -> 0.5 * 400 / 25 / 100 = 0.08.
  const double expected =
    5.0 * 0.04 + 2.0 * std::pow(0.1 / kPi, 2) + 1.0 / 9.0 + 1.0 * 0.25 + 5.0 * 0.08;
  // Nothing asked of roughness, nothing paid for it (the scale-free term has
  // no meaning for a level asked as 0).
  EXPECT_NEAR(scoreFeatureCandidates(pool, handQuery(), w)[0], expected - 1.0 / 9.0, 1e-5);
  const std::vector<float> costs = scoreFeatureCandidates(pool, q, w);
  ASSERT_EQ(costs.size(), 1u);
  EXPECT_NEAR(costs[0], expected, 1e-5);

  MatchWeights offset = w;
  offset.verticalOffset = true; // a constant 5 m difference is no mismatch
  EXPECT_NEAR(scoreFeatureCandidates(pool, q, offset)[0], expected - 0.25, 1e-5);

  FeatureQuery branch = q;
  branch.kind = static_cast<int>(NodeKind::Branch);
  EXPECT_EQ(scoreFeatureCandidates(pool, branch, w)[0], kMismatchPenalty);
  FeatureQuery valley = q;
  valley.type = -1;
  EXPECT_EQ(scoreFeatureCandidates(pool, valley, w)[0], kMismatchPenalty); // not scored
  FeatureQuery threeArms = q;
  threeArms.arms = 3;
  EXPECT_EQ(scoreFeatureCandidates(pool, threeArms, w)[0], kMismatchPenalty);

  // Arms given in the other order align cyclically at no extra cost.
  FeatureQuery swapped = q;
  std::swap(swapped.angles[0], swapped.angles[1]);
  EXPECT_NEAR(scoreFeatureCandidates(pool, swapped, w)[0], expected, 1e-5);
}

TEST(FeatureCost, UnitsDoNotChangeTheRanking)
{
  // The same terrain in metres and scaled to feet gives the same costs.
  const Heightfield metres = crop(colorado(), 100, 100, 300, 300);
  Heightfield feet = metres;
  for (float& v : feet.z)
  {
    v = static_cast<float>(v / 0.3048);
  }
  const FeatureExtraction fm = extractFeatures(metres, FeatureType::Ridge, {});
  PoolOptions o;
  o.patchSize = 48;
  const CandidatePool pm = buildCandidatePool({ &metres }, { &fm.graph }, o);
  const CandidatePool pf = buildCandidatePool({ &feet }, { &fm.graph }, o);
  ASSERT_EQ(pm.size(), pf.size());
  ASSERT_GT(pm.size(), 100u);
  const NoiseVariance nm(metres);
  const NoiseVariance nf(feet);
  const std::size_t probe = pm.sites.size() / 2;
  const FeatureQuery qm = makeFeatureQuery(pm.sites[probe], metres, nm, &metres, nullptr, 48);
  const FeatureQuery qf = makeFeatureQuery(pf.sites[probe], feet, nf, &feet, nullptr, 48);
  const auto cm = scoreFeatureCandidates(pm, qm, {});
  const auto cf = scoreFeatureCandidates(pf, qf, {});
  for (std::size_t c = 0; c < cm.size(); ++c)
  {
    ASSERT_NEAR(cm[c], cf[c], 1e-3 * std::max(1.0f, std::abs(cm[c])));
  }
}

TEST(FeatureCost, LandformSamplesAddTheirWeightedMisfit)
{
  const CandidatePool pool = handPoolWithLandform();
  const MatchWeights w;
  FeatureQuery q = handQuery();
  FeatureQuery without = q;
  without.landformWeight.fill(0.0f);
  const float base = scoreFeatureCandidates(pool, without, w)[0];
  // Sample 3: 20 m off at weight 0.5; sample 20 (the second lane of 16): the
  // candidate 5 m below the centre, the target 10 m above, weight 1. Over 25
  // samples and the height scale^2 100: (0.5 * 400 + 1 * 225) / 25 / 100 = 0.17.
  q.landform[20] = 10.0f;
  q.landformWeight[20] = 1.0f;
  // Padding (samples 25..31) never counts: weight 0 whatever the heights.
  q.landform[27] = 500.0f;
  const float cost = scoreFeatureCandidates(pool, q, w)[0];
  EXPECT_NEAR(cost - base, w.landform * 0.17, 1e-5);
  // Twice the weight, twice the landform cost; weight 0, none.
  MatchWeights heavy = w;
  heavy.landform = 2.0 * w.landform;
  EXPECT_NEAR(scoreFeatureCandidates(pool, q, heavy)[0] - base, 2.0 * w.landform * 0.17, 1e-5);
  MatchWeights off = w;
  off.landform = 0.0;
  EXPECT_NEAR(scoreFeatureCandidates(pool, q, off)[0], base, 1e-6);
}

TEST(FeatureCost, ALandformOnlyQueryFindsItsOwnSite)
{
  // Every other term switched off: the landform samples of the low-passed
  // exemplar around a site pick that site, unturned, out of the whole pool.
  const Heightfield ex = crop(colorado(), 100, 100, 300, 300);
  const FeatureExtraction f = extractFeatures(ex, FeatureType::Ridge, {});
  PoolOptions o;
  o.patchSize = 48;
  const CandidatePool pool = buildCandidatePool({ &ex }, { &f.graph }, o);
  ASSERT_GT(pool.sites.size(), 20u);
  const Heightfield smooth = landformImage(ex, o.patchSize);
  const std::vector<float> sure(ex.size(), 1.0f);
  const NoiseVariance noise(ex);
  MatchWeights w;
  w.feature = w.angle = w.noise = w.overlap = 0.0;
  int hits = 0;
  int trials = 0;
  for (std::size_t s = 0; s < pool.sites.size(); s += pool.sites.size() / 20)
  {
    const FeatureQuery q =
      makeFeatureQuery(pool.sites[s], ex, noise, nullptr, nullptr, o.patchSize, &smooth, &sure);
    ASSERT_GT(std::count(q.landformWeight.begin(), q.landformWeight.end(), 1.0f), 20);
    const std::vector<float> costs = scoreFeatureCandidates(pool, q, w);
    const auto best = topK(costs, 1);
    ++trials;
    // The site's own unturned candidate: no misfit (up to the centre's float rounding).
    for (std::size_t c = 0; c < pool.size(); ++c)
    {
      if (pool.site[c] == static_cast<int>(s) && pool.variant[c] == 0)
      {
        EXPECT_LT(costs[c], 1e-6f) << "site " << s;
      }
    }
    hits += pool.site[best[0].index] == static_cast<int>(s) && pool.variant[best[0].index] == 0;
  }
  EXPECT_GE(hits, trials - 1) << hits << " of " << trials;
}
