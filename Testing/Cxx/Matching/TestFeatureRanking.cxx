// Tests of Kernels/Matching/FeatureRanking.cxx: the bounded ranking finds the
// candidates and costs that scoring every candidate finds, bit for bit, and
// leaves most candidates before their dearer terms.
#include "Features/Ppa.h"
#include "Matching/CandidatePool.h"
#include "Matching/FeatureCost.h"
#include "Matching/FeatureRanking.h"
#include "Matching/LandformTerm.h"
#include "Matching/NoiseVariance.h"
#include "MatchingTestData.h"

#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

using namespace tsynth;
using tsynth::test::matching::colorado;
using tsynth::test::matching::crop;

namespace
{

constexpr int kPatch = 48;

// What the synthesis ranks by: every candidate scored, the k cheapest of each
// exemplar, less those never chosen (of another type, kind or arms).
std::vector<RankedCandidate> reference(const CandidatePool& pool,
  const FeatureQuery& q,
  const MatchWeights& w,
  std::size_t k)
{
  std::vector<RankedCandidate> kept;
  for (const RankedCandidate& r : topKPerExemplar(pool, scoreFeatureCandidates(pool, q, w), k))
  {
    if (r.cost < kMismatchPenalty)
    {
      kept.push_back(r);
    }
  }
  return kept;
}

// Three exemplars (two crops of Colorado, one of them with its valleys).
struct Exemplars
{
  Heightfield a = crop(colorado(), 100, 100, 300, 300);
  Heightfield b = crop(colorado(), 330, 60, 280, 280);
  FeatureExtraction ridgesA = extractFeatures(a, FeatureType::Ridge, {});
  FeatureExtraction valleysA = extractFeatures(a, FeatureType::Valley, {});
  FeatureExtraction ridgesB = extractFeatures(b, FeatureType::Ridge, {});
  CandidatePool pool = makePool();

  CandidatePool makePool() const
  {
    PoolOptions o;
    o.patchSize = kPatch;
    return buildCandidatePool(
      { &a, &a, &b }, { &ridgesA.graph, &valleysA.graph, &ridgesB.graph }, o);
  }
};

// Queries at a target's ridge and valley sites, with the output known over
// its west half (another part of Colorado there) and the landform asked.
struct Queries
{
  Heightfield target = crop(colorado(), 60, 330, 300, 300);
  Heightfield output = crop(colorado(), 300, 320, 300, 300);
  std::vector<std::uint8_t> known;
  NoiseVariance noise{ target };
  Heightfield smooth = landformImage(target, kPatch);
  std::vector<float> sure = std::vector<float>(target.size(), 1.0f);
  std::vector<FeatureQuery> all;

  Queries()
    : known(target.size(), 0)
  {
    for (int y = 0; y < target.height; ++y)
    {
      for (int x = 0; x < target.width / 2; ++x)
      {
        known[static_cast<std::size_t>(y * target.width + x)] = 1;
      }
    }
    PoolOptions o;
    o.patchSize = kPatch;
    for (const FeatureType type : { FeatureType::Ridge, FeatureType::Valley })
    {
      const FeatureExtraction f = extractFeatures(target, type, {});
      const CandidatePool sites = buildCandidatePool({ &target }, { &f.graph }, o);
      for (std::size_t s = 0; s < sites.sites.size(); s += 3)
      {
        all.push_back(
          makeFeatureQuery(sites.sites[s], target, noise, &output, &known, kPatch, &smooth, &sure));
      }
    }
  }
};

const Exemplars& exemplars()
{
  static const Exemplars e;
  return e;
}

const Queries& queries()
{
  static const Queries q;
  return q;
}

void expectSameRanking(const std::vector<RankedCandidate>& got,
  const std::vector<RankedCandidate>& want,
  const std::string& what)
{
  ASSERT_EQ(got.size(), want.size()) << what;
  for (std::size_t i = 0; i < got.size(); ++i)
  {
    EXPECT_EQ(got[i].index, want[i].index) << what << ", rank " << i;
    EXPECT_EQ(got[i].cost, want[i].cost) << what << ", rank " << i; // the same bits
  }
}

} // namespace

TEST(FeatureRanking, FindsTheCandidatesAndCostsOfScoringEveryCandidate)
{
  const CandidatePool& pool = exemplars().pool;
  ASSERT_GT(pool.size(), 1000u);
  ASSERT_GT(queries().all.size(), 20u);
  FeatureRanker ranker(pool);
  RankingCounts total;
  std::size_t overlapping = 0;
  for (const bool offset : { true, false })
  {
    MatchWeights w;
    w.verticalOffset = offset;
    for (const std::size_t k : { std::size_t{ 1 }, std::size_t{ 3 }, std::size_t{ 8 } })
    {
      for (std::size_t i = 0; i < queries().all.size(); ++i)
      {
        const FeatureQuery& q = queries().all[i];
        overlapping +=
          std::count_if(q.weight.begin(), q.weight.end(), [](float v) { return v > 0.0f; }) > 0;
        RankingCounts counts;
        const auto got = ranker.rank(q, w, k, &counts);
        expectSameRanking(got,
          reference(pool, q, w, k),
          "query " + std::to_string(i) + ", k " + std::to_string(k) + (offset ? ", offset" : ""));
        total.shaped += counts.shaped;
        total.scored += counts.scored;
        total.beforeArms += counts.beforeArms;
      }
    }
  }
  // Some queries overlap the known half, some do not.
  EXPECT_GT(overlapping, 0u);
  EXPECT_LT(overlapping, 6 * queries().all.size());
  // The bounds do their work: most candidates are never scored in full, and
  // the profiles' moments leave some that roughness and landform kept.
  EXPECT_LT(total.scored * 4, total.shaped) << total.scored << " of " << total.shaped;
  EXPECT_GT(total.beforeArms, 0u);
}

