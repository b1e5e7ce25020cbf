// tsynth synth: the synthesis pipeline, from files read to terrain, report and debug images.
#include "Commands.h"

#include "CliSupport.h"
#include "CommandLine.h"
#include "FeatureGraphConversion.h"
#include "QualityFigures.h"
#include "TerrainFileIO.h"

#include "Analysis/Hillshade.h"
#include "Analysis/ReliefImage.h"
#include "Core/Error.h"
#include "Core/FileRoles.h"
#include "Core/HeightfieldIO.h"
#include "Core/Memory.h"
#include "Core/OutputFile.h"
#include "Core/PatchSize.h"
#include "Core/Resample.h"
#include "Features/Sketch.h"
#include "Metrics/LandformMetrics.h"
#include "Metrics/Legibility.h"
#include "Metrics/TerrainMetrics.h"
#include "Synthesis/Preview.h"
#include "Synthesis/Regions.h"
#include "Synthesis/Setup.h"
#include "Synthesis/SynthesisFigures.h"
#include "Synthesis/SynthesisRequest.h"
#include "Synthesis/Synthesiser.h"
#include "Synthesis/TileRecord.h"
#include "Synthesis/Tiling.h"

#include <nlohmann/json.hpp>
#include <vtkNew.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <limits>
#include <optional>
#include <sstream>
#include <unistd.h>

namespace tsynth::cli
{
namespace
{

const char* const kSynthHelp =
  R"(Usage: tsynth synth --exemplar DEM [--exemplar DEM ...] --sketch SKETCH -o OUT [options]

Synthesises a terrain that follows the sketch and looks like the exemplars: feature patches
placed along the sketch's ridges and valleys (breadth-first), the rest filled best-first, each
patch chosen among the matcher's best by its graph-cut seam and merged in the gradient domain.

The sketch is a stroke map (RGB: red ridges, blue valleys), a grey sketch map (brighter is
higher), a real DEM used as the target, or poly-lines: a .vtp with a FeatureType cell array
(+1 ridge, -1 valley) and optional Elevation point array (height constraints), in metres in
the raster frame (lower-left cell centre at (0, 0), x east, y north), as `tsynth features`
writes them: its output works directly as a sketch of the same DEM.

