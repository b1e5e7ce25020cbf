// Matcher speed, with same-run ratios:
//   - scoring the whole feature pool of a 2049 x 2049 exemplar against one target:
//     OpenCL (PoCL) vs the CPU reference (2 threads) vs the CPU reference on 1 thread;
//   - dense non-feature search, 64 x 64 window over a 1024 x 1024 exemplar in all
//     10 variants: coarse-to-fine on OpenCL and on the CPU vs exhaustive search;
//   - feature matching as the synthesis does it on the CPU, Mont Blanc's ridge and
//     valley sites against Colorado's pool at patch 32: the bounded ranking vs
//     scoring every candidate and taking the k best;
//   - the synthesiser's fill query (80 x 80, L-shaped known part) over five
//     648 x 648 exemplars: the pruned coarse pass (lower bound first) vs the full one.
// Usage: tsynth_bench_matching [DEM]
#include "BenchUtilities.h"
#include "Core/HeightfieldIO.h"
#include "Features/Ppa.h"
#include "Matching/CandidatePool.h"
#include "Matching/DenseSearch.h"
#include "Matching/FeatureCost.h"
#include "Matching/FeatureRanking.h"
#include "Matching/LandformTerm.h"
#include "Matching/OpenClMatcher.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>

using namespace tsynth;
using Clock = std::chrono::steady_clock;

namespace
{

double bestOf(int n, const std::function<void()>& f)
{
  double best = 1e30;
  for (int r = 0; r < n; ++r)
  {
    const auto t0 = Clock::now();
    f();
    best = std::min(best, std::chrono::duration<double>(Clock::now() - t0).count());
  }
  return best;
}

// Feature matching as the synthesis does it, with a DEM as the target.
void benchFeatureRanking(const Heightfield& exemplar)
{
  const Heightfield target =
    readHeightfield(std::string(TSYNTH_BUNDLED_DATA) + "/dems/alps-montblanc.png");
  constexpr int kPatch = 32;
  constexpr std::size_t kKept = 8;
  PoolOptions po;
  po.patchSize = kPatch;
  const FeatureExtraction ridges = extractFeatures(exemplar, FeatureType::Ridge, {});
  const FeatureExtraction valleys = extractFeatures(exemplar, FeatureType::Valley, {});
  const CandidatePool pool =
    buildCandidatePool({ &exemplar, &exemplar }, { &ridges.graph, &valleys.graph }, po);
  // The target's sites, with the output known over its west half (the target
  // itself there) and the landform asked, as mid-way through a synthesis.
  const NoiseVariance noise(target);
  const Heightfield smooth = landformImage(target, kPatch);
  const std::vector<float> sure(target.size(), 1.0f);
  std::vector<std::uint8_t> known(target.size(), 0);
  for (int j = 0; j < target.height; ++j)
  {
    for (int i = 0; i < target.width / 2; ++i)
    {
      known[target.index(i, j)] = 1;
    }
  }
  std::vector<FeatureQuery> queries;
  for (const FeatureType type : { FeatureType::Ridge, FeatureType::Valley })
  {
    const FeatureExtraction f = extractFeatures(target, type, {});
    const CandidatePool sites = buildCandidatePool({ &target }, { &f.graph }, po);
    for (std::size_t s = 0; s < sites.sites.size();
         s += std::max<std::size_t>(1, sites.sites.size() / 100))
    {
      queries.push_back(
        makeFeatureQuery(sites.sites[s], target, noise, &target, &known, kPatch, &smooth, &sure));
    }
  }
  const MatchWeights w;
  std::vector<std::vector<RankedCandidate>> full(queries.size());
  std::vector<std::vector<RankedCandidate>> ranked(queries.size());
  const double reference = bestOf(3,
    [&]
    {
      for (std::size_t i = 0; i < queries.size(); ++i)
      {
        full[i] = topKPerExemplar(pool, scoreFeatureCandidates(pool, queries[i], w), kKept);
        full[i].erase(std::remove_if(full[i].begin(),
                        full[i].end(),
                        [](const RankedCandidate& r) { return r.cost >= kMismatchPenalty; }),
          full[i].end());
      }
    });
  FeatureRanker ranker(pool);
  RankingCounts counts;
  const double bounded = bestOf(3,
    [&]
    {
      counts = {};
      for (std::size_t i = 0; i < queries.size(); ++i)
      {
        RankingCounts one;
        ranked[i] = ranker.rank(queries[i], w, kKept, &one);
        counts.shaped += one.shaped;
        counts.beforeArms += one.beforeArms;
        counts.beforeOverlap += one.beforeOverlap;
        counts.scored += one.scored;
      }
    });
  std::size_t same = 0;
  for (std::size_t i = 0; i < queries.size(); ++i)
  {
    same += std::equal(full[i].begin(),
      full[i].end(),
      ranked[i].begin(),
      ranked[i].end(),
      [](const RankedCandidate& a, const RankedCandidate& b)
      { return a.index == b.index && a.cost == b.cost; });
  }
  std::printf(
    "\nFeature matching, %zu Mont Blanc sites against Colorado's pool (%zu candidates, patch %d, "
    "k %zu):\n",
    queries.size(),
    pool.size(),
    kPatch,
    kKept);
  std::printf("  score every candidate + top k: %.3f ms per site\n",
    1e3 * reference / static_cast<double>(queries.size()));
  std::printf("  bounded ranking:               %.3f ms per site (ratio %.2fx); the same %zu of "
              "%zu rankings\n",
    1e3 * bounded / static_cast<double>(queries.size()),
    reference / bounded,
    same,
    queries.size());
  const double shaped = static_cast<double>(counts.shaped);
  std::printf("  of %zu candidates of the sites' shapes: %.0f%% left on their bounds (roughness, "
              "landform, angles, profiles' moments), %.0f%% on the arms, %.1f%% scored in full\n",
    counts.shaped,
    100.0 * static_cast<double>(counts.beforeArms) / shaped,
    100.0 * static_cast<double>(counts.beforeOverlap) / shaped,
    100.0 * static_cast<double>(counts.scored) / shaped);
}

} // namespace

