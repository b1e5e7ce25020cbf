#include "Core/Error.h"
#include "Core/HeightfieldIO.h"
#include "Core/Smoothing.h"
#include "Features/Ppa.h"
#include "Matching/CandidatePool.h"
#include "Matching/DenseSearch.h"
#include "Matching/FeatureCost.h"
#include "Matching/OpenClMatcher.h"
#include "Matching/PatchMatcher.h"
#include "Matching/SiteMatch.h"
#include "TestData.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace tsynth;

namespace
{

constexpr double kPi = 3.14159265358979323846;

Heightfield crop(const Heightfield& hf, int x0, int y0, int w, int h)
{
  Heightfield out(w, h);
  out.cellX = hf.cellX;
  out.cellY = hf.cellY;
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      out.at(i, j) = hf.at(x0 + i, y0 + j);
    }
  }
  return out;
}

const Heightfield& colorado()
{
  static const Heightfield hf =
    readHeightfield((test::bundledData() / "dems" / "colorado.png").string());
  return hf;
}

// A one-candidate pool filled by hand, to check the cost formula term by term.
CandidatePool handPool()
{
  CandidatePool p;
  p.patchSize = 80;
  p.heightScale = 10.0;
  p.exemplars.push_back({ "hand", 100, 100, 0, 1 });
  p.exemplar = { 0 };
  p.site = { 0 };
  p.variant = { 0 };
  p.kind = { static_cast<int>(NodeKind::Path) };
  p.type = { 1 };
  p.arms = { 2 };
  p.centreX = { 50 };
  p.centreY = { 50 };
  p.angles = { 0.0f, static_cast<float>(kPi), 0.0f, 0.0f };
  p.along.assign(kMaxArms * kAlongSamples, 0.0f);
  p.across.assign(kMaxArms * kAcrossSamples, 0.0f);
  p.noise = { 100.0f, 0.0f, 0.0f };
  p.descriptor.assign(kDescriptorSize, 1000.0f);
  p.landform.assign(kLandformStride, 0.0f);
  p.landform[3] = 30.0f; // one landform sample 30 m above the centre
  return p;
}

// The hand pool with a second landform sample, in the second lane of 16.
CandidatePool handPoolWithLandform()
{
  CandidatePool p = handPool();
  p.landform[20] = -5.0f; // 5 m below the centre
  return p;
}

FeatureQuery handQuery()
{
  FeatureQuery q;
  q.type = 1;
  q.kind = static_cast<int>(NodeKind::Path);
  q.arms = 2;
  q.angles = { 0.1f, static_cast<float>(kPi) + 0.1f, 0.0f, 0.0f };
  q.along.fill(0.0f);
  q.across.fill(0.0f);
  for (int k = 0; k < 2 * kAlongSamples; ++k)
  {
    q.along[static_cast<std::size_t>(k)] = 2.0f;
  }
  for (int k = 0; k < 2 * kAcrossSamples; ++k)
  {
    q.across[static_cast<std::size_t>(k)] = 2.0f;
  }
  q.noise = { 0.0f, 0.0f, 0.0f };
  q.descriptor.fill(1005.0f);
  q.landform[3] = 10.0f; // the target has it 10 m above
  q.landformWeight.fill(0.0f);
  q.landformWeight[3] = 0.5f;
  q.weight.fill(1.0f);
  return q;
}

} // namespace

TEST(Orientation, QuarterTurnsAndMirrorsAreExactCopies)
{
  Heightfield ex(5, 3);
  for (int j = 0; j < 3; ++j)
  {
    for (int i = 0; i < 5; ++i)
    {
      ex.at(i, j) = static_cast<float>(10 * j + i);
    }
  }
  for (int k : { 0, 2, 4, 6, 8, 9 })
  {
    double cu = 0.0;
    double cv = 0.0;
    const Heightfield out = orientExemplar(ex, variant(k), &cu, &cv);
    EXPECT_FALSE(out.hasMask()) << "variant " << k;
    // Exemplar offset (a, b) from its centre appears rotated by k * 45 degrees
    // (or mirrored) around the centre of the placed image.
    for (int j = 0; j < 3; ++j)
    {
      for (int i = 0; i < 5; ++i)
      {
        const double a = i - 2.0;
        const double b = j - 1.0;
        double pu = a;
        double pv = b;
        if (k < 8)
        {
          const double t = k * kPi / 4;
          pu = std::round(std::cos(t) * a - std::sin(t) * b);
          pv = std::round(std::sin(t) * a + std::cos(t) * b);
        }
        else if (k == 8)
        {
          pu = -a;
        }
        else
        {
          pv = -b;
        }
        ASSERT_EQ(out.at(static_cast<int>(cu + pu), static_cast<int>(cv + pv)), ex.at(i, j))
          << "variant " << k << " cell " << i << "," << j;
      }
    }
  }
  EXPECT_EQ(orientExemplar(ex, variant(2)).width, 3);
  EXPECT_EQ(orientExemplar(ex, variant(2)).height, 5);
  const Heightfield diagonal = orientExemplar(ex, variant(1));
  EXPECT_TRUE(diagonal.hasMask()); // corners outside the rotated exemplar
}

TEST(Orientation, FeatureAnglesFollowTheVariant)
{
  EXPECT_NEAR(variant(2).placedAngle(0.0), kPi / 2, 1e-12);
  EXPECT_NEAR(variant(1).placedAngle(0.0), kPi / 4, 1e-12);
  EXPECT_NEAR(std::abs(variant(8).placedAngle(0.0)), kPi, 1e-12);
  EXPECT_NEAR(variant(9).placedAngle(kPi / 2), -kPi / 2, 1e-12);
}

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
  EXPECT_GE(scoreFeatureCandidates(pool, branch, w)[0], kMismatchPenalty);
  FeatureQuery valley = q;
  valley.type = -1;
  EXPECT_NEAR(scoreFeatureCandidates(pool, valley, w)[0], kMismatchPenalty + 0.25, 1.0);

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