  --exemplar DEM         a DEM to copy terrain from (repeat for several)
  --sketch SKETCH        the sketch
  -o, --output OUT       .tif (GeoTIFF float32), .png (16-bit + sidecar) or .vti
  --size WxH             output size in cells (default: the sketch's pixels; for poly-lines
                         the grid they were found on, else half a patch past their reach)
  --cell M               output cell size in metres (default: the first exemplar's)
  --patch N              patch size in cells, a multiple of 4 from %PATCHMIN% to %PATCHMAX% (default
                         %PATCH%, or %DEMPATCH% for a DEM target, whose ridges and valleys lie
                         closer than %PATCH%-cell patches follow)
  --backend B            %WORDS:Backend%: same result, different speed (default
                         %DEFAULT:Backend%: OpenCL on a GPU or accelerator, else the CPU)
  --merge M              %WORDS:MergeMode% (default %DEFAULT:MergeMode%)
  --fill F               %WORDS:FillOrder% (default %DEFAULT:FillOrder%)
  --drainage M           %WORDS:Drainage% (default %DEFAULT:Drainage%): make every cell
                         drain at the end. Breach cuts valleys out of closed basins, fill
                         raises them to lakes, hybrid does either (tsynth pits), on blocks
                         of a quarter patch down to 2 cells so the changes are broad and
                         seams stay hidden; the last few-cell pits are filled
  --seed N               another seed gives another terrain; the same seed the same terrain
  --preview PREVIEW      first write a quick coarse look at the same terrain: cells 4 times
                         coarser a side (twice for patches under 64), patches as many times
                         smaller: the same landforms in the same places, less detail. Needs
                         a patch of at least 32. Stopped (Ctrl-C) after it, the run leaves
                         the preview complete
  --report FILE.json     per-stage times, counts, costs and quality figures (with --tile-size,
                         each tile's time in each pass: "tiles")
  --debug-dir DIR        target field, feature trees, patch ids and seams as files
  --regions LABELS       style regions: a single-band image of labels over the output (resized to
                         it); label L is served by exemplar number L (counting from 0) unless
                         --region L=E1,E2 says otherwise (repeatable)
  --no-vertical-offset   place patches at their own heights (default: fitted to the overlap)
  --tile-size N          synthesise in square tiles of N cells (at least two patches), each
                         with a halo of one patch, in an order fixed by the tile grid, then
                         finish the whole terrain at once: the placement's memory follows the
                         tile, and the same tile grid gives the same terrain whoever runs it
                         (default: one piece)
  --keep-tiles           with --tile-size: also write OUT.tiles (OUT with its extension
                         replaced), the record of every tile's placement, for --previous
  --previous OLD         re-synthesise an edit of OLD's sketch: each tile whose placement
                         would read the same inputs as in OLD's run (its part of the
                         sketch's target, the cells the tiles before it left, its feature
                         sites) is taken from OLD.tiles instead of placed again, so only the
                         tiles an edit reaches are; the terrain is the same bits as a full
                         synthesis of the edited sketch. The tile size, patch and seed default
                         to OLD's; exemplars, size, cells and placement options must be OLD's.
                         Writes OUT.tiles for the next edit
  --placements N         stop after N placements and write the terrain as those patches made
                         it, unfinished (nodata where no patch is yet): the whole synthesis'
                         first N, to step through it; one piece only (default: all, finished)
  --repetition P         seam-cost penalty for reusing a nearby source, %RANGE:Repetition%
                         (default %DEFAULT:Repetition%; 0 = off)
  --landform-relief F    sketched ridges and valleys get F times the relief they are given
                         to stand out of the exemplars' own land (the exemplars' major ones',
                         raised on rugged land; default %DEFAULT:LandformRelief%;
                         %RANGE:LandformRelief%: above 1 bolder, below softer)
  --max-memory GB        refuse a synthesis estimated to need more (default: 80% of the
                         machine's memory)
  --cache DIR            keep what is computed from the exemplars alone (their ridges and
                         valleys, landform statistics, candidate pool) in DIR, keyed by
                         their content, so the next run with the same exemplars, cell size
                         and patch size starts sooner (default: $TSYNTH_CACHE_DIR, else
                         $XDG_CACHE_HOME/terrainsynthesis, else ~/.cache/terrainsynthesis)
  --no-cache             compute everything afresh and keep nothing
  --no-progress          no progress bar on the terminal
)";

// Each tile's place and colour, its pass and how long it took (wall clock and CPU), in the
// order it was placed: the figures Testing/Benchmarks/tile_cost_model.py models ranks from.
nlohmann::json tileTimingsJson(const std::vector<TileTiming>& tiles)
{
  nlohmann::json out = nlohmann::json::array();
  for (const TileTiming& t : tiles)
  {
    out.push_back({ { "column", t.column },
      { "row", t.row },
      { "colour", t.colour },
      { "pass", t.fill ? "fill" : "features" },
      { "seconds", t.seconds },
      { "cpu_seconds", t.cpuSeconds },
      { "taken_over", t.takenOver } });
  }
  return out;
}

// Everything `tsynth synth` was asked to do, checked.
struct SynthArguments
{
  std::vector<std::string> exemplars;
  std::string sketch;
  std::string output;
  std::optional<std::string> report;
  std::optional<std::string> preview; // written first: the quick coarse look (Preview.h)
  std::optional<std::string> debugDir;
  std::optional<std::string> regions;
  std::vector<std::string> regionMaps;
  SynthesisRequest request; // every option of the synthesis itself
  bool progress = true;
  // --keep-tiles: write OUT.tiles, the tiles' record (TileRecord.h); --previous
  // OLD: take unchanged tiles from OLD.tiles (and write OUT.tiles).
  bool keepTiles = false;
  std::optional<std::string> previous;
};

// The files --debug-dir writes (writeDebug), for the check that they replace no input.
std::vector<std::string> debugFileNames(std::size_t exemplarCount)
{
  std::vector<std::string> names = { "target.tif",
    "target.png",
    "patches.tif",
    "target-confidence.tif",
    "sketch-features.vtp",
    "implied-features.vtp",
    "patch-id.tif",
    "seams.tif" };
  for (std::size_t e = 0; e < exemplarCount; ++e)
  {
    names.push_back("exemplar" + std::to_string(e) + "-features.vtp");
  }
  return names;
}

void checkPaths(const SynthArguments& a)
{
  if (a.exemplars.empty())
  {
    throw UsageError("tsynth synth needs at least one --exemplar DEM.");
  }
  if (a.sketch.empty())
  {
    throw UsageError("tsynth synth needs a --sketch.");
  }
  if (a.output.empty())
  {
    throw UsageError("tsynth synth needs an output file: -o OUT.tif|.png|.vti.");
  }
  if (!isVtiPath(a.output) && !isHeightfieldWriteExtension(a.output))
  {
    throw UsageError("The output must end in .tif, .png or .vti, not " + a.output + ".");
  }
  if (a.preview && !isVtiPath(*a.preview) && !isHeightfieldWriteExtension(*a.preview))
  {
    throw UsageError("--preview must end in .tif, .png or .vti, not " + *a.preview + ".");
  }
  if (a.report && !hasExtension(*a.report, ".json"))
  {
    throw UsageError("--report expects a .json file.");
  }
  if (!a.regions && !a.regionMaps.empty())
  {
    throw UsageError("--region needs --regions LABELS.");
  }
  if (a.debugDir)
  {
    requireCreatableFolder(*a.debugDir);
  }
  // Every output is written after the run: refuse unwritable places, and outputs that would
  // replace an input or each other, before it.
  FileRoles files;
  for (const std::string& exemplar : a.exemplars)
  {
    files.input(exemplar, "--exemplar");
  }
  files.input(a.sketch, "--sketch");
  if (a.regions)
  {
    files.input(*a.regions, "--regions");
  }
  files.output(a.output, "-o");
  if (a.previous)
  {
    files.input(recordPathOf(*a.previous), "--previous's tile record", false);
  }
  if (a.keepTiles)
  {
    files.output(recordPathOf(a.output), "the tile record of -o", FileRoles::Content::Other);
  }
  if (a.preview)
  {
    files.output(*a.preview, "--preview");
  }
  if (a.report)
  {
    files.output(*a.report, "--report");
  }
  if (a.debugDir && std::filesystem::is_directory(*a.debugDir))
  {
    for (const std::string& name : debugFileNames(a.exemplars.size()))
    {
      // target.png is the target's picture, written without a sidecar.
      const bool picture = hasExtension(name, ".png");
      files.output(*a.debugDir + "/" + name,
        "--debug-dir",
        picture ? FileRoles::Content::Other : FileRoles::Content::Heights);
    }
  }
  files.check();
}

// --patch, --backend, --merge, --fill, --seed, --drainage, --no-vertical-offset, --tile-size,
// --placements, --repetition.
void takeSynthesisOptions(CommandLine& cl, SynthesisOptions& o)
{
  if (const auto patch = takeRowNumber(cl, synthesisOption("PatchSize")))
  {
    o.patchSize = static_cast<int>(*patch);
    try
    {
      checkPatchSize(o.patchSize, "--patch");
    }
    catch (const Error& e)
    {
      throw UsageError(e.what());
    }
  }
  if (const auto backend = takeRowChoice(cl, synthesisOption("Backend")))
  {
    o.backend = static_cast<Backend>(*backend);
  }
  if (const auto merge = takeRowChoice(cl, synthesisOption("MergeMode")))
  {
    o.merge = static_cast<MergeMode>(*merge);
  }
  if (const auto fill = takeRowChoice(cl, synthesisOption("FillOrder")))
  {
    o.fill = static_cast<FillOrder>(*fill);
  }
  if (const auto seed = cl.take("--seed"))
  {
    o.seed = parseSeed(*seed);
  }
  if (const auto drainage = takeRowChoice(cl, synthesisOption("Drainage")))
  {
    o.drainage = offOrMethod(*drainage);
  }
  o.verticalOffset = !cl.takeFlag("--no-vertical-offset");
  if (const auto tile = takeCount(cl, "--tile-size", 1, kMaxOutputSide))
  {
    try
    {
      if (o.patchSize != kAutomaticPatch) // else once the sketch is read (resolvePatchSize)
      {
        checkTileSize(*tile, o.patchSize);
      }
    }
    catch (const Error& e)
    {
      throw UsageError(std::string(e.what()) + " (--tile-size)");
    }
    o.tileSize = *tile;
  }
  if (const auto repetition = takeRowNumber(cl, synthesisOption("Repetition")))
  {
    o.repetitionPenalty = *repetition;
  }
  if (const auto placements = takeRowNumber(cl, synthesisOption("PlacementLimit")))
  {
    // More placements than an int counts are all of them.
    o.placementLimit = *placements >= static_cast<double>(std::numeric_limits<int>::max())
      ? kAllPlacements
      : placementLimitOf(static_cast<int>(*placements));
  }
}

// --size, --cell, --landform-relief and --max-memory.
void takeGridOptions(CommandLine& cl, SynthesisRequest& r)
{
  if (const auto size = cl.take("--size"))
  {
    r.grid = parseSize(*size, r.grid);
  }
  if (const auto cell = cl.takeNumber("--cell")) // the filter's 0 is the option left out
  {
    if (!(*cell > 0.0) || !std::isfinite(*cell))
    {
      throw UsageError("--cell expects a positive number of metres.");
    }
    r.grid.cellX = r.grid.cellY = *cell;
  }
  if (const auto relief = takeRowNumber(cl, synthesisOption("LandformRelief")))
  {
    r.landformRelief = *relief;
  }
  r.memoryBudgetGB = takeMemoryBudget(cl) / kBytesPerGB;
}

// --cache DIR and --no-cache.
void takeCacheOptions(CommandLine& cl, SynthesisRequest& r)
{
  const std::optional<std::string> cache = cl.take("--cache");
  const bool noCache = cl.takeFlag("--no-cache");
  if (cache && noCache)
  {
    throw UsageError("--cache and --no-cache contradict each other: give one.");
  }
  if (cache && cache->empty())
  {
    throw UsageError("--cache expects a directory.");
  }
  r.useExemplarCache = !noCache;
  r.cacheDirectory = cache.value_or("");
}

// Which of these options the command line gives.
struct GivenOptions
{
  bool patch = false;
  bool seed = false;
  bool tileSize = false;
};

// --previous OLD: OLD's tile record read into the request's options, whose
// tile size, patch size and seed default to the record's.
void takePreviousRecord(SynthArguments& a, const GivenOptions& given)
{
  const std::string path = recordPathOf(*a.previous);
  if (!std::filesystem::exists(path))
  {
    throw UsageError(*a.previous + " has no tile record beside it (" + path +
      "): synthesise it with --keep-tiles and --tile-size first.");
  }
  auto record = std::make_shared<PlacementRecord>(loadRecord(path));
  SynthesisOptions& o = a.request.options;
  o.tileSize = given.tileSize ? o.tileSize : record->tileSize;
  o.patchSize = given.patch ? o.patchSize : record->patchSize;
  o.seed = given.seed ? o.seed : record->seed;
  o.previous = std::move(record);
}

SynthArguments parseSynthArguments(std::vector<std::string> args)
{
  SynthArguments a;
  CommandLine cl(std::move(args));
  const GivenOptions given{ cl.gives("--patch"), cl.gives("--seed"), cl.gives("--tile-size") };
  a.exemplars = cl.takeAll("--exemplar");
  a.regionMaps = cl.takeAll("--region");
  a.regions = cl.take("--regions");
  a.sketch = cl.take("--sketch").value_or("");
  a.output = cl.take("--output", "-o").value_or("");
  a.report = cl.take("--report");
  a.preview = cl.take("--preview");
  a.debugDir = cl.take("--debug-dir");
  a.progress = !cl.takeFlag("--no-progress");
  a.previous = cl.take("--previous");
  a.keepTiles = cl.takeFlag("--keep-tiles") || a.previous.has_value();
  takeCacheOptions(cl, a.request);
  takeSynthesisOptions(cl, a.request.options);
  a.request.options.keepRecord = a.keepTiles;
  if (a.previous)
  {
    takePreviousRecord(a, given);
  }
  else if (a.keepTiles && a.request.options.tileSize == 0)
  {
    throw UsageError("--keep-tiles keeps a record tile by tile: give --tile-size N too.");
  }
  takeGridOptions(cl, a.request);
  if (!cl.positionals().empty())
  {
    throw UsageError("Unexpected argument \"" + cl.positionals()[0] + "\".");
  }
  checkPaths(a);
  // An automatic patch (80, or 32 for a DEM target) is always large enough.
  if (a.preview && a.request.options.patchSize != kAutomaticPatch &&
    a.request.options.patchSize < kMinPreviewedPatch)
  {
    throw UsageError("--preview needs a --patch of at least " + std::to_string(kMinPreviewedPatch) +
      " cells (its coarser level halves it at least).");
  }
  return a;
}

// The files read into the set-up's inputs (warnings printed as they come), and
// the request's automatic patch size fixed for the sketch read.
SetupInputs readSynthInputs(SynthArguments& a)
{
  std::vector<Heightfield> exemplars;
  for (const std::string& path : a.exemplars)
  {
    RasterInfo info;
    exemplars.push_back(readTerrainFile(path, {}, &info));
    printWarnings(info.warnings);
  }
  std::vector<std::string> warnings;
  SketchInput sketch = readSketchInput(a.sketch, warnings);
  printWarnings(warnings);
  SetupOptionNames names;
  names.size = "--size";
  names.cell = "--cell";
  names.patch = "--patch";
  names.memory = kMemoryOption;
  try
  {
    resolvePatchSize(a.request, sketch, names); // --patch was checked already: only the tiles fail
  }
  catch (const Error& e)
  {
    throw UsageError(std::string(e.what()) + " (--tile-size)");
  }
  return setupInputs(a.request, std::move(exemplars), a.exemplars, std::move(sketch), names);
}

// The options with the style regions (--regions) laid on the grid.
SynthesisOptions optionsOnGrid(const SynthArguments& a,
  const OutputGrid& grid,
  std::size_t exemplars)
{
  SynthesisOptions o = a.request.options;
  if (a.regions)
  {
    ReadOptions plain;
    plain.useSidecar = false;
    assignRegions(
      o, readHeightfield(*a.regions, plain), a.regionMaps, grid.width, grid.height, exemplars);
  }
  return o;
}

SynthesisResult runWithProgress(SynthesisSetup& setup,
  const SynthArguments& a,
  const InterruptGuard& interrupt)
{
  SynthesisOptions o = optionsOnGrid(a, setup.grid, setup.exemplars.size());
  ProgressBar bar(a.progress);
  o.progress = [&](double f, const std::string& stage)
  {
    bar(f, stage);
    interrupt.reclaim(); // PoCL's LLVM takes the signals when it compiles the matcher
  };
  SynthesisResult r = synthesiseTakingPool(setup, o);
  interrupt.reclaim();
  bar(1.0, "done");
  printWarnings(r.warnings);
  return r;
}

// What --preview wrote, for the summary and the report.
struct PreviewSummary
{
  std::string file;
  OutputGrid grid;
  int patchSize = 0;
  double seconds = 0.0;        // set-up, synthesis and upsampling, wall clock
  double prepareSeconds = 0.0; // of it, the set-up at the preview's cells
  SynthesisTimings timings;    // of it, the synthesis' stages
};

// --preview: the coarse level (Preview.h), written before the whole synthesis starts.
PreviewSummary writePreview(const SynthArguments& a, const SetupInputs& in)
{
  const PreviewPlan plan = planPreview(in);
  const Preview p = synthesisePreview(in, optionsOnGrid(a, plan.full, in.exemplars.size()));
  writeTerrainFile(*a.preview, p.result.terrain);
  publishStagedOutputs(); // it stays, complete, even if the run is stopped after it
  const SynthesisTimings& t = p.result.timings;
  std::cout << std::fixed << std::setprecision(2) << "Preview: " << plan.coarse.width << " x "
            << plan.coarse.height << " cells of " << plan.coarse.cellX << " m (patch "
            << plan.patchSize << ") in " << p.seconds << " s (prepare " << p.prepareSeconds
            << ", matcher setup " << t.setup << ", features " << t.features << ", fill " << t.fill
            << "): " << *a.preview << std::endl;
  return { *a.preview, plan.coarse, plan.patchSize, p.seconds, p.prepareSeconds, t };
}

// How the run went, besides the synthesis itself.
struct RunRecord
{
  double prepare = 0.0; // seconds: reading the inputs and prepareSynthesis
  double write = 0.0;   // writing the terrain
  double measure = 0.0; // the quality and landform figures
  std::optional<PreviewSummary> preview;
};

void printSummary(const SynthesisSetup& setup,
  const SynthesisResult& r,
  const SynthesisFigures& figures,
  const RunRecord& run,
  const std::string& output)
{
  std::cout << std::fixed << std::setprecision(2) << "Synthesised " << setup.grid.width << " x "
            << setup.grid.height << " cells of " << setup.grid.cellX
            << " m (sketch: " << setup.sketchKind << ") with " << setup.exemplars.size()
            << " exemplar(s): " << r.placements.size() << " patches (" << featurePlacements(r)
            << " on features), backend " << r.backend << ".\n";
  const LandformStatistics& l = setup.landform;
  std::cout << std::setprecision(0) << "Landforms of the exemplars: ridges " << l.ridge.relief
            << " m high, " << std::setprecision(1) << l.ridge.width / 1000.0
            << " km to their foot; valleys " << std::setprecision(0) << l.valley.relief
            << " m deep, " << std::setprecision(1) << l.valley.width / 1000.0
            << " km to their rim; floors fall " << l.floorGradient * 100.0 << "%.\n"
            << std::setprecision(2);
  if (setup.target.ridgeRaise > 1.0 || setup.target.valleyRaise > 1.0)
  {
    std::cout << "Sketched landforms stand out of the land's own relief: ridges x"
              << setup.target.ridgeRaise << ", valleys x" << setup.target.valleyRaise
              << " the exemplars' relief.\n";
  }
  std::cout << "Times: prepare " << run.prepare << " s, matcher setup " << r.timings.setup
            << " s, features " << r.timings.features << " s, fill " << r.timings.fill
            << " s, finishing " << r.timings.finish << " s, writing " << run.write << " s, figures "
            << run.measure << " s"
            << (setup.cache.hit ? " (the exemplars' preparation read from the cache)" : "")
            << ".\n";
  if (r.record)
  {
    std::cout << "Tiles: " << r.tilesTakenOver << " of " << r.tiles.size()
              << " tile passes taken over from the previous record, "
              << r.tiles.size() - r.tilesTakenOver << " placed; record kept in "
              << recordPathOf(output) << ".\n";
  }
  if (r.finishing.drained)
  {
    std::cout << "Drainage: " << r.finishing.pitsBefore << " pits before, " << r.finishing.pitsAfter
              << " after; largest change +" << r.finishing.largestDrainageRaise << " / -"
              << r.finishing.largestDrainageLowering << " m, mean "
              << r.finishing.meanDrainageChange << " m.\n";
  }
  printEvaluation("Quality:", figures.quality);
  printLandforms("", figures.landforms);
  printLegibility("", figures.legibility);
  printLegibility("  before corrections", figures.patchLegibility);
  if (!std::isnan(figures.lineOffset))
  {
    std::cout << std::left << std::setw(22) << ""
              << " feature patches lay their own lines " << figure(figures.lineOffset, 1)
              << " cells from the strokes (median; 90% within " << figure(figures.lineOffset90, 1)
              << ")\n";
  }
  if (!figures.correlation.empty())
  {
    printCorrelation("", figures.correlation);
    printCorrelation("  before corrections", figures.patchCorrelation);
  }
  std::cout << "Wrote " << output << "\n";
}

// One row per placement, in placement order: [order, feature, exemplar, variant,
// x0, y0, match cost, seam cost, landform misfit (m), vertical offset (m), line
// offset (cells; null where not measured)].
nlohmann::json placementListJson(const std::vector<Placement>& placements)
{
  nlohmann::json list = nlohmann::json::array();
  for (const Placement& p : placements)
  {
    list.push_back({ p.order,
      p.feature ? 1 : 0,
      p.exemplar,
      p.variant,
      p.x0,
      p.y0,
      p.matchCost,
      p.seamCost,
      p.landformMisfit,
      p.offset,
      std::isnan(p.lineOffset) ? nlohmann::json() : nlohmann::json(p.lineOffset) });
  }
  return list;
}

double meanSeamCost(const std::vector<Placement>& placements)
{
  double sum = 0.0;
  for (const Placement& p : placements)
  {
    sum += p.seamCost;
  }
  return placements.empty() ? 0.0 : sum / static_cast<double>(placements.size());
}

// The exemplars' ridge and valley cross-sections the landform target was built from.
nlohmann::json landformProfilesJson(const LandformStatistics& l)
{
  auto profile = [](const LandformProfile& p)
  {
    return nlohmann::json{ { "level_m", p.level },
      { "relief_m", p.relief },
      { "width_m", p.width },
      { "distance_m", p.section.distances() },
      { "height_m", p.section.values() } };
  };
  return { { "ridge", profile(l.ridge) },
    { "valley", profile(l.valley) },
    { "base_m", l.base },
    { "floor_gradient", l.floorGradient } };
}

nlohmann::json finishingJson(const FinishingReport& f, const SynthesisOptions& o)
{
  nlohmann::json finishing = { { "landform_correction_max_m", f.landformCorrection },
    { "valley_cells", f.valleyCells },
    { "valley_cells_lowered", f.valleyCellsLowered },
    { "deepest_valley_cut_m", f.deepestValleyCut },
    { "mean_valley_cut_m", f.meanValleyCut },
    { "cells_brought_into_range", f.cellsBroughtIntoRange } };
  if (f.drained)
  {
    finishing["drainage"] = { { "method", pitRemovalMethodName(*o.drainage) },
      { "pits_before", f.pitsBefore },
      { "pits_after", f.pitsAfter },
      { "largest_raise_m", f.largestDrainageRaise },
      { "largest_lowering_m", f.largestDrainageLowering },
      { "mean_change_m", f.meanDrainageChange } };
  }
  return finishing;
}

void writeReport(const std::string& path,
  const SynthArguments& a,
  const SynthesisSetup& setup,
  const SynthesisResult& r,
  const SynthesisFigures& figures,
  const RunRecord& run)
{
  nlohmann::json report = { { "output", a.output },
    { "size", { setup.grid.width, setup.grid.height } },
    { "cell_size_m", { setup.grid.cellX, setup.grid.cellY } },
    { "sketch", a.sketch },
    { "sketch_kind", setup.sketchKind },
    { "exemplars", setup.exemplars.size() },
    { "backend", r.backend },
    { "patch_size", a.request.options.patchSize },
    { "merge", mergeModeName(a.request.options.merge) },
    { "seed", a.request.options.seed },
    { "memory_estimate_gb", setup.memoryEstimate / kBytesPerGB },
    { "exemplar_cache",
      { { "directory", setup.cache.directory },
        { "entry", setup.cache.entry },
        { "hit", setup.cache.hit },
        { "seconds", setup.cache.seconds },
        { "problem", setup.cache.problem } } },
    { "times_s",
      { { "prepare", run.prepare },
        { "setup", r.timings.setup },
        { "features", r.timings.features },
        { "fill", r.timings.fill },
        { "finish", r.timings.finish },
        { "write", run.write },
        { "measure", run.measure } } },
    { "placements", r.placements.size() },
    { "anchored_merges", r.anchoredMerges },
    { "feature_placements", featurePlacements(r) },
    { "mean_seam_cost", meanSeamCost(r.placements) },
    { "quality", evaluationJson(figures.quality) },
    { "landform_quality", landformJson(figures.landforms) },
    { "legibility", legibilityJson(figures.legibility) },
    { "legibility_before_corrections", legibilityJson(figures.patchLegibility) },
    { "feature_line_offset_cells",
      { { "median", figures.lineOffset }, { "p90", figures.lineOffset90 } } },
    { "landform_raise",
      { { "ridge", setup.target.ridgeRaise }, { "valley", setup.target.valleyRaise } } },
    { "landforms", landformProfilesJson(setup.landform) },
    { "finishing", finishingJson(r.finishing, a.request.options) },
    { "placement_list", placementListJson(r.placements) } };
  if (!r.tiles.empty())
  {
    report["tiles"] = tileTimingsJson(r.tiles);
    report["tiles_taken_over"] = r.tilesTakenOver;
  }
  if (run.preview)
  {
    const PreviewSummary& p = *run.preview;
    report["preview"] = { { "file", p.file },
      { "size", { p.grid.width, p.grid.height } },
      { "cell_size_m", { p.grid.cellX, p.grid.cellY } },
      { "patch_size", p.patchSize },
      { "seconds", p.seconds },
      { "times_s",
        { { "prepare", p.prepareSeconds },
          { "setup", p.timings.setup },
          { "features", p.timings.features },
          { "fill", p.timings.fill },
          { "finish", p.timings.finish } } } };
  }
  if (!figures.correlation.empty())
  {
    report["target_correlation"] = correlationJson(figures.correlation);
    report["target_correlation_before_corrections"] = correlationJson(figures.patchCorrelation);
  }
  OutputFile file(path);
  // Paths are escaped by nlohmann; bytes that are not UTF-8 are replaced rather
  // than throwing after the terrain was written.
  file.write(report.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
  file.commit();
}

// Target field, feature trees, patch ids and seams, for looking at in ParaView.
void writeDebug(const std::string& dir, const SynthesisSetup& setup, const SynthesisResult& r)
{
  createOutputFolder(dir);
  writeTerrainFile(dir + "/target.tif", setup.target.field);
  const ShadedRelief shade = computeHillshade(setup.target.field, HillshadeOptions{});
  writeRgbPng(dir + "/target.png",
    setup.target.field.width,
    setup.target.field.height,
    renderRelief(setup.target.field, shade));
  writeTerrainFile(dir + "/patches.tif", r.patches);
  Heightfield confidence = setup.target.field;
  confidence.valid.clear();
  std::copy(setup.target.weight.begin(), setup.target.weight.end(), confidence.z.begin());
  writeTerrainFile(dir + "/target-confidence.tif", confidence);
  vtkNew<vtkPolyData> tree;
  featureGraphToPolyData(setup.target.graph, tree);
  writePolyDataFile(dir + "/sketch-features.vtp", tree);
  vtkNew<vtkPolyData> implied;
  featureGraphToPolyData(setup.target.implied, implied);
  writePolyDataFile(dir + "/implied-features.vtp", implied);
  for (std::size_t e = 0; e < setup.graphs.size(); ++e)
  {
    vtkNew<vtkPolyData> t;
    featureGraphToPolyData(setup.graphs[e], t);
    writePolyDataFile(dir + "/exemplar" + std::to_string(e) + "-features.vtp", t);
  }
  Heightfield ids = r.terrain;
  Heightfield seams = r.terrain;
  ids.valid.clear();
  seams.valid.clear();
  for (std::size_t c = 0; c < ids.size(); ++c)
  {
    ids.z[c] = static_cast<float>(r.patchId[c]);
    seams.z[c] = r.seam[c];
  }
  writeTerrainFile(dir + "/patch-id.tif", ids);
  writeTerrainFile(dir + "/seams.tif", seams);
}

// Lets go of what neither the figures nor the summary and report read once
// the terrain and the debug files are written: the placement's per-cell planes
// (patch ids, seams, match costs) and the target's besides its field (the
// candidate pool went with the placement: synthesiseTakingPool). The figures'
// own planes come on top of what is held, and at 4096 x 4096 these are 350 MB
// of it.
void releaseWrittenPlanes(SynthesisSetup& setup, SynthesisResult& r)
{
  std::vector<int>().swap(r.patchId);
  std::vector<std::uint8_t>().swap(r.seam);
  std::vector<float>().swap(r.matchCost);
  std::vector<float>().swap(setup.target.weight);
  std::vector<float>().swap(setup.target.halfWidth);
  std::vector<float>().swap(setup.target.downstream);
  returnFreedMemory();
}

} // namespace

int runSynth(std::vector<std::string> args)
{
  if (wantsHelp(args))
  {
    std::cout << withPatchDefault(kSynthHelp);
    return 0;
  }
  SynthArguments a = parseSynthArguments(std::move(args));
  const InterruptGuard interrupt; // from here on Ctrl-C stops the run cleanly
  const auto t0 = std::chrono::steady_clock::now();
  SynthesisSetup setup;
  SynthesisResult r;
  RunRecord run;
  try
  {
    SetupInputs in = readSynthInputs(a);
    if (a.preview)
    {
      run.preview = writePreview(a, in);
    }
    setup = prepareSynthesis(std::move(in));
    run.prepare = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    printWarnings(setup.warnings);
    interrupt.check();
    r = runWithProgress(setup, a, interrupt);
  }
  catch (const Cancelled&)
  {
    std::cerr << (run.preview ? "\ntsynth: stopped; only the preview " + run.preview->file +
          " was written (complete), not " + a.output + ".\n"
                              : std::string("\ntsynth: stopped; nothing was written.\n"));
    return interruptedExit();
  }
  auto since = [](std::chrono::steady_clock::time_point t)
  { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count(); };
  auto t1 = std::chrono::steady_clock::now();
  writeTerrainFile(a.output, r.terrain);
  if (r.record)
  {
    saveRecord(*r.record, recordPathOf(a.output));
  }
  run.write = since(t1);
  if (a.debugDir)
  {
    writeDebug(*a.debugDir, setup, r);
  }
  releaseWrittenPlanes(setup, r);
  t1 = std::chrono::steady_clock::now();
  const SynthesisFigures figures = measureSynthesis(setup, r, a.request.options.patchSize);
  run.measure = since(t1);
  printSummary(setup, r, figures, run, a.output);
  if (a.report)
  {
    writeReport(*a.report, a, setup, r, figures, run);
  }
  return 0;
}

} // namespace tsynth::cli
