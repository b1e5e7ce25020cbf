// tsynth evaluate: quality figures of a terrain against its exemplars and
// sketch, beside two trivial baselines for scale.
#include "Commands.h"

#include "CliSupport.h"
#include "CommandLine.h"
#include "QualityFigures.h"
#include "TerrainFileIO.h"

#include "Core/PatchSize.h"
#include "Core/Resample.h"
#include "Features/Sketch.h"
#include "Metrics/LandformMetrics.h"
#include "Metrics/Legibility.h"
#include "Metrics/TerrainMetrics.h"
#include "Synthesis/Setup.h"
#include "Synthesis/SynthesisFigures.h"

#include <nlohmann/json.hpp>

#include <iostream>
#include <optional>

namespace tsynth::cli
{
namespace
{

const char* const kEvaluateHelp =
  R"(Usage: tsynth evaluate TERRAIN --exemplar DEM [--exemplar DEM ...] [--sketch SKETCH] [--json]

Quality figures of a terrain against its exemplars (pooled: each counts by its area) and
sketch, with two trivial baselines for scale, made from the first exemplar (the exemplar
tiled; random exemplar patches pasted without blending):
  fidelity   share of samples along each sketched ridge (valley) where the terrain has a crest
             (trough) across the line: the extreme within 2 cells beats both sides at 8 cells
  seam       99.9th percentile of |Laplacian| over that of the exemplar (1 = as smooth)
  slope      Wasserstein-1 distance of slope-angle distributions over the exemplar's mean slope
  pits       strict local minima per 1000 cells
and, with a sketch, at the scale of the landforms (a patch across the lines):
  prominence median height of the sketched ridges over the land a patch away on both sides,
             and depth of the valleys below it, in metres and as a ratio to the same figure
             on the exemplars' own ridges and valleys (1 = like the exemplars' own)
  order      chance that a point on a sketched ridge is higher than one on a sketched valley
  drainage   share of the valleys' length along which D8 flow (after filling pits) gathers
             the water of their flanks; descent: share of floor steps a quarter patch apart
             that go down towards the outlet
  shedding   share of the ridges' length from which water runs off to the sides
A figure that does not apply (no ridge sketched, a flat exemplar) is shown as "-" (null in JSON).

  --patch N   landform scale in cells (default %PATCH%, the synthesis default)
)";

// The synthesis' default patch: the random-patch baseline's patch, and the
// smallest sketch evaluate accepts.
constexpr int kEvaluationPatch = kDefaultSynthesisPatch;
// The landform scales --patch accepts, as `tsynth features` takes patches.
constexpr int kMinLandformScale = 8;
constexpr int kMaxLandformScale = 4096;

// The sketch as the synthesis reads it, on the terrain's grid: its features,
// and for a DEM used as the target its heights.
struct SketchOnTerrain
{
  FeatureGraph graph;
  bool demTarget = false;
  Heightfield heights; // the DEM target resampled onto the terrain's grid
};

SketchOnTerrain sketchOnTerrain(const std::string& path, const Heightfield& terrain)
{
  std::vector<std::string> warnings;
  const SketchInput input = readSketchInput(path, warnings);
  printWarnings(warnings);
  // The synthesis' checks of a sketch for a grid of the terrain's size (poly-lines
  // outside it or in the wrong unit are refused), then its analysis.
  GridRequest request;
  request.width = terrain.width;
  request.height = terrain.height;
  request.cellX = terrain.cellX;
  request.cellY = terrain.cellY;
  SetupOptionNames names;
  names.size = "the terrain's size";
  names.cell = "cell size";
  const OutputGrid grid =
    outputGrid(sketchExtent(input), request, terrain.cellX, terrain.cellY, 1, names);
  const AnalysedSketch s = analyseSketch(input, grid, kEvaluationPatch);
  printWarnings(s.warnings);
  SketchOnTerrain out;
  out.graph = scaleGraph(
    s.graph, s.width, s.height, terrain.width, terrain.height, terrain.cellX, terrain.cellY);
  out.demTarget = s.hasHeights && s.kind == "DEM";
  if (out.demTarget)
  {
    out.heights = resampleNearest(s.heights, terrain.width, terrain.height);
  }
  return out;
}