TEST(DenseSearch, FindsAWindowCutFromTheExemplar)
{
  const Heightfield ex = crop(colorado(), 200, 200, 200, 200);
  DenseOptions o;
  o.patchSize = 32;
  const DenseMatcher matcher({ &ex }, o);
  // The window at (57, 83), half known (an L-shaped overlap, as during filling).
  DenseQuery q;
  q.heights.resize(32 * 32);
  q.known.resize(32 * 32);
  for (int j = 0; j < 32; ++j)
  {
    for (int i = 0; i < 32; ++i)
    {
      q.heights[static_cast<std::size_t>(j * 32 + i)] = ex.at(57 + i, 83 + j);
      q.known[static_cast<std::size_t>(j * 32 + i)] = (i < 10 || j < 10) ? 1 : 0;
    }
  }
  const auto best = matcher.search(q, 3);
  ASSERT_FALSE(best.empty());
  EXPECT_EQ(best[0].variant, 0);
  EXPECT_EQ(best[0].x, 57);
  EXPECT_EQ(best[0].y, 83);
  EXPECT_NEAR(best[0].overlap, 0.0f, 1e-9f);
  EXPECT_NEAR(best[0].centreX, 57 + 15.5, 1e-9);
  EXPECT_NEAR(best[0].centreY, 83 + 15.5, 1e-9);
}

TEST(DenseSearch, RoughnessMisfitIsScaleFreeAndSkipsLevelsNotAsked)
{
  EXPECT_EQ(roughnessMisfit({ 100.0f, 200.0f, 800.0f }, { 100.0f, 200.0f, 800.0f }), 0.0);
  // Twice or half the variance asked: (1/3)^2 per level, at any scale.
  EXPECT_NEAR(roughnessMisfit({ 100.0f, 0.0f, 0.0f }, { 200.0f, 5.0f, 9.0f }), 1.0 / 9.0, 1e-12);
  EXPECT_NEAR(roughnessMisfit({ 1e6f, 0.0f, 0.0f }, { 5e5f, 0.0f, 0.0f }), 1.0 / 9.0, 1e-12);
  // A flat window against a rough one asked for: 1 per level.
  EXPECT_NEAR(roughnessMisfit({ 50.0f, 60.0f, 70.0f }, { 0.0f, 0.0f, 0.0f }), 3.0, 1e-12);
  EXPECT_EQ(roughnessMisfit({ 0.0f, 0.0f, 0.0f }, { 50.0f, 60.0f, 70.0f }), 0.0);
}

TEST(DenseSearch, TheRoughnessTermStopsTheFillPreferringSmoothLand)
{
  // Colorado with its west half smoothed (sigma 6 cells): the same heights,
  // far less roughness. The query knows a level strip at the exemplar's mean,
  // which smooth windows stray least from; it asks for the east's roughness.
  Heightfield ex = crop(colorado(), 200, 200, 240, 160);
  const Heightfield smooth = smoothLarge(ex, 6.0);
  double sum = 0.0;
  for (int j = 0; j < ex.height; ++j)
  {
    for (int i = 0; i < ex.width; ++i)
    {
      sum += ex.at(i, j);
      if (i < ex.width / 2)
      {
        ex.at(i, j) = smooth.at(i, j);
      }
    }
  }
  const float mean = static_cast<float>(sum / static_cast<double>(ex.size()));
  constexpr int P = 32;
  DenseQuery q;
  q.heights.assign(P * P, mean);
  q.known.assign(P * P, 0);
  for (int j = 0; j < P; ++j)
  {
    for (int i = 0; i < 6; ++i)
    {
      q.known[static_cast<std::size_t>(j * P + i)] = 1;
    }
  }
  DenseOptions o;
  o.patchSize = P;
  o.variants.fill(false);
  o.variants[0] = true;
  // The term ranks the refined candidates: let it see the best 32 offsets.
  o.refinePerVariant = 32;
  o.refineTotal = 32;
  const DenseMatcher matcher({ &ex }, o);
  const NoiseVariance noise(ex);
  q.noise = noise.window(0.75 * ex.width, 0.5 * ex.height, P); // the rough half's
  o.noiseWeight = 0.0;
  const DenseMatcher blind({ &ex }, o);
  const auto without = blind.search(q, 1);
  const auto with = matcher.search(q, 1);
  ASSERT_FALSE(without.empty());
  ASSERT_FALSE(with.empty());
  // Without the term the known strip is matched in the smooth half; with it
  // the whole window lies in the rough half (variant 0: x is the exemplar's).
  EXPECT_LE(without[0].x + 6, ex.width / 2);
  EXPECT_GE(with[0].x, ex.width / 2);
  EXPECT_GT(with[0].overlap, without[0].overlap); // a worse overlap, taken for its roughness
}

