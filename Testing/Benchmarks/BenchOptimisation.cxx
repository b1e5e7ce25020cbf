// Terrain optimisation (Scott & Dodgson 2021) on a real source and a guide made
// as in the paper (a different DEM down-sampled 16 times, then up-sampled
// bilinearly to the output size): total and per-level seconds, energies, pits,
// the RMS to the guide at 1/16 scale, and same-run ratios (all threads vs one
// thread; the lane-wise early-exit SSD vs a plain scalar SSD PatchMatch on the
// finest level).
// Usage: tsynth_bench_optimisation [--source DEM] [--guide-dem DEM] [--size N]
//   [--patch N] [--levels L] [--alpha A] [--pm N] [--mu N] [--seed S]
//   [--rotations] [--reflections] [--no-pits] [--fill|--breach] [--out FILE]
//   [--no-thread-ratio] [--no-ssd-ratio] [--no-fit-range] [--guide-out FILE]
// The guide's heights are mapped onto the source's range unless --no-fit-range.
#include "BenchUtilities.h"
#include "Core/HeightfieldIO.h"
#include "Core/Resample.h"
#include "Optimisation/PatchMatch.h"
#include "Optimisation/Pyramid.h"
#include "Optimisation/TerrainOptimisation.h"

#include <omp.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

using namespace tsynth;
using Clock = std::chrono::steady_clock;

namespace
{

constexpr int kGuideReduction = 16; // the paper's guide: the target down-sampled 16 times
constexpr int kCoarseLevels = 4;    // 2^4 = 16: the scale the guide holds

double seconds(Clock::time_point t0)
{
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Box mean of 16 x 16 blocks, then bilinear up-sampling to size x size, on the
// source's cell size (the guide is a sketch of a terrain like the source's).
Heightfield paperGuide(const Heightfield& dem, int size, double cell)
{
  const int w = dem.width / kGuideReduction;
  const int h = dem.height / kGuideReduction;
  Heightfield small(w, h);
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      double sum = 0.0;
      for (int y = 0; y < kGuideReduction; ++y)
      {
        for (int x = 0; x < kGuideReduction; ++x)
        {
          sum += dem.at(i * kGuideReduction + x, j * kGuideReduction + y);
        }
      }
      small.at(i, j) = static_cast<float>(sum / (kGuideReduction * kGuideReduction));
    }
  }
  // Cell sizes that map the small grid's extent onto size x size cells.
  small.cellX = small.cellY = 1.0;
  Heightfield up = resampleToCellSize(small, (w - 1.0) / (size - 1.0), (h - 1.0) / (size - 1.0));
  Heightfield guide(size, size);
  for (int j = 0; j < size; ++j)
  {
    for (int i = 0; i < size; ++i)
    {
      guide.at(i, j) = up.at(std::min(i, up.width - 1), std::min(j, up.height - 1));
    }
  }
  guide.cellX = guide.cellY = cell;
  guide.cellSizeKnown = true;
  return guide;
}

// The guide's heights mapped linearly onto the source's range: matching is on
// absolute heights, so a guide the source cannot reach only measures the gap.
void fitRange(Heightfield& guide, const HeightRange& to)
{
  const HeightRange from = computeHeightRange(guide);
  const double scale = (to.max - to.min) / std::max(1e-6, double(from.max - from.min));
  for (float& z : guide.z)
  {
    z = static_cast<float>(to.min + (z - from.min) * scale);
  }
}

double coarseRms(const Heightfield& a, const Heightfield& b)
{
  const Heightfield ca = optim::gaussianPyramid(a, kCoarseLevels).back();
  const Heightfield cb = optim::gaussianPyramid(b, kCoarseLevels).back();
  double sum = 0.0;
  for (std::size_t k = 0; k < ca.size(); ++k)
  {
    sum += (ca.z[k] - cb.z[k]) * (ca.z[k] - cb.z[k]);
  }
  return std::sqrt(sum / static_cast<double>(ca.size()));
}

struct Args
{
  std::string source = std::string(TSYNTH_BUNDLED_DATA) + "/dems/colorado.png";
  std::string guideDem = std::string(TSYNTH_BUNDLED_DATA) + "/dems/alps-montblanc.png";
  int size = 1024;
  std::string out;
  std::string guideOut;
  bool threadRatio = true;
  bool ssdRatio = true;
  bool fitRange = true;
  OptimisationOptions options;
};

Args parse(int argc, char** argv)
{
  Args a;
  for (int i = 1; i < argc; ++i)
  {
    const std::string s = argv[i];
    auto next = [&]() { return std::string(i + 1 < argc ? argv[++i] : ""); };
    if (s == "--source")
      a.source = next();
    else if (s == "--guide-dem")
      a.guideDem = next();
    else if (s == "--size")
      a.size = std::stoi(next());
    else if (s == "--patch")
      a.options.patchSize = std::stoi(next());
    else if (s == "--levels")
      a.options.levels = std::stoi(next());
    else if (s == "--alpha")
      a.options.alpha = std::stod(next());
    else if (s == "--pm")
      a.options.patchMatchIterations = std::stoi(next());
    else if (s == "--mu")
      a.options.iterationsPerLevel = std::stoi(next());
    else if (s == "--seed")
      a.options.seed = std::stoull(next());
    else if (s == "--rotations")
      a.options.rotations = true;
    else if (s == "--reflections")
      a.options.reflections = true;
    else if (s == "--no-pits")
      a.options.removePits = false;
    else if (s == "--fill")
      a.options.pitRemoval.method = PitRemovalMethod::Fill;
    else if (s == "--breach")
      a.options.pitRemoval.method = PitRemovalMethod::Breach;
    else if (s == "--out")
      a.out = next();
    else if (s == "--no-thread-ratio")
      a.threadRatio = false;
    else if (s == "--no-ssd-ratio")
      a.ssdRatio = false;
    else if (s == "--no-fit-range")
      a.fitRange = false;
    else if (s == "--guide-out")
      a.guideOut = next();
    else
    {
      std::fprintf(stderr, "unknown argument %s\n", s.c_str());
      std::exit(2);
    }
  }
  return a;
}