// Everything `tsynth evaluate` was asked to do, checked.
struct EvaluateArguments
{
  std::string terrain;
  std::vector<std::string> exemplars;
  std::optional<std::string> sketch;
  bool json = false;
  int patch = kEvaluationPatch; // the landform scale
};

EvaluateArguments parseEvaluateArguments(std::vector<std::string> args)
{
  CommandLine cl(std::move(args));
  EvaluateArguments a;
  a.exemplars = cl.takeAll("--exemplar");
  a.sketch = cl.take("--sketch");
  a.json = cl.takeFlag("--json");
  const auto patch = cl.takeNumber("--patch");
  const auto rest = cl.positionals();
  if (patch && !(*patch >= kMinLandformScale && *patch <= kMaxLandformScale))
  {
    throw UsageError("--patch expects a landform scale from " + std::to_string(kMinLandformScale) +
      " to " + std::to_string(kMaxLandformScale) + " cells.");
  }
  if (rest.size() != 1)
  {
    throw UsageError("tsynth evaluate needs one terrain file.");
  }
  if (a.exemplars.empty())
  {
    throw UsageError("tsynth evaluate needs an --exemplar DEM to compare with.");
  }
  a.terrain = rest[0];
  a.patch = static_cast<int>(patch.value_or(kEvaluationPatch));
  return a;
}

// The figures of one terrain; those that need a sketch (or a DEM target) stay
// empty without one.
struct TerrainFigures
{
  TerrainEvaluation quality;
  LandformMeasures landforms;
  Legibility legibility;
  std::vector<BandCorrelation> correlation;
};

// The terrain and the two baselines made from the first exemplar, measured.
struct Evaluation
{
  TerrainFigures terrain;
  TerrainFigures tiled;  // no legibility nor correlation: the tiled exemplar follows no sketch
  TerrainFigures random; // random exemplar patches pasted without blending
};

enum class Against
{
  AllExemplars,
  FirstExemplar
};

// Measures terrains against the exemplars (pooled) and the sketch if any.
class Evaluator
{
public:
  Evaluator(const EvaluateArguments& a, const Heightfield& terrain)
    : patch_(a.patch)
  {
    for (const std::string& path : a.exemplars)
    {
      exemplars_.push_back(readTerrainFile(path));
    }
    for (const Heightfield& x : exemplars_)
    {
      pooled_.push_back(&x);
      ownLines_.push_back(ownFeatureLines(x)); // landform figures compare with these
    }
    for (const FeatureGraph& g : ownLines_)
    {
      linePointers_.push_back(&g);
    }
    if (a.sketch)
    {
      drawn_ = sketchOnTerrain(*a.sketch, terrain);
      LegibilityOptions go;
      go.loneHalfWidth = kLoneHalfWidthInPatches * a.patch;
      land_.emplace(pooled_);
      meter_.emplace(drawn_.graph, *land_, go);
    }
  }

  Evaluator(const Evaluator&) = delete; // holds pointers into itself
  Evaluator& operator=(const Evaluator&) = delete;

  const Heightfield& firstExemplar() const { return exemplars_.front(); }
  bool hasSketch() const { return meter_.has_value(); }
  bool hasDemTarget() const { return drawn_.demTarget; }