TEST(DenseSearch, CoarseToFineFindsTheExhaustiveWinner)
{
  // Queries from another part of the DEM, with random known masks: the fast
  // search must return the brute-force best on at least 95% of them.
  const Heightfield ex = crop(colorado(), 0, 0, 180, 180);
  const Heightfield source = crop(colorado(), 300, 300, 300, 300);
  DenseOptions o;
  o.patchSize = 32;
  const DenseMatcher matcher({ &ex }, o);
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> pos(0, 300 - 32);
  std::uniform_int_distribution<int> band(6, 20);
  int same = 0;
  const int queries = 40;
  for (int n = 0; n < queries; ++n)
  {
    const int x0 = pos(rng);
    const int y0 = pos(rng);
    const int b = band(rng);
    DenseQuery q;
    q.heights.resize(32 * 32);
    q.known.resize(32 * 32);
    for (int j = 0; j < 32; ++j)
    {
      for (int i = 0; i < 32; ++i)
      {
        q.heights[static_cast<std::size_t>(j * 32 + i)] = source.at(x0 + i, y0 + j);
        q.known[static_cast<std::size_t>(j * 32 + i)] =
          (n % 2 == 0 ? (i < b || j < b) : (j >= 32 - b)) ? 1 : 0;
      }
    }
    const auto fast = matcher.search(q, 1);
    const auto exact = matcher.bruteForce(q, 1);
    ASSERT_EQ(fast.size(), 1u);
    ASSERT_EQ(exact.size(), 1u);
    EXPECT_GE(fast[0].cost, exact[0].cost * (1 - 1e-5f)); // never better than exhaustive
    same +=
      (fast[0].variant == exact[0].variant && fast[0].x == exact[0].x && fast[0].y == exact[0].y)
      ? 1
      : 0;
  }
  EXPECT_GE(same, (queries * 95 + 99) / 100) << same << " of " << queries;
}

// Offsets of the `count` smallest finite costs, by (cost, index).
std::vector<std::size_t> head(const std::vector<float>& costs, std::size_t count)
{
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < costs.size(); ++i)
  {
    if (std::isfinite(costs[i]))
    {
      order.push_back(i);
    }
  }
  std::sort(order.begin(),
    order.end(),
    [&](std::size_t a, std::size_t b)
    { return costs[a] < costs[b] || (costs[a] == costs[b] && a < b); });
  order.resize(std::min(order.size(), count));
  return order;
}

// A 32 x 32 query cut from Colorado at (x0, y0), raised by `lift`, with the
// cells `known(i, j)` says known (called row by row).
template<typename Known>
DenseQuery coloradoQuery(int x0, int y0, float lift, Known known)
{
  DenseQuery q;
  q.heights.resize(32 * 32);
  q.known.resize(32 * 32);
  for (int j = 0; j < 32; ++j)
  {
    for (int i = 0; i < 32; ++i)
    {
      const std::size_t k = static_cast<std::size_t>(j * 32 + i);
      q.heights[k] = colorado().at(x0 + i, y0 + j) + lift;
      q.known[k] = known(i, j) ? 1 : 0;
    }
  }
  return q;
}

// Landform samples of the same window where it continues (as the synthesis
// asks for them), each of weight `weight(sx, sy)`.
template<typename Weight>
void addLandformSamples(DenseQuery& q, int x0, int y0, float lift, int coarseFactor, Weight weight)
{
  for (int sy = 0; sy < kLandformSide; ++sy)
  {
    for (int sx = 0; sx < kLandformSide; ++sx)
    {
      const std::size_t k = static_cast<std::size_t>(sy * kLandformSide + sx);
      q.landform.heights[k] = colorado().at(x0 + landformCell(sx, 32, coarseFactor),
                                y0 + landformCell(sy, 32, coarseFactor)) +
        lift;
      q.landform.weights[k] = weight(sx, sy);
    }
  }
}

TEST(DenseSearch, PrunedCoarsePassKeepsTheExactHeadOfEveryVariant)
{
  // Three exemplars, queries with L-shaped known parts and one with scattered
  // known cells (blocks of unequal weight, which the bound must leave out).
  const Heightfield a = crop(colorado(), 0, 0, 200, 200);
  const Heightfield b = crop(colorado(), 220, 0, 180, 240);
  const Heightfield c = crop(colorado(), 0, 260, 260, 180);
  DenseOptions o;
  o.patchSize = 32;
  const DenseMatcher matcher({ &a, &b, &c }, o);
  auto cpu = [&](
               const CoarseTerms& t, CoarseImage i, const std::vector<std::vector<std::uint8_t>>* r)
  { return matcher.coarseSsd(t, i, r); };
  std::mt19937 rng(5);
  std::size_t valid = 0;
  std::size_t scored = 0;
  for (int n = 0; n < 6; ++n)
  {
    DenseQuery q = coloradoQuery(450 + 20 * n,
      420,
      15.0f,
      [&](int i, int j) { return n == 5 ? rng() % 3 == 0 : (i < 8 + 3 * n || j < 10); });
    if (n % 2 == 1)
    {
      // Landform samples, some of them unsure.
      addLandformSamples(q,
        450 + 20 * n,
        420,
        15.0f,
        o.coarseFactor,
        [](int sx, int sy) { return static_cast<float>((sx + sy) % 3) * 0.5f; });
    }
    const CoarseQuery cq = matcher.coarseQuery(q);
    const auto full = matcher.coarseCosts(cq);
    const auto boundCosts = matcher.coarseSsd(cq.bound, CoarseImage::Pairs);
    const auto pruned = matcher.prunedCoarseCosts(cq, cpu);
    ASSERT_EQ(full.size(), pruned.size());
    for (std::size_t v = 0; v < full.size(); ++v)
    {
      for (std::size_t k = 0; k < full[v].size(); ++k)
      {
        if (std::isfinite(full[v][k]))
        {
          ++valid;
          const float bound = boundCosts[v][k];
          ASSERT_LE(bound, full[v][k] * (1 + 1e-5f) + 1e-6f) << "the bound must be a bound";
        }
        if (std::isfinite(pruned[v][k]))
        {
          ++scored;
          ASSERT_EQ(pruned[v][k], full[v][k]) << "scored offsets keep their exact cost";
        }
      }
      ASSERT_EQ(head(pruned[v], matcher.headSize()), head(full[v], matcher.headSize()))
        << "query " << n << ", oriented exemplar " << v;
    }
    const auto fast = matcher.refine(q, pruned, 8);
    const auto exact = matcher.refine(q, full, 8);
    ASSERT_EQ(fast.size(), exact.size());
    for (std::size_t r = 0; r < fast.size(); ++r)
    {
      EXPECT_EQ(fast[r].cost, exact[r].cost);
      EXPECT_EQ(fast[r].x, exact[r].x);
      EXPECT_EQ(fast[r].y, exact[r].y);
    }
  }
  // The point of it: most offsets never get the full sum.
  EXPECT_LT(scored, valid / 2) << scored << " of " << valid;
}

