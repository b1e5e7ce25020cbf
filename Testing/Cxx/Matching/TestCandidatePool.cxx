// Tests of Kernels/Matching/CandidatePool.cxx: a site matches itself first, pools merge, and
// pools are deterministic, keep clear of nodata and refuse bad input.
#include "Core/Error.h"
#include "Features/Ppa.h"
#include "Matching/CandidatePool.h"
#include "Matching/FeatureCost.h"
#include "MatchingTestData.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

using namespace tsynth;
using tsynth::test::matching::colorado;
using tsynth::test::matching::crop;

TEST(CandidatePool, ASiteMatchesItselfFirst)
{
  const Heightfield ex = crop(colorado(), 50, 50, 400, 400);
  const FeatureExtraction f = extractFeatures(ex, FeatureType::Ridge, {});
  PoolOptions o;
  o.patchSize = 64;
  const CandidatePool pool = buildCandidatePool({ &ex }, { &f.graph }, o);
  ASSERT_EQ(pool.size() % kVariantCount, 0u);
  EXPECT_EQ(pool.size(), pool.sites.size() * kVariantCount);
  const NoiseVariance noise(ex);
  std::vector<std::uint8_t> known(ex.size(), 1);
  int hits = 0;
  int trials = 0;
  for (std::size_t s = 0; s < pool.sites.size();
       s += std::max<std::size_t>(1, pool.sites.size() / 25))
  {
    const FeatureQuery q = makeFeatureQuery(pool.sites[s], ex, noise, &ex, &known, 64);
    const auto best = topK(scoreFeatureCandidates(pool, q, {}), 1);
    ASSERT_EQ(best.size(), 1u);
    ++trials;
    hits +=
      pool.site[best[0].index] == static_cast<int>(s) && pool.variant[best[0].index] == 0 ? 1 : 0;
    EXPECT_LT(best[0].cost, 1e-3f);
  }
  EXPECT_GE(hits, trials - 1) << hits << " of " << trials;
}

TEST(CandidatePool, TwoExemplarsMergeAndKeepTheirOwnTopK)
{
  const Heightfield a = crop(colorado(), 0, 0, 300, 300);
  const Heightfield b = crop(colorado(), 320, 320, 300, 300);
  const FeatureExtraction fa = extractFeatures(a, FeatureType::Ridge, {});
  const FeatureExtraction fb = extractFeatures(b, FeatureType::Ridge, {});
  PoolOptions o;
  o.patchSize = 48;
  const CandidatePool pa = buildCandidatePool({ &a }, { &fa.graph }, o, { "a" });
  const CandidatePool pb = buildCandidatePool({ &b }, { &fb.graph }, o, { "b" });
  const CandidatePool both =
    buildCandidatePool({ &a, &b }, { &fa.graph, &fb.graph }, o, { "a", "b" });
  CandidatePool merged = pa;
  mergePools(merged, pb);
  ASSERT_EQ(both.size(), pa.size() + pb.size());
  ASSERT_EQ(merged.size(), both.size());
  EXPECT_EQ(merged.descriptor, both.descriptor);
  EXPECT_EQ(merged.exemplar, both.exemplar);
  ASSERT_EQ(both.exemplars.size(), 2u);
  EXPECT_EQ(both.exemplars[1].firstCandidate, pa.size());

  const NoiseVariance noise(a);
  const FeatureQuery q = makeFeatureQuery(pa.sites[0], a, noise, nullptr, nullptr, 48);
  const auto costs = scoreFeatureCandidates(both, q, {});
  const auto perExemplar = topKPerExemplar(both, costs, 3);
  ASSERT_EQ(perExemplar.size(), 6u);
  int fromB = 0;
  for (const auto& r : perExemplar)
  {
    fromB += both.exemplar[r.index] == 1 ? 1 : 0;
  }
  EXPECT_EQ(fromB, 3);
  EXPECT_TRUE(std::is_sorted(perExemplar.begin(),
    perExemplar.end(),
    [](const RankedCandidate& x, const RankedCandidate& y) { return x.cost < y.cost; }));
}

TEST(CandidatePool, DeterministicAndNodataExcluded)
{
  Heightfield ex = crop(colorado(), 100, 100, 300, 300);
  ex.valid.assign(ex.size(), 1);
  for (int j = 140; j < 160; ++j)
  {
    for (int i = 140; i < 160; ++i)
    {
      ex.valid[ex.index(i, j)] = 0;
    }
  }
  normaliseMask(ex);
  const FeatureExtraction f = extractFeatures(ex, FeatureType::Ridge, {});
  PoolOptions o;
  o.patchSize = 40;
  const CandidatePool p1 = buildCandidatePool({ &ex }, { &f.graph }, o);
  const CandidatePool p2 = buildCandidatePool({ &ex }, { &f.graph }, o);
  EXPECT_EQ(p1.descriptor, p2.descriptor);
  EXPECT_EQ(p1.along, p2.along);
  const double reach = std::ceil(20.0 * std::sqrt(2.0)) + 1;
  for (std::size_t c = 0; c < p1.size(); ++c)
  {
    const bool clearX = p1.centreX[c] + reach < 140 || p1.centreX[c] - reach >= 160;
    const bool clearY = p1.centreY[c] + reach < 140 || p1.centreY[c] - reach >= 160;
    ASSERT_TRUE(clearX || clearY) << "candidate " << c << " overlaps the nodata hole";
    ASSERT_FALSE(std::isnan(p1.descriptor[c * kDescriptorSize]));
  }
}

TEST(CandidatePool, BadInput)
{
  const Heightfield small = crop(colorado(), 0, 0, 50, 50);
  const FeatureGraph none;
  PoolOptions o;
  o.patchSize = 80;
  EXPECT_THROW(buildCandidatePool({ &small }, { &none }, o), Error);
  // An exemplar with no features of the type: an empty pool and a warning.
  Heightfield flat(200, 200, 10.0f);
  const CandidatePool p = buildCandidatePool({ &flat }, { &none }, o);
  EXPECT_EQ(p.size(), 0u);
  ASSERT_EQ(p.warnings.size(), 1u);
  EXPECT_NE(p.warnings[0].find("non-feature"), std::string::npos);
}