  // The figures of `t` against `against` (the terrain against every exemplar, its
  // baselines against the first); legibility and target correlation only if `followsSketch`.
  TerrainFigures measure(const Heightfield& t, Against against, bool followsSketch) const
  {
    TerrainFigures f;
    const FeatureGraph* sketch = hasSketch() ? &drawn_.graph : nullptr;
    f.quality = against == Against::AllExemplars ? evaluateTerrain(t, pooled_, sketch)
                                                 : evaluateTerrain(t, exemplars_.front(), sketch);
    if (hasSketch())
    {
      LandformOptions lo;
      lo.patchSize = patch_;
      f.landforms = evaluateLandforms(t, drawn_.graph, pooled_, linePointers_, lo);
    }
    if (hasSketch() && followsSketch)
    {
      f.legibility = meter_->measure(t);
    }
    if (drawn_.demTarget && followsSketch)
    {
      f.correlation = bandPassCorrelation(t, drawn_.heights, defaultCorrelationScales());
    }
    return f;
  }

private:
  int patch_;
  std::vector<Heightfield> exemplars_;
  std::vector<const Heightfield*> pooled_;
  std::vector<FeatureGraph> ownLines_;
  std::vector<const FeatureGraph*> linePointers_;
  SketchOnTerrain drawn_;
  std::optional<LandRelief> land_; // the meter keeps a reference
  std::optional<LegibilityMeter> meter_;
};

Evaluation evaluateWithBaselines(const EvaluateArguments& a)
{
  const Heightfield terrain = readTerrainFile(a.terrain);
  const Evaluator evaluator(a, terrain);
  const Heightfield& exemplar = evaluator.firstExemplar();
  Evaluation e;
  e.terrain = evaluator.measure(terrain, Against::AllExemplars, true);
  // The tiled exemplar makes no attempt at the sketch: its landforms, not its legibility.
  e.tiled = evaluator.measure(
    tiledBaseline(exemplar, terrain.width, terrain.height), Against::FirstExemplar, false);
  e.random = evaluator.measure(
    randomPatchBaseline(exemplar, terrain.width, terrain.height, kEvaluationPatch, 1),
    Against::FirstExemplar,
    true);
  return e;
}

void printFigures(const EvaluateArguments& a, const Evaluation& e)
{
  const char* name = a.terrain.c_str();
  printEvaluation(name, e.terrain.quality);
  printEvaluation("baseline: tiled", e.tiled.quality);
  printEvaluation("baseline: random", e.random.quality);
  if (a.sketch)
  {
    printLandforms(name, e.terrain.landforms);
    printLandforms("baseline: tiled", e.tiled.landforms);
    printLandforms("baseline: random", e.random.landforms);
    printLegibility(name, e.terrain.legibility);
    printLegibility("baseline: random", e.random.legibility);
  }
  if (!e.terrain.correlation.empty())
  {
    printCorrelation(name, e.terrain.correlation);
    printCorrelation("baseline: random", e.random.correlation);
  }
}

nlohmann::json figuresJson(const EvaluateArguments& a, const Evaluation& e)
{
  nlohmann::json figures = { { "terrain", evaluationJson(e.terrain.quality) },
    { "tiled_exemplar", evaluationJson(e.tiled.quality) },
    { "random_patches", evaluationJson(e.random.quality) } };
  if (a.sketch)
  {
    figures["terrain"]["landforms"] = landformJson(e.terrain.landforms);
    figures["tiled_exemplar"]["landforms"] = landformJson(e.tiled.landforms);
    figures["random_patches"]["landforms"] = landformJson(e.random.landforms);
    figures["terrain"]["legibility"] = legibilityJson(e.terrain.legibility);
    figures["random_patches"]["legibility"] = legibilityJson(e.random.legibility);
  }
  if (!e.terrain.correlation.empty())
  {
    figures["terrain"]["target_correlation"] = correlationJson(e.terrain.correlation);
    figures["random_patches"]["target_correlation"] = correlationJson(e.random.correlation);
  }
  return figures;
}

} // namespace

int runEvaluate(std::vector<std::string> args)
{
  if (wantsHelp(args))
  {
    std::cout << withPatchDefault(kEvaluateHelp);
    return 0;
  }
  const EvaluateArguments a = parseEvaluateArguments(std::move(args));
  const Evaluation e = evaluateWithBaselines(a);
  if (a.json)
  {
    std::cout << figuresJson(a, e).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace)
              << "\n";
  }
  else
  {
    printFigures(a, e);
  }
  return 0;
}

} // namespace tsynth::cli