TEST(DenseSearch, PruningAcrossExemplarsKeepsWhatRefineReturns)
{
  // Five exemplars (40 oriented ones); queries with an L, a band or scattered
  // cells known, with and without landform samples; refine() asked for
  // several k and exemplar subsets (as regions ask).
  std::vector<Heightfield> crops;
  for (int e = 0; e < 5; ++e)
  {
    crops.push_back(crop(colorado(), 60 * e, 40 * e, 300 - 10 * e, 260));
  }
  std::vector<const Heightfield*> exemplars;
  for (const Heightfield& c : crops)
  {
    exemplars.push_back(&c);
  }
  DenseOptions o;
  o.patchSize = 32;
  const DenseMatcher matcher(exemplars, o);
  auto cpu = [&](
               const CoarseTerms& t, CoarseImage i, const std::vector<std::vector<std::uint8_t>>* r)
  { return matcher.coarseSsd(t, i, r); };
  auto scored = [](const std::vector<std::vector<float>>& costs)
  {
    std::size_t n = 0;
    for (const std::vector<float>& c : costs)
    {
      n += static_cast<std::size_t>(
        std::count_if(c.begin(), c.end(), [](float v) { return std::isfinite(v); }));
    }
    return n;
  };
  const std::vector<int> someExemplars = { 1, 3 };
  std::mt19937 rng(11);
  std::size_t acrossScored = 0;
  std::size_t eachScored = 0;
  std::size_t valid = 0;
  for (int n = 0; n < 8; ++n)
  {
    const float lift = 7.0f * static_cast<float>(n);
    DenseQuery q = coloradoQuery(400 + 17 * n,
      380 + 9 * n,
      lift,
      [&](int i, int j)
      { return n % 3 == 0 ? i < 16 : (n % 3 == 1 ? (i < 8 || j < 16) : rng() % 2 == 0); });
    if (n % 2 == 1)
    {
      addLandformSamples(q,
        400 + 17 * n,
        380 + 9 * n,
        lift,
        o.coarseFactor,
        [](int sx, int sy)
        { return 0.5f + static_cast<float>((sy * kLandformSide + sx) % 2) * 0.5f; });
    }
    const CoarseQuery cq = matcher.coarseQuery(q);
    // Scattered cells leave no 4 x 4 blocks of equal weight: no quad bound.
    ASSERT_EQ(cq.quadBound.empty(), n % 3 == 2) << "query " << n;
    const auto full = matcher.coarseCosts(cq);
    const auto pairs = matcher.coarseSsd(cq.bound, CoarseImage::Pairs);
    const auto quads = matcher.coarseSsd(cq.quadBound, CoarseImage::Quads);
    for (std::size_t v = 0; v < full.size(); ++v)
    {
      for (std::size_t k = 0; k < full[v].size(); ++k)
      {
        if (std::isfinite(full[v][k]))
        {
          ASSERT_LE(quads[v][k], pairs[v][k] * (1 + 1e-5f) + 1e-6f) << "quads bound the pairs";
          ASSERT_LE(pairs[v][k], full[v][k] * (1 + 1e-5f) + 1e-6f) << "pairs bound the blocks";
        }
      }
    }
    const auto each = matcher.prunedCoarseCosts(cq, cpu);
    for (std::size_t k : { 1u, 4u, 40u })
    {
      for (const std::vector<int>* only :
        { static_cast<const std::vector<int>*>(nullptr), &someExemplars })
      {
        const DenseMatcher::RefineRequest request{ k, only };
        const auto across = matcher.prunedCoarseCosts(cq, cpu, &request);
        const auto fast = matcher.refine(q, across, k, only);
        const auto exact = matcher.refine(q, full, k, only);
        ASSERT_EQ(fast.size(), exact.size()) << "query " << n << ", k " << k;
        ASSERT_FALSE(exact.empty());
        for (std::size_t r = 0; r < fast.size(); ++r)
        {
          EXPECT_EQ(fast[r].cost, exact[r].cost) << "query " << n << ", k " << k << ", match " << r;
          EXPECT_EQ(fast[r].exemplar, exact[r].exemplar);
          EXPECT_EQ(fast[r].variant, exact[r].variant);
          EXPECT_EQ(fast[r].x, exact[r].x);
          EXPECT_EQ(fast[r].y, exact[r].y);
        }
        if (only == nullptr && k == 4)
        {
          acrossScored += scored(across);
          eachScored += scored(each);
          valid += scored(full);
        }
      }
    }
  }
  // The point of it: with many exemplars, most of them have nothing good
  // enough to score in full, where pruning each on its own keeps its head.
  EXPECT_LT(acrossScored * 4, eachScored * 3)
    << acrossScored << " against " << eachScored << " of " << valid;
  EXPECT_LT(eachScored, valid);
}

