// Distance-based synthesis (Rusnell 2009) at the two sizes: 512 x 512
// with 100 stroke features and 1536 x 1536 with 15,000, default options, three
// profiles and fBm costs. Prints seconds (best of the repetitions, run
// interleaved) and same-run ratios: the bucket queue (the default) against the
// radix heap, and whether they give the same bits; std::priority_queue against
// the radix heap; 2 threads against 1; the approximate preview against the
// whole synthesis; and the mean cells a feature's search settles
// (the thesis: 35-47 thousand at these sizes, 28 s mean at 512^2 and 55 min at
// 1536^2 with 14,758 features on a Pentium 4).
// Usage: tsynth_bench_distance [repetitions] [--only 512|1536] [--write DIR]
//   --only: one of the two cases; --write: each case's heights and approximate
//   field (s = 2 and s = 1.1) as raw little-endian float32 files in DIR, to
//   compare the bits of two builds.
#include "Core/Random.h"
#include "Distance/DistanceSynthesis.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

using namespace tsynth;
using Clock = std::chrono::steady_clock;

namespace
{

constexpr std::uint64_t kLayoutSeed = 12;
// The thesis's running example's sea level scale (the default is 2): lower
// features, smaller footprints.
constexpr double kRunningExampleS = 1.1;

// `count` short strokes (two segments each) at seeded random places, fBm costs,
// profiles by feature id mod 3 (linear, rounded, sharp), `width` cells wide.
DistanceInputs strokeScene(int size, int count, double minLength, double maxLength, double width)
{
  std::vector<GeneratorLine> lines;
  for (int f = 0; f < count; ++f)
  {
    auto u = [&](int k) { return seededUniform(kLayoutSeed, static_cast<std::uint64_t>(f), k); };
    GeneratorLine line;
    Point2 p{ u(0) * (size - 1), u(1) * (size - 1) };
    double angle = u(2) * 2.0 * M_PI;
    line.points.push_back(p);
    for (int s = 0; s < 2; ++s)
    {
      const double length = 0.5 * (minLength + (maxLength - minLength) * u(3 + s));
      p = { p.x + length * std::cos(angle), p.y + length * std::sin(angle) };
      line.points.push_back(p);
      angle += (u(5 + s) - 0.5);
    }
    lines.push_back(line);
  }
  DistanceInputs in;
  in.width = size;
  in.height = size;
  in.features = generatorsFromLines(lines, size, size, 3);
  in.profiles = { MonotoneProfile::fromPoints({ 0.0, width }, { 1.0, 0.0 }),
    MonotoneProfile::fromPoints({ 0.0, 0.3 * width, width }, { 1.0, 0.85, 0.0 }),
    MonotoneProfile::fromPoints({ 0.0, 0.3 * width, width }, { 1.0, 0.3, 0.0 }) };
  return in;
}

void writeFloats(const std::string& path, const std::vector<float>& values)
{
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(values.data()),
    static_cast<std::streamsize>(values.size() * sizeof(float)));
  if (!out)
  {
    std::fprintf(stderr, "cannot write %s\n", path.c_str());
    std::exit(1);
  }
}

// Writes DIR/<tag>_heights.f32 and DIR/<tag>_approximate.f32.
void writeTerrain(const std::string& dir, const std::string& tag, const DistanceTerrain& t)
{
  if (!dir.empty())
  {
    writeFloats(dir + "/" + tag + "_heights.f32", t.heights.z);
    writeFloats(dir + "/" + tag + "_approximate.f32", t.approximate.z);
  }
}

// One timed configuration: a queue on a thread count.
struct Config
{
  const char* label;
  DijkstraQueue queue;
  int threads;
  bool approximateOnly;
  double seaLevelScale;
};

struct Timing
{
  double best = std::numeric_limits<double>::infinity();
  DistanceTerrain result;
};

// Each repetition runs every configuration once, so that a change of the
// machine's load mid-run reaches all of them alike; each keeps its best time.
std::vector<Timing> timeInterleaved(const DistanceInputs& in,
  int repetitions,
  const std::vector<Config>& configs)
{
  std::vector<Timing> timings(configs.size());
  for (int r = 0; r < repetitions; ++r)
  {
    for (std::size_t i = 0; i < configs.size(); ++i)
    {
      const Config& c = configs[i];
      Timing& t = timings[i];
      DistanceOptions o;
      o.queue = c.queue;
      o.approximateOnly = c.approximateOnly;
      o.seaLevelScale = c.seaLevelScale;
      omp_set_num_threads(c.threads);
      const auto t0 = Clock::now();
      t.result = synthesiseByDistance(in, o);
      t.best = std::min(t.best, std::chrono::duration<double>(Clock::now() - t0).count());
    }
  }
  return timings;
}

