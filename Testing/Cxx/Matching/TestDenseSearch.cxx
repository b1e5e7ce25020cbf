// Tests of Kernels/Matching/DenseSearch.cxx: the non-feature search against the exhaustive one,
// the roughness and landform terms, and the pruned coarse pass.
#include "Core/Error.h"
#include "Core/Smoothing.h"
#include "Matching/DenseSearch.h"
#include "Matching/LandformTerm.h"
#include "Matching/NoiseVariance.h"
#include "MatchingTestData.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

using namespace tsynth;
using tsynth::test::matching::colorado;
using tsynth::test::matching::crop;

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