namespace
{

// A landform-only query (nothing known yet) for the window at (x0, y0) of the
// unturned exemplar: its own low-passed heights at the landform samples.
DenseQuery landformQuery(const Heightfield& smooth, const DenseOptions& o, int x0, int y0)
{
  const int P = o.patchSize;
  DenseQuery q;
  q.heights.assign(static_cast<std::size_t>(P * P), 0.0f);
  q.known.assign(static_cast<std::size_t>(P * P), 0);
  for (int b = 0; b < kLandformSide; ++b)
  {
    for (int a = 0; a < kLandformSide; ++a)
    {
      const std::size_t k = static_cast<std::size_t>(b * kLandformSide + a);
      q.landform.heights[k] =
        smooth.at(x0 + landformCell(a, P, o.coarseFactor), y0 + landformCell(b, P, o.coarseFactor));
      q.landform.weights[k] = 1.0f;
    }
  }
  return q;
}

} // namespace

TEST(DenseSearch, ALandformOnlyQueryFindsItsWindow)
{
  const Heightfield ex = crop(colorado(), 200, 200, 200, 200);
  DenseOptions o;
  o.patchSize = 32;
  o.noiseWeight = 0.0; // the query says nothing of noise: only the landform decides
  const DenseMatcher matcher({ &ex }, o);
  const Heightfield smooth = landformImage(ex, o.patchSize);
  for (const auto& [x0, y0] : { std::pair{ 57, 83 }, std::pair{ 120, 16 }, std::pair{ 8, 150 } })
  {
    const DenseQuery q = landformQuery(smooth, o, x0, y0);
    const auto fast = matcher.search(q, 3);
    const auto exact = matcher.bruteForce(q, 3);
    ASSERT_FALSE(fast.empty());
    ASSERT_FALSE(exact.empty());
    for (const DenseMatch& m : { fast[0], exact[0] })
    {
      // The window itself, or one the landform cannot tell from it.
      EXPECT_EQ(m.landform, 0.0f) << x0 << ", " << y0;
      EXPECT_EQ(m.landformRms, 0.0f);
      EXPECT_EQ(m.cost, 0.0f);
      EXPECT_EQ(m.variant, 0);
      EXPECT_EQ(m.x, x0);
      EXPECT_EQ(m.y, y0);
    }
    // Elsewhere the landform misfit is a real cost: metres of misfit, weighted
    // as landformWeight / 25 samples / heightScale^2.
    ASSERT_GE(exact.size(), 2u);
    EXPECT_GT(exact[1].landformRms, 0.0f);
    EXPECT_NEAR(exact[1].cost,
      o.landformWeight * exact[1].landformRms * exact[1].landformRms /
        (matcher.heightScale() * matcher.heightScale()),
      1e-4 * exact[1].cost);
  }
}

TEST(DenseSearch, PrunedCoarsePassKeepsTheHeadWithLandformQueries)
{
  // Landform samples from the low-passed target (as the synthesis asks for
  // them), with nothing, an L or most of the window known, and with the
  // landform at full and at partial confidence.
  const Heightfield a = crop(colorado(), 0, 0, 200, 200);
  const Heightfield b = crop(colorado(), 220, 40, 180, 220);
  DenseOptions o;
  o.patchSize = 32;
  const DenseMatcher matcher({ &a, &b }, o);
  const Heightfield target = crop(colorado(), 380, 380, 200, 200);
  const Heightfield smoothTarget = landformImage(target, o.patchSize);
  auto cpu = [&](
               const CoarseTerms& t, CoarseImage i, const std::vector<std::vector<std::uint8_t>>* r)
  { return matcher.coarseSsd(t, i, r); };
  for (int n = 0; n < 6; ++n)
  {
    const int x0 = 10 + 29 * n;
    const int y0 = 150 - 23 * n;
    DenseQuery q = landformQuery(smoothTarget, o, x0, y0);
    const int band = n / 2 == 0 ? 0 : (n / 2 == 1 ? 8 : 24);
    for (int j = 0; j < 32; ++j)
    {
      for (int i = 0; i < 32; ++i)
      {
        const std::size_t k = static_cast<std::size_t>(j * 32 + i);
        q.heights[k] = target.at(x0 + i, y0 + j);
        q.known[k] = (i < band || j < band) ? 1 : 0;
      }
    }
    if (n % 2 == 1)
    {
      for (std::size_t k = 0; k < q.landform.weights.size(); ++k)
      {
        q.landform.weights[k] = static_cast<float>(k % 4) / 3.0f;
      }
    }
    const CoarseQuery cq = matcher.coarseQuery(q);
    ASSERT_FALSE(cq.landform.empty());
    const auto full = matcher.coarseCosts(cq);
    const auto pruned = matcher.prunedCoarseCosts(cq, cpu);
    // Without the landform the head would be another: the samples matter.
    DenseQuery withoutLandform = q;
    withoutLandform.landform.weights.fill(0.0f);
    const auto overlapOnly = matcher.coarseCosts(matcher.coarseQuery(withoutLandform));
    bool differs = false;
    for (std::size_t v = 0; v < full.size(); ++v)
    {
      for (std::size_t k = 0; k < full[v].size(); ++k)
      {
        if (std::isfinite(pruned[v][k]))
        {
          ASSERT_EQ(pruned[v][k], full[v][k])
            << "query " << n << ": scored offsets keep their cost";
        }
      }
      const auto head = [&](const std::vector<float>& c) { return ::head(c, matcher.headSize()); };
      ASSERT_EQ(head(pruned[v]), head(full[v])) << "query " << n << ", oriented exemplar " << v;
      differs = differs || (band > 0 && head(overlapOnly[v]) != head(full[v]));
    }
    if (band > 0)
    {
      EXPECT_TRUE(differs) << "query " << n;
    }
    const auto fast = matcher.refine(q, pruned, 4);
    const auto exact = matcher.refine(q, full, 4);
    ASSERT_EQ(fast.size(), exact.size());
    for (std::size_t r = 0; r < fast.size(); ++r)
    {
      EXPECT_EQ(fast[r].cost, exact[r].cost);
      EXPECT_EQ(fast[r].landform, exact[r].landform);
    }
  }
}