int main(int argc, char** argv)
{
  const std::string path =
    argc > 1 ? argv[1] : std::string(TSYNTH_BUNDLED_DATA) + "/dems/colorado.png";
  const Heightfield dem = readHeightfield(path);
  std::shared_ptr<OpenClDevice> device;
  try
  {
    device = OpenClDevice::create();
    std::printf("OpenCL device: %s\n", device->name().c_str());
  }
  catch (const std::exception& e)
  {
    std::printf("OpenCL unavailable: %s\n", e.what());
  }

  // Feature scoring on a 2049 x 2049 exemplar.
  {
    const Heightfield ex = bench::mirrorTile(dem, 2049);
    auto t0 = Clock::now();
    const FeatureExtraction f = extractFeatures(ex, FeatureType::Ridge, {});
    const double ppa = std::chrono::duration<double>(Clock::now() - t0).count();
    t0 = Clock::now();
    const CandidatePool pool = buildCandidatePool({ &ex }, { &f.graph }, {});
    const double build = std::chrono::duration<double>(Clock::now() - t0).count();
    std::printf("\nFeature pool: 2049 x 2049 exemplar, patch 80: %zu sites, %zu candidate variants "
                "(PPA %.0f ms, pool build %.0f ms)\n",
      pool.sites.size(),
      pool.size(),
      1e3 * ppa,
      1e3 * build);
    const NoiseVariance noise(ex);
    std::vector<std::uint8_t> known(ex.size(), 0);
    for (int j = 900; j < 1000; ++j)
    {
      for (int i = 0; i < ex.width; ++i)
      {
        known[ex.index(i, j)] = 1;
      }
    }
    const FeatureQuery q =
      makeFeatureQuery(pool.sites[pool.sites.size() / 3], ex, noise, &ex, &known, 80);
    std::vector<float> costs;
    const double cpu = bestOf(10, [&] { costs = scoreFeatureCandidates(pool, q, {}); });
    const double topk = bestOf(10, [&] { (void)topK(costs, 8); });
    const int threads = omp_get_max_threads();
    omp_set_num_threads(1);
    const double cpu1 = bestOf(5, [&] { costs = scoreFeatureCandidates(pool, q, {}); });
    omp_set_num_threads(threads);
    std::printf("  CPU reference, %d threads: %.2f ms per target (+ top-8 %.2f ms)\n",
      threads,
      1e3 * cpu,
      1e3 * topk);
    std::printf("  CPU reference, 1 thread:   %.2f ms (ratio %.2fx)\n", 1e3 * cpu1, cpu1 / cpu);
    if (device)
    {
      OpenClFeatureScorer scorer(device, pool);
      (void)scorer.score(q, {});
      const double gpu = bestOf(10, [&] { costs = scorer.score(q, {}); });
      std::printf("  OpenCL on %s: %.2f ms (OpenCL vs CPU: %.2fx)\n",
        device->name().c_str(),
        1e3 * gpu,
        cpu / gpu);
    }
  }

  benchFeatureRanking(dem);

  // Dense search on a 1024 x 1024 exemplar.
  {
    const Heightfield ex = bench::mirrorTile(dem, 1024);
    DenseOptions o;
    o.patchSize = 64;
    auto t0 = Clock::now();
    const DenseMatcher matcher({ &ex }, o);
    const double prep = std::chrono::duration<double>(Clock::now() - t0).count();
    DenseQuery q;
    q.heights.resize(64 * 64);
    q.known.resize(64 * 64);
    for (int j = 0; j < 64; ++j)
    {
      for (int i = 0; i < 64; ++i)
      {
        q.heights[static_cast<std::size_t>(j * 64 + i)] = dem.at(400 + i, 200 + j) + 30.0f;
        q.known[static_cast<std::size_t>(j * 64 + i)] = (i < 24 || j < 24) ? 1 : 0;
      }
    }
    std::printf(
      "\nDense search: 64 x 64 window (L-shaped known part) over 1024 x 1024, 10 variants "
      "(preparing the oriented exemplars once: %.0f ms)\n",
      1e3 * prep);
    std::vector<DenseMatch> fast;
    const double cpu = bestOf(5, [&] { fast = matcher.search(q, 8); });
    std::printf("  coarse-to-fine, CPU: %.1f ms per query\n", 1e3 * cpu);
    double gpu = 0.0;
    if (device)
    {
      OpenClDenseScorer scorer(device, matcher);
      auto cl =
        [&](const CoarseTerms& t, CoarseImage i, const std::vector<std::vector<std::uint8_t>>* r)
      { return scorer.coarseSsd(t, i, r); };
      (void)scorer.coarseCosts(matcher.coarseQuery(q));
      gpu = bestOf(5,
        [&]
        { fast = matcher.refine(q, matcher.prunedCoarseCosts(matcher.coarseQuery(q), cl), 8); });
      std::printf(
        "  coarse-to-fine, OpenCL pruned coarse pass + CPU refinement: %.1f ms (OpenCL vs "
        "CPU %.2fx)\n",
        1e3 * gpu,
        cpu / gpu);
    }
    // Exhaustive search in one variant (the naive loop), scaled to ten.
    DenseOptions one = o;
    one.variants.fill(false);
    one.variants[0] = true;
    const DenseMatcher single({ &ex }, one);
    std::vector<DenseMatch> exact;
    const double brute = bestOf(1, [&] { exact = single.bruteForce(q, 1); });
    std::printf("  exhaustive full-resolution search, 1 variant: %.0f ms; x10 variants ~ %.0f ms: "
                "coarse-to-fine is %.0fx faster on the CPU%s\n",
      1e3 * brute,
      1e4 * brute,
      10 * brute / cpu,
      device ? (", " + std::to_string(static_cast<int>(10 * brute / gpu)) + "x with OpenCL").c_str()
             : "");
    const bool agree = !fast.empty() && !exact.empty() &&
      (fast[0].variant != 0 || (fast[0].x == exact[0].x && fast[0].y == exact[0].y) ||
        fast[0].cost <= exact[0].cost);
    std::printf("  best match: variant %d at (%d, %d), cost %.4g; exhaustive best in variant 0: "
                "(%d, %d), cost %.4g%s\n",
      fast[0].variant,
      fast[0].x,
      fast[0].y,
      fast[0].cost,
      exact[0].x,
      exact[0].y,
      exact[0].cost,
      agree ? "" : "  (DISAGREE)");
  }
  // Fill queries over five exemplars: pruned vs full coarse pass.
  {
    std::vector<Heightfield> crops;
    const Heightfield big = bench::mirrorTile(dem, 1400);
    for (int e = 0; e < 5; ++e)
    {
      Heightfield c(648, 648);
      c.cellX = dem.cellX;
      c.cellY = dem.cellY;
      for (int j = 0; j < 648; ++j)
      {
        for (int i = 0; i < 648; ++i)
        {
          c.at(i, j) = big.at(i + 150 * e, j + 100 * e);
        }
      }
      crops.push_back(std::move(c));
    }
    std::vector<const Heightfield*> exemplars;
    for (const Heightfield& c : crops)
    {
      exemplars.push_back(&c);
    }
    DenseOptions o;
    o.patchSize = 80;
    const DenseMatcher matcher(exemplars, o);
    std::unique_ptr<OpenClDenseScorer> scorer;
    if (device)
    {
      scorer = std::make_unique<OpenClDenseScorer>(device, matcher);
    }
    std::printf("\nFill queries: 80 x 80 window, L-shaped known part, over five 648 x 648 "
                "exemplars in 10 variants (mean of 8 queries)\n");
    double full = 0.0, pruned = 0.0, across = 0.0, fullCl = 0.0, prunedCl = 0.0, share = 0.0,
           acrossShare = 0.0;
    int same = 0, sameAcross = 0;
    const int queries = 8;
    for (int n = 0; n < queries; ++n)
    {
      DenseQuery q;
      q.heights.resize(80 * 80);
      q.known.resize(80 * 80);
      const int band = 20 + 5 * n;
      for (int j = 0; j < 80; ++j)
      {
        for (int i = 0; i < 80; ++i)
        {
          q.heights[static_cast<std::size_t>(j * 80 + i)] = big.at(700 + 37 * n + i, 900 + j);
          q.known[static_cast<std::size_t>(j * 80 + i)] = (i < band || j < band) ? 1 : 0;
        }
      }
      const CoarseQuery cq = matcher.coarseQuery(q);
      auto cpu =
        [&](const CoarseTerms& t, CoarseImage i, const std::vector<std::vector<std::uint8_t>>* r)
      { return matcher.coarseSsd(t, i, r); };
      std::vector<std::vector<float>> a, b, c;
      full += bestOf(2, [&] { a = matcher.coarseCosts(cq); });
      pruned += bestOf(2, [&] { b = matcher.prunedCoarseCosts(cq, cpu); });
      const DenseMatcher::RefineRequest request{ 8, nullptr };
      across += bestOf(2, [&] { c = matcher.prunedCoarseCosts(cq, cpu, &request); });
      const auto scoredShare = [&](const std::vector<std::vector<float>>& costs)
      {
        std::size_t finite = 0;
        for (const auto& v : costs)
        {
          finite += static_cast<std::size_t>(
            std::count_if(v.begin(), v.end(), [](float x) { return std::isfinite(x); }));
        }
        std::size_t total = 0;
        for (const auto& v : a)
        {
          total += v.size();
        }
        return static_cast<double>(finite) / static_cast<double>(std::max<std::size_t>(1, total));
      };
      share += scoredShare(b);
      acrossShare += scoredShare(c);
      const auto ra = matcher.refine(q, a, 8);
      const auto sameAs = [&](const std::vector<DenseMatch>& rb)
      {
        return ra.size() == rb.size() &&
            std::equal(ra.begin(),
              ra.end(),
              rb.begin(),
              [](const DenseMatch& x, const DenseMatch& y)
              { return x.variant == y.variant && x.x == y.x && x.y == y.y && x.cost == y.cost; })
          ? 1
          : 0;
      };
      same += sameAs(matcher.refine(q, b, 8));
      sameAcross += sameAs(matcher.refine(q, c, 8));
      if (scorer)
      {
        auto cl =
          [&](const CoarseTerms& t, CoarseImage i, const std::vector<std::vector<std::uint8_t>>* r)
        { return scorer->coarseSsd(t, i, r); };
        fullCl += bestOf(2, [&] { a = scorer->coarseCosts(cq); });
        prunedCl += bestOf(2, [&] { b = matcher.prunedCoarseCosts(cq, cl); });
      }
    }
    std::printf("  CPU: full coarse pass %.1f ms, pruned %.1f ms (%.2fx faster); offsets scored "
                "in full: %.1f%%; same top 8 after refinement on %d of %d queries\n",
      1e3 * full / queries,
      1e3 * pruned / queries,
      full / pruned,
      100.0 * share / queries,
      same,
      queries);
    std::printf("  CPU, pruned across exemplars too (refine's 8 best asked): %.1f ms (%.2fx faster "
                "than the full pass, %.2fx than pruning each); offsets scored in full: %.1f%%; "
                "same top 8 on %d of %d queries\n",
      1e3 * across / queries,
      full / across,
      pruned / across,
      100.0 * acrossShare / queries,
      sameAcross,
      queries);
    if (scorer)
    {
      std::printf("  OpenCL: full coarse pass %.1f ms, pruned %.1f ms (%.2fx faster)\n",
        1e3 * fullCl / queries,
        1e3 * prunedCl / queries,
        fullCl / prunedCl);
    }
  }
  return 0;
}
