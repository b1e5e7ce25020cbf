#include "TerrainOptimisation.h"

#include "../Core/Grid.h"
#include "../Hydrology/MultiscalePitRemoval.h"

#include "../Core/Error.h"
#include "../Core/Memory.h"
#include "../Core/Resample.h"
#include "../Hydrology/Flow.h"
#include "../Synthesis/Setup.h"
#include "PatchMatch.h"
#include "Pyramid.h"

#include <chrono>
#include <cmath>
#include <optional>
#include <string>

namespace tsynth
{
namespace
{

using Clock = std::chrono::steady_clock;

// A coarsest source level of at least two patches per side, so that the
// initial search has more than a handful of distinct patches to choose from.
constexpr int kMinSourcePatchesPerSide = 2;
// Cell sizes closer than this (relative) count as equal: no resampling.
constexpr double kCellSizeTolerance = 1e-6;
// Random streams: one per (level, EM iteration) for the search, one per level
// for the up-sampling's fallbacks; kStreamsPerLevel exceeds any iteration count used.
constexpr std::uint64_t kStreamsPerLevel = 1ULL << 20;
constexpr std::uint64_t kUpsampleStream = 1ULL << 40;
// Peak resident memory of `tsynth optimise` measured with /usr/bin/time -v (guide
// lambda_circle_grey, defaults but for what is named): source colorado (648^2
// cells) 127 / 189 / 443 MB at 512^2 / 1024^2 / 2048^2 output cells; at 1024^2
// with --rotations --reflections 222 MB; source 2048^2 cells (30 m) 347 MB, with
// both (8 orientations) 639 MB; colorado with a stroke guide and --drain 206 MB.
// That is 81 bytes per output cell, 31 per source cell plus 10 per source cell
// and orientation, and 86 MB before any (program, libraries); --drain adds
// under 20 per output cell. Rounded up for a margin (the estimate is 1.3 to 1.4
// times each of these peaks):
constexpr double kOptimiseBaseBytes = 128.0e6;
constexpr double kBytesPerOutputCell = 100.0;
constexpr double kDrainBytesPerOutputCell = 25.0;
constexpr double kBytesPerSourceCell = 40.0;
constexpr double kBytesPerOrientedSourceCell = 14.0;
// Free land starts as copies of random source regions this many coarsest cells
// a side: a quarter of the smallest coarsest level, so several distinct pieces
// of the source's own structure meet in it.
constexpr int kFreeLandRegionCells = kMinCoarsestSide / 4;

void checkOptions(const OptimisationOptions& o)
{
  if (o.patchSize % 2 == 0 || o.patchSize < kMinPatchSize || o.patchSize > kMaxPatchSize)
  {
    throw Error("The patch size must be odd and between " + std::to_string(kMinPatchSize) +
      " and " + std::to_string(kMaxPatchSize) + " cells, not " + std::to_string(o.patchSize) + ".");
  }
  if (!(o.alpha >= 0.0 && o.alpha <= 1.0))
  {
    throw Error("The guide weight alpha must be between 0 and 1.");
  }
  if (o.iterationsPerLevel < 1 || o.patchMatchIterations < 1)
  {
    throw Error("The iterations per level and the PatchMatch iterations must be at least 1.");
  }
  if (o.levels < 0)
  {
    throw Error("The number of pyramid levels cannot be negative (0 chooses it).");
  }
}

bool sameCellSize(double a, double b)
{
  return std::abs(a - b) <= kCellSizeTolerance * std::max(std::abs(a), std::abs(b));
}

// The source on the guide's cell size (bilinear, nodata-aware), or as it is.
Heightfield sourceOnGuideCells(const Heightfield& source, const Heightfield& guide)
{
  if (sameCellSize(source.cellX, guide.cellX) && sameCellSize(source.cellY, guide.cellY))
  {
    return source;
  }
  return resampleToCellSize(source, guide.cellX, guide.cellY);
}

// The cells the source will have on the guide's cell size.
std::size_t sourceCellsOnGuide(const Heightfield& source, const Heightfield& guide)
{
  const double scale = (source.cellX / guide.cellX) * (source.cellY / guide.cellY);
  return static_cast<std::size_t>(static_cast<double>(source.size()) * scale);
}

int minSide(const Heightfield& hf, int level)
{
  return std::min(optim::levelSide(hf.width, level), optim::levelSide(hf.height, level));
}

bool levelsFit(const Heightfield& source, const Heightfield& guide, int levels, int patch)
{
  return minSide(guide, levels) >= patch &&
    minSide(source, levels) >= kMinSourcePatchesPerSide * patch;
}

int chooseLevels(const Heightfield& source, const Heightfield& guide, const OptimisationOptions& o)
{
  int levels = o.levels;
  if (levels == 0)
  {
    while (minSide(guide, levels + 1) >= kMinCoarsestSide &&
      minSide(source, levels + 1) >= kMinCoarsestSide)
    {
      ++levels;
    }
  }
  if (!levelsFit(source, guide, levels, o.patchSize))
  {
    throw Error("With " + std::to_string(levels) + " pyramid levels the coarsest guide (" +
      std::to_string(minSide(guide, levels)) + " cells) or source (" +
      std::to_string(minSide(source, levels)) + " cells) is smaller than the patch size " +
      std::to_string(o.patchSize) + " (guide) or twice it (source) allows: use fewer levels, a " +
      "smaller patch or larger inputs.");
  }
  return levels;
}

// The exponential schedule w_k = alpha (2^k - 1) / (2^L - 1): alpha at the
// coarsest level, about halved per finer level, 0 at the finest.
double guideWeight(double alpha, int k, int levels)
{
  if (levels == 0)
  {
    return 0.0;
  }
  return alpha * (std::ldexp(1.0, k) - 1.0) / (std::ldexp(1.0, levels) - 1.0);
}

// Progress in units of one PatchMatch iteration on one cell.
class Progress
{
public:
  Progress(const ProgressReport& callback, double total)
    : callback_(callback)
    , total_(total)
  {
  }
  void add(double work)
  {
    done_ += work;
    report(std::min(1.0, done_ / total_));
  }
  void report(double fraction) const { reportProgress(callback_, fraction, "optimise"); }

private:
  const ProgressReport& callback_;
  double total_;
  double done_ = 0.0;
};

// The guide of a level as the E-step reads it: heights (invalid cells get the
// level's valid mean, only used as the coarsest start) and its weight per cell
// (the confidence; 0 at invalid cells; empty: 1 everywhere).
struct GuideLevel
{
  int width = 0;
  int height = 0;
  std::vector<float> z;
  std::vector<float> weight;
};

GuideLevel guideLevel(const Heightfield& g, const Heightfield* confidence)
{
  GuideLevel out{ g.width, g.height, g.z, {} };
  const double mean = computeHeightRange(g).mean;
  if (g.hasMask() || confidence != nullptr)
  {
    out.weight.assign(g.size(), 1.0f);
  }
  for (std::size_t k = 0; k < out.z.size(); ++k)
  {
    const bool valid = g.isValid(k) && std::isfinite(out.z[k]);
    if (!valid)
    {
      out.z[k] = static_cast<float>(mean);
    }
    if (!out.weight.empty())
    {
      out.weight[k] = !valid ? 0.0f : confidence ? std::clamp(confidence->z[k], 0.0f, 1.0f) : 1.0f;
    }
  }
  return out;
}

double meanCost(const std::vector<float>& cost, int width, int height)
{
  double total = 0.0;
  for (int y = 0; y < height; ++y)
  {
    double row = 0.0;
    for (int x = 0; x < width; ++x)
    {
      row += cost[rowMajor(x, y, width)];
    }
    total += row;
  }
  return total / (static_cast<double>(width) * static_cast<double>(height));
}

Heightfield asHeightfield(const optim::TargetGrid& r, const Heightfield& like)
{
  Heightfield hf(r.width, r.height);
  hf.cellX = like.cellX;
  hf.cellY = like.cellY;
  hf.cellSizeKnown = like.cellSizeKnown;
  hf.sourceZUnit = like.sourceZUnit;
  hf.z = r.z;
  return hf;
}

// The state carried from level to level.
struct Run
{
  const OptimisationOptions& options;
  int levels;
  std::vector<Heightfield> sources;
  std::vector<Heightfield> guides;
  std::vector<Heightfield> confidences; // empty: the guide is trusted everywhere
  Progress progress;
  std::vector<optim::Match> map;

