#include "SynthesisRequest.h"

#include "../Core/Memory.h"
#include "../Core/PatchSize.h"
#include "ExemplarCache.h"
#include "TileRecord.h"
#include "Tiling.h"

#include <utility>
#include <variant>

namespace tsynth
{

int patchSizeFor(int requested, const SketchInput& sketch)
{
  if (requested != kAutomaticPatch)
  {
    return requested;
  }
  return std::holds_alternative<Heightfield>(sketch) ? kDefaultDemTargetPatch
                                                     : kDefaultSynthesisPatch;
}

void resolvePatchSize(SynthesisRequest& request,
  const SketchInput& sketch,
  const SetupOptionNames& names)
{
  SynthesisOptions& o = request.options;
  o.patchSize = patchSizeFor(o.patchSize, sketch);
  checkPatchSize(o.patchSize, names.patch);
  if (o.tileSize > 0)
  {
    checkTileSize(o.tileSize, o.patchSize);
  }
}

SetupInputs setupInputs(const SynthesisRequest& request,
  std::vector<Heightfield> exemplars,
  std::vector<std::string> exemplarNames,
  SketchInput sketch,
  SetupOptionNames optionNames)
{
  SetupInputs in;
  in.exemplars = std::move(exemplars);
  in.exemplarNames = std::move(exemplarNames);
  in.sketch = std::move(sketch);
  in.grid = request.grid;
  in.patchSize = request.options.patchSize;
  in.seed = request.options.seed;
  in.landformRelief = request.landformRelief;
  in.memoryBudget = request.memoryBudgetGB * kBytesPerGB;
  in.matcherBackend = request.options.backend;
  in.cacheDirectory = !request.useExemplarCache ? std::string()
    : request.cacheDirectory.empty()            ? defaultExemplarCacheDirectory()
                                                : request.cacheDirectory;
  in.recordedTileSize = request.options.keepRecord ? request.options.tileSize : 0;
  in.previousRecordBytes =
    request.options.previous != nullptr ? tileRecordBytes(*request.options.previous) : 0.0;
  in.names = std::move(optionNames);
  return in;
}

namespace
{

std::vector<OptionRow> makeRows()
{
  const SynthesisRequest d;
  const SynthesisOptions& o = d.options;
  using T = OptionType;
  return {
    numberRow("PatchSize", "--patch", T::Integer, o.patchSize, kAutomaticPatch, kMaxSynthesisPatch),
    numberRow("OutputSize", "--size", T::Integer, d.grid.width, 0, kMaxOutputSide),
    numberRow("CellSize", "--cell", T::Real, d.grid.cellX, 0.0, kUnbounded),
    numberRow("Seed", "--seed", T::Integer, static_cast<double>(o.seed), 0.0, kUnbounded),
    numberRow("LandformRelief",
      "--landform-relief",
      T::Real,
      d.landformRelief,
      kMinLandformRelief,
      kMaxLandformRelief),
    memoryBudgetRow(d.memoryBudgetGB * kBytesPerGB),
    choiceRow("Backend",
      "--backend",
      static_cast<int>(o.backend),
      choicesOf(kBackendWords),
      { "Auto", "OpenCL", "CPU" }),
    choiceRow("MergeMode",
      "--merge",
      static_cast<int>(o.merge),
      choicesOf(kMergeModeWords),
      optionRow(mergeOptionRows(), "Mode").labels),
    choiceRow("FillOrder",
      "--fill",
      static_cast<int>(o.fill),
      choicesOf(kFillOrderWords),
      { "Best-first", "Concentric" }),
    choiceRow("Drainage",
      "--drainage",
      offOrMethodValue(o.drainage),
      offOrMethodChoices(),
      offOrMethodLabels()),
    switchRow("VerticalOffset", "--no-vertical-offset", o.verticalOffset),
    numberRow(
      "Repetition", "--repetition", T::Real, o.repetitionPenalty, 0.0, kMaxRepetitionPenalty),
    numberRow("TileSize", "--tile-size", T::Integer, o.tileSize, 0.0, kUnbounded),
    numberRow("PlacementLimit",
      "--placements",
      T::Integer,
      o.placementLimit == kAllPlacements ? kAllPlacementsNumber : 0,
      kAllPlacementsNumber,
      kUnbounded),
    switchRow("UseExemplarCache", "--no-cache", d.useExemplarCache),
  };
}

} // namespace

const std::vector<OptionRow>& synthesisOptionRows()
{
  static const std::vector<OptionRow> rows = makeRows();
  return rows;
}

const OptionRow& synthesisOption(const std::string& property)
{
  return optionRow(synthesisOptionRows(), property);
}

} // namespace tsynth