TEST(DenseSearch, BadInput)
{
  const Heightfield small = crop(colorado(), 0, 0, 40, 40);
  DenseOptions o;
  o.patchSize = 64;
  EXPECT_THROW(DenseMatcher({ &small }, o), Error);
  o.patchSize = 30; // not a multiple of the coarse factor 4
  const Heightfield ex = crop(colorado(), 0, 0, 100, 100);
  EXPECT_THROW(DenseMatcher({ &ex }, o), Error);
}

// OpenCL (PoCL here) against the CPU reference --------------------------------------------

TEST(OpenCL, FeatureScoresEqualTheCpuReference)
{
  std::shared_ptr<OpenClDevice> device;
  ASSERT_NO_THROW(device = OpenClDevice::create()) << "this machine has PoCL: OpenCL must work";
  const Heightfield ex = crop(colorado(), 40, 40, 500, 500);
  const FeatureExtraction f = extractFeatures(ex, FeatureType::Ridge, {});
  PoolOptions o;
  o.patchSize = 64;
  const CandidatePool pool = buildCandidatePool({ &ex }, { &f.graph }, o);
  ASSERT_GT(pool.size(), 1000u);
  OpenClFeatureScorer scorer(device, pool);
  const NoiseVariance noise(ex);
  std::vector<std::uint8_t> known(ex.size(), 0);
  for (std::size_t k = 0; k < known.size(); k += 3)
  {
    known[k] = 1;
  }
  for (std::size_t s = 0; s < pool.sites.size(); s += pool.sites.size() / 7)
  {
    for (bool offset : { false, true })
    {
      MatchWeights w;
      w.verticalOffset = offset;
      const FeatureQuery q = makeFeatureQuery(pool.sites[s], ex, noise, &ex, &known, 64);
      const auto cpu = scoreFeatureCandidates(pool, q, w);
      const auto gpu = scorer.score(q, w);
      ASSERT_EQ(cpu.size(), gpu.size());
      for (std::size_t c = 0; c < cpu.size(); ++c)
      {
        ASSERT_NEAR(gpu[c], cpu[c], 1e-4 * std::max(1.0f, std::abs(cpu[c]))) << "candidate " << c;
      }
      const auto a = topK(cpu, 8);
      const auto b = topK(gpu, 8);
      for (std::size_t r = 0; r < a.size(); ++r)
      {
        EXPECT_EQ(a[r].index, b[r].index) << "rank " << r;
      }
    }
  }
}

TEST(OpenCL, FeatureScoresWithLandformQueriesEqualTheCpuReference)
{
  std::shared_ptr<OpenClDevice> device;
  ASSERT_NO_THROW(device = OpenClDevice::create()) << "this machine has PoCL: OpenCL must work";
  const Heightfield ex = crop(colorado(), 100, 100, 300, 300);
  const FeatureExtraction f = extractFeatures(ex, FeatureType::Ridge, {});
  PoolOptions o;
  o.patchSize = 48;
  const CandidatePool pool = buildCandidatePool({ &ex }, { &f.graph }, o);
  ASSERT_GT(pool.size(), 500u);
  OpenClFeatureScorer scorer(device, pool);
  // The target: another part of the DEM, low-passed, with a confidence that
  // falls from 1 in the west to 0 in the east, and the north half known.
  const Heightfield target = crop(colorado(), 320, 300, 300, 300);
  const Heightfield lowTarget = landformImage(target, o.patchSize);
  std::vector<float> confidence(target.size());
  std::vector<std::uint8_t> known(target.size());
  for (int j = 0; j < target.height; ++j)
  {
    for (int i = 0; i < target.width; ++i)
    {
      confidence[target.index(i, j)] = 1.0f - static_cast<float>(i) / (target.width - 1);
      known[target.index(i, j)] = j >= target.height / 2 ? 1 : 0;
    }
  }
  const NoiseVariance noise(target);
  int withLandform = 0;
  int queries = 0;
  for (std::size_t s = 0; s < pool.sites.size(); s += pool.sites.size() / 9)
  {
    ++queries;
    const FeatureQuery q = makeFeatureQuery(
      pool.sites[s], target, noise, &target, &known, o.patchSize, &lowTarget, &confidence);
    withLandform += std::any_of(
      q.landformWeight.begin(), q.landformWeight.end(), [](float w) { return w > 0.0f; });
    const auto cpu = scoreFeatureCandidates(pool, q, {});
    const auto gpu = scorer.score(q, {});
    ASSERT_EQ(cpu.size(), gpu.size());
    for (std::size_t c = 0; c < cpu.size(); ++c)
    {
      ASSERT_NEAR(gpu[c], cpu[c], 1e-4 * std::max(1.0f, std::abs(cpu[c]))) << "candidate " << c;
    }
    const auto a = topK(cpu, 8);
    const auto b = topK(gpu, 8);
    for (std::size_t r = 0; r < a.size(); ++r)
    {
      EXPECT_EQ(a[r].index, b[r].index) << "rank " << r;
    }
  }
  EXPECT_GE(2 * withLandform, queries) << "half the queries at least carry landform samples";
  // The hand-made candidate too, both lanes of landform samples.
  const CandidatePool hand = handPoolWithLandform();
  FeatureQuery q = handQuery();
  q.landform[20] = 10.0f;
  q.landformWeight[20] = 1.0f;
  OpenClFeatureScorer handScorer(device, hand);
  EXPECT_NEAR(handScorer.score(q, {})[0], scoreFeatureCandidates(hand, q, {})[0], 1e-5);
}