void printRun(const OptimisationResult& r, double total)
{
  std::printf("level  size        seconds  energy (m^2 per patch, per iteration)      pits "
              "before/after removal\n");
  for (const OptimisationLevel& l : r.levels)
  {
    std::printf("%5d  %4d x %-4d %8.2f ", l.level, l.width, l.height, l.seconds);
    for (double e : l.energy)
    {
      std::printf(" %12.1f", e);
    }
    std::printf("   %zu/%zu\n", l.pitsBeforeRemoval, l.pitsAfter);
  }
  std::printf("total %.2f s\n", total);
}

// One M-step on the finest level from random matches, with the given SSD.
double finestSearch(const Heightfield& source,
  const Heightfield& target,
  const OptimisationOptions& o,
  bool plain,
  double* energy)
{
  const optim::SourceLevel s =
    optim::makeSourceLevel(source, o.patchSize, o.rotations, o.reflections, 0);
  optim::TargetGrid g{ target.width, target.height, target.z };
  std::vector<optim::Match> map = optim::randomMatches(s, g.width, g.height, o.seed, 1);
  std::vector<float> cost;
  optim::PatchMatchSettings settings;
  settings.iterations = o.patchMatchIterations;
  settings.seed = o.seed;
  settings.plainSsd = plain;
  const auto t0 = Clock::now();
  optim::patchMatch(s, g, map, cost, settings);
  const double t = seconds(t0);
  double sum = 0.0;
  for (float c : cost)
  {
    sum += c;
  }
  *energy = sum / static_cast<double>(cost.size());
  return t;
}

} // namespace

int main(int argc, char** argv)
{
  const Args a = parse(argc, argv);
  const Heightfield source = readHeightfield(a.source);
  Heightfield guide = paperGuide(readHeightfield(a.guideDem), a.size, source.cellX);
  const HeightRange sr = computeHeightRange(source);
  if (a.fitRange)
  {
    fitRange(guide, sr);
  }
  if (!a.guideOut.empty())
  {
    writeHeightfield(a.guideOut, guide);
  }
  const HeightRange gr = computeHeightRange(guide);
  std::printf(
    "source %s %d x %d (%.0f..%.0f m), guide from %s at %d^2 (%.0f..%.0f m), %d threads\n",
    a.source.c_str(),
    source.width,
    source.height,
    sr.min,
    sr.max,
    a.guideDem.c_str(),
    a.size,
    gr.min,
    gr.max,
    omp_get_max_threads());
  std::printf("patch %d, levels %d, alpha %.2f, PatchMatch iterations %d, mu %d, pits %s\n",
    a.options.patchSize,
    a.options.levels,
    a.options.alpha,
    a.options.patchMatchIterations,
    a.options.iterationsPerLevel,
    a.options.removePits ? pitRemovalMethodName(a.options.pitRemoval.method).c_str() : "off");
  auto t0 = Clock::now();
  const OptimisationResult r = optimiseTerrain(source, guide, a.options);
  const double total = seconds(t0);
  printRun(r, total);
  const HeightRange orr = computeHeightRange(r.terrain);
  std::printf(
    "output %.0f..%.0f m; RMS to the guide at 1/16 scale: output %.1f m, source tiled %.1f m\n",
    orr.min,
    orr.max,
    coarseRms(r.terrain, guide),
    coarseRms(bench::mirrorTile(source, a.size), guide));
  if (!a.out.empty())
  {
    writeHeightfield(a.out, r.terrain);
  }
  if (a.threadRatio && omp_get_max_threads() > 1)
  {
    const int threads = omp_get_max_threads();
    omp_set_num_threads(1);
    t0 = Clock::now();
    const OptimisationResult one = optimiseTerrain(source, guide, a.options);
    const double t1 = seconds(t0);
    omp_set_num_threads(threads);
    std::printf("1 thread %.2f s, %d threads %.2f s: speed-up %.2f; same bits: %s\n",
      t1,
      threads,
      total,
      t1 / total,
      one.terrain.z == r.terrain.z ? "yes" : "NO");
  }
  if (a.ssdRatio)
  {
    double eFast = 0.0, ePlain = 0.0;
    const double fast = finestSearch(source, r.terrain, a.options, false, &eFast);
    const double plain = finestSearch(source, r.terrain, a.options, true, &ePlain);
    std::printf(
      "finest-level M-step from random matches: lanes+early exit %.2f s, plain scalar %.2f s: "
      "ratio %.2f; energies %.3f vs %.3f\n",
      fast,
      plain,
      plain / fast,
      eFast,
      ePlain);
  }
  return 0;
}