TEST(FeatureRanking, BoundsTheArmsAnglesWithoutLosingTheCheapest)
{
  // Where the arms' angles weigh most, the bound's angle part decides which
  // candidates are left: one that rounds above the cost's, or turns the wrong
  // way round, drops the cheapest.
  const CandidatePool& pool = exemplars().pool;
  FeatureRanker ranker(pool);
  MatchWeights w;
  w.angle = 20.0;
  w.feature = 0.5;
  w.noise = w.landform = 0.1;
  std::size_t leftEarly = 0;
  std::size_t shaped = 0;
  for (const std::size_t k : { std::size_t{ 1 }, std::size_t{ 8 } })
  {
    for (std::size_t i = 0; i < queries().all.size(); ++i)
    {
      RankingCounts counts;
      expectSameRanking(ranker.rank(queries().all[i], w, k, &counts),
        reference(pool, queries().all[i], w, k),
        "query " + std::to_string(i) + ", k " + std::to_string(k));
      leftEarly += counts.beforeArms;
      shaped += counts.shaped;
    }
  }
  // Most are left before their arms are compared in full.
  EXPECT_GT(leftEarly * 2, shaped) << leftEarly << " of " << shaped;
}

TEST(FeatureRanking, DoesNotDependOnTheThreadCount)
{
  const CandidatePool& pool = exemplars().pool;
  FeatureRanker ranker(pool);
  const MatchWeights w;
  const int threads = omp_get_max_threads();
  for (std::size_t i = 0; i < queries().all.size(); i += 4)
  {
    omp_set_num_threads(1);
    const auto one = ranker.rank(queries().all[i], w, 8);
    omp_set_num_threads(3);
    const auto three = ranker.rank(queries().all[i], w, 8);
    omp_set_num_threads(threads);
    expectSameRanking(three, one, "query " + std::to_string(i));
  }
}

TEST(FeatureRanking, FindsACandidateOfZeroCostAmongItsTwins)
{
  // Queries made from the exemplar's own sites: each site's unturned candidate
  // costs (about) 0 on the profiles (the target is the exemplar), the case
  // where a bound that rounds above the true cost would drop it.
  const Exemplars& e = exemplars();
  const NoiseVariance noise(e.a);
  MatchWeights w;
  w.noise = w.overlap = w.landform = 0.0;
  FeatureRanker ranker(e.pool);
  int found = 0;
  int asked = 0;
  std::size_t unturned = 0;
  for (std::size_t c = 0; c < e.pool.size(); ++c)
  {
    if (e.pool.exemplar[c] != 0 || e.pool.variant[c] != 0 || unturned++ % 5 != 0)
    {
      continue;
    }
    const FeatureSite& site = e.pool.sites[static_cast<std::size_t>(e.pool.site[c])];
    const FeatureQuery q = makeFeatureQuery(site, e.a, noise, nullptr, nullptr, kPatch);
    const auto got = ranker.rank(q, w, 2);
    expectSameRanking(got, reference(e.pool, q, w, 2), "candidate " + std::to_string(c));
    ++asked;
    // Its own candidate, up to the centre height's float rounding.
    found += !got.empty() && got[0].cost < 1e-6f;
  }
  ASSERT_GT(asked, 5);
  EXPECT_GE(found, asked / 2) << found << " of " << asked;
}

TEST(FeatureRanking, TakesTheLandformsPaddingAsTheScoringDoes)
{
  // The landform is stored padded to kLandformStride samples. The ranker
  // leaves out the padding when every candidate holds 0 there (as the pool
  // builds it) and must then count a query's padding as against 0; it keeps
  // the padding of a pool whose candidates hold something there.
  const CandidatePool& pool = exemplars().pool;
  const float height = static_cast<float>(pool.heightScale);
  CandidatePool padded = pool;
  for (std::size_t c = 0; c < padded.size(); c += 7)
  {
    padded.landform[c * kLandformStride + kLandformSamples + 2] = 0.3f * height;
  }
  const MatchWeights w;
  std::size_t changed = 0;
  for (const CandidatePool* p : { &pool, static_cast<const CandidatePool*>(&padded) })
  {
    FeatureRanker ranker(*p);
    for (std::size_t i = 0; i < queries().all.size(); i += 2)
    {
      FeatureQuery q = queries().all[i];
      for (int k = kLandformSamples; k < kLandformStride; ++k)
      {
        q.landform[k] = 0.1f * height * static_cast<float>(k - kLandformSamples);
        q.landformWeight[k] = 0.5f;
      }
      const auto want = reference(*p, q, w, 3);
      expectSameRanking(ranker.rank(q, w, 3), want, "query " + std::to_string(i));
      const auto unpadded = reference(*p, queries().all[i], w, 3);
      changed += !want.empty() && !unpadded.empty() && want[0].cost != unpadded[0].cost;
    }
  }
  EXPECT_GT(changed, 0u); // the padding counts in the cost
}

TEST(FeatureRanking, RanksNothingForNoCandidateOrNoneAsked)
{
  FeatureRanker ranker(exemplars().pool);
  FeatureQuery q = queries().all.front();
  EXPECT_TRUE(ranker.rank(q, {}, 0).empty());
  q.arms = 0;
  q.kind = 99; // no candidate has this kind
  EXPECT_TRUE(ranker.rank(q, {}, 8).empty());
}