TEST(OpenCL, DenseCoarseCostsEqualTheCpuReference)
{
  std::shared_ptr<OpenClDevice> device;
  ASSERT_NO_THROW(device = OpenClDevice::create());
  const Heightfield ex = crop(colorado(), 0, 0, 256, 256);
  const Heightfield source = crop(colorado(), 300, 300, 200, 200);
  DenseOptions o;
  o.patchSize = 64;
  const DenseMatcher matcher({ &ex }, o);
  OpenClDenseScorer scorer(device, matcher);
  DenseQuery q;
  q.heights.resize(64 * 64);
  q.known.resize(64 * 64);
  for (int j = 0; j < 64; ++j)
  {
    for (int i = 0; i < 64; ++i)
    {
      q.heights[static_cast<std::size_t>(j * 64 + i)] = source.at(20 + i, 30 + j);
      q.known[static_cast<std::size_t>(j * 64 + i)] = (i < 20 || j < 12) ? 1 : 0;
    }
  }
  const CoarseQuery cq = matcher.coarseQuery(q);
  const auto cpu = matcher.coarseCosts(cq);
  const auto gpu = scorer.coarseCosts(cq);
  ASSERT_EQ(cpu.size(), gpu.size());
  for (std::size_t v = 0; v < cpu.size(); ++v)
  {
    ASSERT_EQ(cpu[v].size(), gpu[v].size());
    for (std::size_t k = 0; k < cpu[v].size(); ++k)
    {
      if (std::isinf(cpu[v][k]))
      {
        ASSERT_TRUE(std::isinf(gpu[v][k]));
        continue;
      }
      ASSERT_NEAR(gpu[v][k], cpu[v][k], 1e-4 * std::max(1.0f, cpu[v][k]));
    }
  }
  const auto a = matcher.refine(q, cpu, 8);
  const auto b = matcher.refine(q, gpu, 8);
  // The pruned pass agrees too, whichever backend sums.
  const auto c = matcher.refine(q,
    matcher.prunedCoarseCosts(cq,
      [&](const CoarseTerms& t, CoarseImage i, const std::vector<std::vector<std::uint8_t>>* r)
      { return scorer.coarseSsd(t, i, r); }),
    8);
  ASSERT_EQ(a.size(), c.size());
  for (std::size_t r = 0; r < a.size(); ++r)
  {
    EXPECT_EQ(a[r].x, c[r].x);
    EXPECT_EQ(a[r].y, c[r].y);
    EXPECT_EQ(a[r].cost, c[r].cost);
  }
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t r = 0; r < a.size(); ++r)
  {
    EXPECT_EQ(a[r].variant, b[r].variant);
    EXPECT_EQ(a[r].x, b[r].x);
    EXPECT_EQ(a[r].y, b[r].y);
    EXPECT_EQ(a[r].cost, b[r].cost);
  }
}

TEST(OpenCL, BackendNames)
{
  EXPECT_EQ(parseBackend("auto"), Backend::Auto);
  EXPECT_EQ(parseBackend("opencl"), Backend::OpenCL);
  EXPECT_EQ(parseBackend("cpu"), Backend::Cpu);
  EXPECT_THROW(parseBackend("cuda"), Error);
}

TEST(OpenCL, ABuildErrorIsReportedWithTheCompilerLog)
{
  try
  {
    OpenClDevice::create("__kernel void broken(__global float* x) { x[0] = undefined_name; }");
    FAIL() << "a broken kernel built";
  }
  catch (const Error& e)
  {
    const std::string message = e.what();
    EXPECT_NE(message.find("did not build"), std::string::npos) << message;
    EXPECT_NE(message.find("undefined_name"), std::string::npos) << message; // the log names it
  }
}

TEST(PatchMatcher, BackendsAgreeAndAutoPicksOpenClOnlyOnAGpu)
{
  const Heightfield ex = crop(colorado(), 60, 60, 400, 400);
  const FeatureExtraction f = extractFeatures(ex, FeatureType::Ridge, {});
  MatcherOptions o;
  o.patchSize = 64;
  o.backend = Backend::Auto;
  // Here OpenCL is PoCL, a CPU device: auto matches on the CPU backend.
  EXPECT_EQ(PatchMatcher({ &ex }, { &f.graph }, o).backend(),
    openClHasAccelerator() ? Backend::OpenCL : Backend::Cpu);
  o.backend = Backend::OpenCL;
  PatchMatcher automatic({ &ex }, { &f.graph }, o);
  EXPECT_EQ(automatic.backend(), Backend::OpenCL);
  o.backend = Backend::Cpu;
  PatchMatcher cpu({ &ex }, { &f.graph }, o);
  EXPECT_EQ(cpu.backend(), Backend::Cpu);
  const NoiseVariance noise(ex);
  const FeatureQuery q = makeFeatureQuery(cpu.pool().sites[3], ex, noise, nullptr, nullptr, 64);
  const auto a = automatic.matchFeature(q);
  const auto b = cpu.matchFeature(q);
  ASSERT_EQ(a.size(), 8u);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t r = 0; r < a.size(); ++r)
  {
    EXPECT_EQ(a[r].poolIndex, b[r].poolIndex);
    EXPECT_NEAR(a[r].cost, b[r].cost, 1e-4 * std::max(1.0f, b[r].cost));
  }
}

