// PPA on a 2049 x 2049 real DEM (a bundled DEM mirror-tiled), per step, with
// same-run ratios against reference implementations:
//   - the whole extraction on 2 threads vs 1 thread;
//   - the default (with the significance test) vs significance 0 (PPA without it);
//   - our Kruskal (radix sort + Boost disjoint sets) vs Boost.Graph's
//     kruskal_minimum_spanning_tree on the same edges.
// Usage: tsynth_bench_ppa [DEM] [repetitions]
#include "BenchUtilities.h"
#include "Core/HeightfieldIO.h"
#include "Features/Ppa.h"

#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/kruskal_min_spanning_tree.hpp>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

using namespace tsynth;
using Clock = std::chrono::steady_clock;

namespace
{

double seconds(Clock::time_point t0)
{
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

PpaTimings best(const Heightfield& hf,
  int repetitions,
  const PpaOptions& options,
  FeatureExtraction* last)
{
  PpaTimings b;
  double bestTotal = 1e30;
  for (int r = 0; r < repetitions; ++r)
  {
    FeatureExtraction e = extractFeatures(hf, FeatureType::Ridge, options);
    if (e.timings.total() < bestTotal)
    {
      bestTotal = e.timings.total();
      b = e.timings;
    }
    if (last != nullptr)
    {
      *last = std::move(e);
    }
  }
  return b;
}

} // namespace

int main(int argc, char** argv)
{
  const std::string path =
    argc > 1 ? argv[1] : std::string(TSYNTH_BUNDLED_DATA) + "/dems/colorado.png";
  const int repetitions = argc > 2 ? std::max(1, std::atoi(argv[2])) : 3;
  const Heightfield hf = bench::mirrorTile(readHeightfield(path), 2049);
  std::printf("PPA benchmark: %s mirror-tiled to %d x %d, best of %d\n",
    path.c_str(),
    hf.width,
    hf.height,
    repetitions);

  FeatureExtraction result;
  FeatureExtraction plain;
  const PpaOptions defaults;
  PpaOptions off;
  off.significance = 0.0;
  const int threads = omp_get_max_threads();
  const PpaTimings t = best(hf, repetitions, defaults, &result);
  const PpaTimings tOff = best(hf, repetitions, off, &plain);
  omp_set_num_threads(1);
  const PpaTimings t1 = best(hf, repetitions, defaults, nullptr);
  omp_set_num_threads(threads);

  std::printf("\n%-28s %10s %12s %16s\n", "step", "ms", "ms 1 thread", "ms significance 0");
  auto row = [](const char* name, double a, double b, double c)
  { std::printf("%-28s %10.1f %12.1f %16.1f\n", name, 1e3 * a, 1e3 * b, 1e3 * c); };
  row("profile recognition", t.profile, t1.profile, tOff.profile);
  row("significance", t.significance, t1.significance, tOff.significance);
  row("target connection", t.connect, t1.connect, tOff.connect);
  row("spanning forest (Kruskal)", t.spanningForest, t1.spanningForest, tOff.spanningForest);
  row("pruning", t.pruning, t1.pruning, tOff.pruning);
  row("graph, smoothing, control", t.graph, t1.graph, tOff.graph);
  row("total", t.total(), t1.total(), tOff.total());
  std::printf("\ntargets %zu (%zu removed as insignificant: drop %.1f m = max(0.02 x relief "
              "%.1f m, 4 x noise %.2f m)), candidate edges %zu, forest edges %zu, cells kept %zu\n",
    result.statistics.targets,
    result.statistics.insignificant,
    result.statistics.significantDrop,
    result.statistics.relief,
    result.statistics.noise,
    result.statistics.candidateEdges,
    result.statistics.forestEdges,
    result.statistics.prunedCells);
  std::printf("significance 0: targets %zu, candidate edges %zu, cells kept %zu\n",
    plain.statistics.targets,
    plain.statistics.candidateEdges,
    plain.statistics.prunedCells);
  std::printf("graph: %zu nodes (%d branch, %d end), %zu chains, %d trees\n",
    result.graph.nodes.size(),
    result.graph.countKind(NodeKind::Branch),
    result.graph.countKind(NodeKind::End),
    result.graph.chains.size(),
    result.graph.componentCount);
  std::printf("ratio %d threads vs 1 thread: %.2fx\n", threads, t1.total() / t.total());
  std::printf("ratio default vs significance 0: %.2fx the time (significance step %.1f%% of "
              "the default's total)\n",
    t.total() / tOff.total(),
    100.0 * t.significance / t.total());
  std::printf("ratio vs Tasse's thesis (26.7 s for 2049^2): %.0fx faster\n", 26.7 / t.total());

  // Kruskal: ours vs Boost.Graph's on the same candidate edges.
  const auto targets = profileTargets(hf, 3, 0.0, 0.1); // significance 0: the most edges
  const auto edges = connectTargets(hf, targets);
  auto t0 = Clock::now();
  const PixelGraph ours = maximumSpanningForest(hf.width, hf.height, edges);
  const double oursSeconds = seconds(t0);
  using Graph = boost::adjacency_list<boost::vecS,
    boost::vecS,
    boost::undirectedS,
    boost::no_property,
    boost::property<boost::edge_weight_t, float>>;
  t0 = Clock::now();
  Graph g(hf.size());
  for (const CellEdge& e : edges)
  {
    boost::add_edge(e.a, e.b, -e.weight, g);
  }
  const double buildSeconds = seconds(t0);
  t0 = Clock::now();
  std::vector<boost::graph_traits<Graph>::edge_descriptor> tree;
  boost::kruskal_minimum_spanning_tree(g, std::back_inserter(tree));
  const double boostSeconds = seconds(t0);
  std::printf("\nKruskal on %zu edges: ours %.1f ms; Boost.Graph %.1f ms (+%.1f ms building the "
              "adjacency_list); ratio %.1fx (%.1fx with building); same forest size: %s\n",
    edges.size(),
    1e3 * oursSeconds,
    1e3 * boostSeconds,
    1e3 * buildSeconds,
    boostSeconds / oursSeconds,
    (boostSeconds + buildSeconds) / oursSeconds,
    ours.edgeCount() == tree.size() ? "yes" : "NO");
  return ours.edgeCount() == tree.size() ? 0 : 1;
}