  GuideLevel guide(int k) const
  {
    const auto level = static_cast<std::size_t>(k);
    return guideLevel(guides[level], confidences.empty() ? nullptr : &confidences[level]);
  }
  std::vector<float> cost;
  optim::TargetGrid terrain;

  optim::PatchMatchSettings search(int k, int iteration, double cellsPerIteration)
  {
    optim::PatchMatchSettings s;
    s.iterations = options.patchMatchIterations;
    s.seed = options.seed;
    s.stream =
      static_cast<std::uint64_t>(k) * kStreamsPerLevel + static_cast<std::uint64_t>(iteration);
    s.afterIteration = [this, cellsPerIteration](int)
    {
      progress.add(cellsPerIteration);
      return true;
    };
    return s;
  }
};

double cellsOf(const Heightfield& hf)
{
  return static_cast<double>(hf.width) * static_cast<double>(hf.height);
}

double totalWork(const std::vector<Heightfield>& guides, const OptimisationOptions& o)
{
  double work = cellsOf(guides.back()) * o.patchMatchIterations; // the initial M-step
  for (const Heightfield& g : guides)
  {
    work += cellsOf(g) * o.patchMatchIterations * o.iterationsPerLevel;
  }
  return work;
}

// R^L = G^L and C^L from an M-step on it, starting from random matches; where
// the guide is less than fully trusted, R^L starts as the guide blended by its
// confidence with random regions of the source, which the M-step starts from.
void initialise(Run& run, const optim::SourceLevel& source)
{
  const int k = run.levels;
  const GuideLevel g = run.guide(k);
  const std::uint64_t stream = static_cast<std::uint64_t>(k) * kStreamsPerLevel + kUpsampleStream;
  run.terrain = { g.width, g.height, g.z };
  if (run.confidences.empty())
  {
    run.map = optim::randomMatches(source, g.width, g.height, run.options.seed, stream);
  }
  else
  {
    run.map = optim::randomRegions(
      source, g.width, g.height, kFreeLandRegionCells, run.options.seed, stream);
    optim::reconstruct(source, run.map, g.width, g.height, g.z, g.weight, 1.0, run.terrain.z);
  }
  optim::patchMatch(source,
    run.terrain,
    run.map,
    run.cost,
    run.search(k, run.options.iterationsPerLevel, static_cast<double>(g.width) * g.height));
}

OptimisationLevel optimiseLevel(Run& run, const optim::SourceLevel& source, int k)
{
  const auto t0 = Clock::now();
  const Heightfield& guideHf = run.guides[static_cast<std::size_t>(k)];
  const GuideLevel g = run.guide(k);
  const double w = guideWeight(run.options.alpha, k, run.levels);
  const double cells = static_cast<double>(g.width) * g.height;
  OptimisationLevel report;
  report.level = k;
  report.width = g.width;
  report.height = g.height;
  run.terrain.width = g.width;
  run.terrain.height = g.height;
  for (int it = 0; it < run.options.iterationsPerLevel; ++it)
  {
    optim::reconstruct(source, run.map, g.width, g.height, g.z, g.weight, w, run.terrain.z);
    if (run.options.removePits && k > 0)
    {
      const Heightfield level = asHeightfield(run.terrain, guideHf);
      report.pitsBeforeRemoval = countPits(level);
      run.terrain.z = removePits(level, run.options.pitRemoval).dem.z;
    }
    optim::patchMatch(source, run.terrain, run.map, run.cost, run.search(k, it, cells));
    report.energy.push_back(meanCost(run.cost, g.width, g.height));
  }
  if (k > 0)
  {
    report.pitsAfter = countPits(asHeightfield(run.terrain, guideHf));
    if (!(run.options.removePits))
    {
      report.pitsBeforeRemoval = report.pitsAfter;
    }
  }
  else
  {
    optim::reconstruct(source, run.map, g.width, g.height, g.z, g.weight, w, run.terrain.z);
    const Heightfield level = asHeightfield(run.terrain, guideHf);
    report.pitsBeforeRemoval = report.pitsAfter = countPits(level);
  }
  report.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return report;
}

// The confidence as a grid of the guide's shape, through the same pyramid.
std::vector<Heightfield> confidencePyramid(const Heightfield& guide,
  const std::vector<float>& confidence,
  int levels)
{
  if (confidence.empty())
  {
    return {};
  }
  if (confidence.size() != guide.size())
  {
    throw Error("The guide's confidence has " + std::to_string(confidence.size()) +
      " cells but the guide has " + std::to_string(guide.size()) + ".");
  }
  Heightfield c = guide;
  c.z = confidence;
  c.valid.clear();
  return optim::gaussianPyramid(c, levels);
}

void checkInputs(const Heightfield& source, const Heightfield& guide)
{
  checkOptimisationSource(source);
  if (guide.size() == 0 || guide.validCount() == 0)
  {
    throw Error("The guide has no valid cell: give a guide with height data.");
  }
}

} // namespace

double optimisationMemoryEstimate(int width,
  int height,
  std::size_t sourceCells,
  const OptimisationOptions& o)
{
  const double orientations = (o.rotations ? 4.0 : 1.0) * (o.reflections ? 2.0 : 1.0);
  const double output = static_cast<double>(width) * static_cast<double>(height);
  const double source = static_cast<double>(sourceCells);
  return kOptimiseBaseBytes +
    output * (kBytesPerOutputCell + (o.drainOutput ? kDrainBytesPerOutputCell : 0.0)) +
    source * (kBytesPerSourceCell + orientations * kBytesPerOrientedSourceCell);
}

void checkOptimisationMemory(int width,
  int height,
  std::size_t sourceCells,
  const OptimisationOptions& o)
{
  checkMemoryBudget(optimisationMemoryEstimate(width, height, sourceCells, o),
    o.memoryBudget,
    "This optimisation of " + std::to_string(width) + " x " + std::to_string(height) +
      " cells from a source of " + std::to_string(sourceCells) + " cells",
    "give a smaller " + o.sizeOption + " or source, drop rotations and reflections",
    o.memoryOption);
}

void checkOptimisationSource(const Heightfield& source)
{
  if (source.size() == 0 || source.validCount() == 0)
  {
    throw Error("The source DEM has no valid cell: give a source with height data.");
  }
  const HeightRange relief = computeHeightRange(source);
  if (relief.max == relief.min)
  {
    throw Error("The source DEM is flat: it has no relief to copy; give a real DEM as the source.");
  }
}

OptimisationResult optimiseTerrain(const Heightfield& source,
  const Heightfield& guide,
  const OptimisationOptions& options)
{
  checkOptions(options);
  checkInputs(source, guide);
  checkOptimisationMemory(guide.width, guide.height, sourceCellsOnGuide(source, guide), options);
  const Heightfield resampled = sourceOnGuideCells(source, guide);
  checkInputs(resampled, guide);
  const int levels = chooseLevels(resampled, guide, options);
  std::vector<Heightfield> guides = optim::gaussianPyramid(guide, levels);
  Run run{ options,
    levels,
    optim::gaussianPyramid(resampled, levels),
    guides,
    confidencePyramid(guide, options.guideConfidence, levels),
    Progress(options.progress, totalWork(guides, options)),
    {},
    {},
    {} };
  run.progress.report(0.0);

  OptimisationResult result;
  optim::SourceLevel coarser;
  for (int k = levels; k >= 0; --k)
  {
    const auto t0 = Clock::now();
    optim::SourceLevel level = optim::makeSourceLevel(run.sources[static_cast<std::size_t>(k)],
      options.patchSize,
      options.rotations,
      options.reflections,
      k);
    if (k == levels)
    {
      initialise(run, level);
    }
    else
    {
      const Heightfield& g = run.guides[static_cast<std::size_t>(k)];
      run.map = optim::upsampleMatches(run.map,
        run.terrain.width,
        coarser,
        level,
        g.width,
        g.height,
        options.seed,
        static_cast<std::uint64_t>(k) * kStreamsPerLevel + kUpsampleStream);
    }
    const double setup = std::chrono::duration<double>(Clock::now() - t0).count();
    result.levels.push_back(optimiseLevel(run, level, k));
    result.levels.back().seconds += setup;
    coarser = std::move(level);
  }
  result.terrain = asHeightfield(run.terrain, guide);
  result.terrain.georef = guide.georef;
  if (options.drainOutput)
  {
    MultiscalePitRemovalOptions d;
    d.pitRemoval = options.pitRemoval;
    d.coarsestFactor = 1 << levels; // the coarsest level's cells
    result.pitsBeforeDraining = removePitsMultiscale(result.terrain, d).pitsBefore;
    result.levels.back().pitsAfter = countPits(result.terrain);
  }
  run.progress.report(1.0);
  return result;
}

const std::vector<OptionRow>& optimisationOptionRows()
{
  static const std::vector<OptionRow> rows = []
  {
    const OptimisationOptions d;
    using T = OptionType;
    const std::optional<PitRemovalMethod> pits =
      d.removePits ? std::optional<PitRemovalMethod>(d.pitRemoval.method) : std::nullopt;
    return std::vector<OptionRow>{
      numberRow("PatchSize", "--patch", T::Integer, d.patchSize, kMinPatchSize, kMaxPatchSize),
      numberRow("Levels", "--levels", T::Integer, d.levels, 0, kMaxOptimisationLevels),
      numberRow("Alpha", "--alpha", T::Real, d.alpha, 0.0, 1.0),
      numberRow("IterationsPerLevel",
        "--iterations",
        T::Integer,
        d.iterationsPerLevel,
        1,
        kMaxOptimisationIterations),
      numberRow("SearchIterations",
        "--search-iterations",
        T::Integer,
        d.patchMatchIterations,
        1,
        kMaxOptimisationIterations),
      switchRow("Rotations", "--rotations", d.rotations),
      switchRow("Reflections", "--reflections", d.reflections),
      choiceRow(
        "PitRemoval", "--pits", offOrMethodValue(pits), offOrMethodChoices(), offOrMethodLabels()),
      switchRow("DrainOutput", "--drain", d.drainOutput),
      numberRow("Seed", "--seed", T::Integer, static_cast<double>(d.seed), 0.0, kUnbounded),
      numberRow("OutputSize", "--size", T::Integer, 0, 0, kMaxOutputSide),
      memoryBudgetRow(d.memoryBudget),
    };
  }();
  return rows;
}

} // namespace tsynth