TEST(PatchMatcher, MissingFeatureTypeFallsBackToDenseWithAWarning)
{
  const Heightfield ex = crop(colorado(), 60, 60, 300, 300);
  const FeatureExtraction ridges = extractFeatures(ex, FeatureType::Ridge, {});
  MatcherOptions o;
  o.patchSize = 48;
  o.backend = Backend::Cpu;
  PatchMatcher matcher({ &ex }, { &ridges.graph }, o); // ridges only
  FeatureQuery valley;
  valley.type = -1;
  valley.kind = static_cast<int>(NodeKind::End);
  valley.arms = 1;
  DenseQuery window;
  window.heights.assign(48 * 48, 0.0f);
  window.known.assign(48 * 48, 0);
  for (int j = 0; j < 48; ++j)
  {
    for (int i = 0; i < 12; ++i)
    {
      window.heights[static_cast<std::size_t>(j * 48 + i)] = ex.at(100 + i, 120 + j);
      window.known[static_cast<std::size_t>(j * 48 + i)] = 1;
    }
  }
  const auto found = matcher.matchFeature(valley, &window);
  ASSERT_FALSE(found.empty());
  EXPECT_FALSE(found[0].feature);
  EXPECT_NEAR(found[0].centreX, 100 + 23.5, 1e-9); // the window cut from the exemplar
  EXPECT_NEAR(found[0].centreY, 120 + 23.5, 1e-9);
  ASSERT_FALSE(matcher.warnings().empty());
  EXPECT_NE(matcher.warnings().back().find("non-feature"), std::string::npos);
}

TEST(PatchMatcher, NoOpenClPlatformFallsBackToTheCpu)
{
  // A real failure: the ICD loader is pointed at an empty vendor folder.
  setenv("OCL_ICD_VENDORS", "/nonexistent-tsynth-test", 1);
  const Heightfield ex = crop(colorado(), 0, 0, 200, 200);
  const FeatureExtraction f = extractFeatures(ex, FeatureType::Ridge, {});
  MatcherOptions o;
  o.patchSize = 48;
  // Auto has no accelerator to use and takes the CPU, as it would on PoCL.
  EXPECT_FALSE(openClHasAccelerator());
  PatchMatcher matcher({ &ex }, { &f.graph }, o);
  EXPECT_EQ(matcher.backend(), Backend::Cpu);
  // Asked for OpenCL, it says why there is none.
  o.backend = Backend::OpenCL;
  try
  {
    PatchMatcher refused({ &ex }, { &f.graph }, o);
    ADD_FAILURE() << "OpenCL without a platform was accepted";
  }
  catch (const Error& e)
  {
    EXPECT_NE(std::string(e.what()).find("No OpenCL platform"), std::string::npos) << e.what();
  }
}

TEST(SiteMatch, ADenseSiteFindsItsOwnPlaceAndMapsItsCost)
{
  // The target is a piece of the exemplar: matching its centre finds where it
  // was cut (the unrotated variant), and the cost map is lowest there.
  const Heightfield ex = crop(colorado(), 60, 60, 300, 300);
  const Heightfield target = crop(ex, 100, 120, 96, 96);
  const FeatureExtraction f = extractFeatures(ex, FeatureType::Ridge, {});
  MatcherOptions o;
  o.patchSize = 48;
  o.backend = Backend::Cpu;
  PatchMatcher matcher({ &ex }, { &f.graph }, o);
  const std::vector<std::uint8_t> known(target.size(), 1);
  const SiteMatchResult r = matchAtSite(matcher, target, known, 48.0, 48.0, false, 48);
  ASSERT_FALSE(r.candidates.empty());
  EXPECT_FALSE(r.atFeature);
  EXPECT_NEAR(r.candidates[0].centreX, 100 + 48, 0.5);
  EXPECT_NEAR(r.candidates[0].centreY, 120 + 48, 0.5);
  ASSERT_EQ(r.costMap.size(), ex.size());
  std::size_t lowest = 0;
  for (std::size_t k = 0; k < r.costMap.size(); ++k)
  {
    if (std::isfinite(r.costMap[k]) && !(r.costMap[k] >= r.costMap[lowest]))
    {
      lowest = k;
    }
  }
  // Within one coarse block (4 cells) of where the window was cut.
  EXPECT_LE(std::abs(static_cast<int>(lowest % 300) - 148), 4);
  EXPECT_LE(std::abs(static_cast<int>(lowest / 300) - 168), 4);
}

TEST(SiteMatch, AFeatureSiteSnapsToTheNearestTargetFeatureOrSaysThereIsNone)
{
  const Heightfield ex = crop(colorado(), 60, 60, 300, 300);
  FeatureGraph both = extractFeatures(ex, FeatureType::Ridge, {}).graph;
  appendGraph(both, extractFeatures(ex, FeatureType::Valley, {}).graph);
  MatcherOptions o;
  o.patchSize = 48;
  o.backend = Backend::Cpu;
  PatchMatcher matcher({ &ex }, { &both }, o);
  const std::vector<std::uint8_t> known(ex.size(), 1);
  const SiteMatchResult r = matchAtSite(matcher, ex, known, 150.0, 150.0, true, 48);
  ASSERT_TRUE(r.atFeature);
  EXPECT_LE(std::hypot(r.centreX - 150.0, r.centreY - 150.0), 24.0);
  EXPECT_TRUE(r.candidates.front().feature);
  // A flat target has no feature: a dense match and a warning.
  Heightfield flat(96, 96, 3000.0f);
  flat.cellX = flat.cellY = ex.cellX;
  const SiteMatchResult none =
    matchAtSite(matcher, flat, std::vector<std::uint8_t>(flat.size(), 1), 48.0, 48.0, true, 48);
  EXPECT_FALSE(none.atFeature);
  EXPECT_FALSE(none.candidates.empty());
  ASSERT_FALSE(none.warnings.empty());
  EXPECT_NE(none.warnings.front().find("No target feature"), std::string::npos);
  // Bad input.
  EXPECT_THROW(
    matchAtSite(matcher, flat, std::vector<std::uint8_t>(5, 1), 48, 48, false, 48), Error);
  EXPECT_THROW(
    matchAtSite(
      matcher, crop(ex, 0, 0, 40, 40), std::vector<std::uint8_t>(1600, 1), 20, 20, false, 48),
    Error);
}