const char* sameBits(const DistanceTerrain& a, const DistanceTerrain& b)
{
  return a.heights.z == b.heights.z && a.approximate.z == b.approximate.z ? "same bits"
                                                                          : "BITS DIFFER";
}

void bench(const char* name,
  const std::string& tag,
  const DistanceInputs& in,
  int repetitions,
  const std::string& writeDir)
{
  const double s = DistanceOptions().seaLevelScale;
  const std::vector<Config> configs = {
    { "buckets, 2 threads", DijkstraQueue::Bucket, 2, false, s },
    { "buckets, 1 thread", DijkstraQueue::Bucket, 1, false, s },
    { "radix heap, 2 threads", DijkstraQueue::Radix, 2, false, s },
    { "radix heap, 1 thread", DijkstraQueue::Radix, 1, false, s },
    { "std::priority_queue, 1 thread", DijkstraQueue::BinaryHeap, 1, false, s },
    { "approximate field, 2 threads", DijkstraQueue::Bucket, 2, true, s },
    { "s = 1.1, buckets, 2 threads", DijkstraQueue::Bucket, 2, false, kRunningExampleS },
    { "s = 1.1, radix heap, 2 threads", DijkstraQueue::Radix, 2, false, kRunningExampleS }
  };
  const std::vector<Timing> c = timeInterleaved(in, repetitions, configs);
  const DistanceTerrain& t = c[0].result;
  std::printf("%s: %zu features, %zu generator nodes, c_s %.2f; best of %d\n",
    name,
    t.features,
    t.generators,
    t.seaLevelCost,
    repetitions);
  for (std::size_t i = 0; i < c.size(); ++i)
  {
    std::printf("  %-32s %8.3f s\n", configs[i].label, c[i].best);
  }
  std::printf("  buckets against the radix heap: %.2fx (2 threads), %.2fx (1 thread), "
              "%.2fx (s = 1.1); %s\n",
    c[2].best / c[0].best,
    c[3].best / c[1].best,
    c[7].best / c[6].best,
    sameBits(c[0].result, c[2].result));
  std::printf(
    "  std::priority_queue against the radix heap: %.2fx (1 thread)\n", c[4].best / c[3].best);
  std::printf("  2 threads against 1: %.2fx (buckets), %.2fx (radix heap)\n",
    c[1].best / c[0].best,
    c[3].best / c[2].best);
  std::printf("  approximate field: %.0f%% of the whole\n", 100.0 * c[5].best / c[0].best);
  std::printf("  cells settled per feature %.0f (grid %d cells), %.0f at s = 1.1; "
              "%zu searches left to the radix heap\n",
    static_cast<double>(t.featureVisits) / static_cast<double>(t.features),
    in.width * in.height,
    static_cast<double>(c[6].result.featureVisits) / static_cast<double>(c[6].result.features),
    t.radixSearches);
  writeTerrain(writeDir, tag + "_s2", t);
  writeTerrain(writeDir, tag + "_s1.1", c[6].result);
}

} // namespace

int main(int argc, char** argv)
{
  int repetitions = 3;
  std::string only;
  std::string writeDir;
  for (int a = 1; a < argc; ++a)
  {
    if (std::strcmp(argv[a], "--only") == 0 && a + 1 < argc)
    {
      only = argv[++a];
    }
    else if (std::strcmp(argv[a], "--write") == 0 && a + 1 < argc)
    {
      writeDir = argv[++a];
    }
    else
    {
      repetitions = std::max(1, std::atoi(argv[a]));
    }
  }
  if (only.empty() || only == "512")
  {
    bench("512 x 512", "512", strokeScene(512, 100, 20.0, 80.0, 120.0), repetitions, writeDir);
  }
  if (only.empty() || only == "1536")
  {
    bench("1536 x 1536", "1536", strokeScene(1536, 15000, 2.0, 12.0, 40.0), repetitions, writeDir);
  }
  return 0;
}
