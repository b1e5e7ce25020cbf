#include "SynthCommands.h"

#include "CommandLine.h"
#include "FeatureGraphConversion.h"
#include "TerrainFileIO.h"

#include "Core/Error.h"
#include "Core/HeightfieldIO.h"
#include "Core/OutputFile.h"
#include "Core/Resample.h"
#include "Features/Ppa.h"
#include "Features/Sketch.h"
#include "Metrics/TerrainMetrics.h"
#include "Synthesis/Regions.h"
#include "Synthesis/Synthesizer.h"

#include <vtkNew.h>
#include <vtkPolyData.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
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
higher), poly-lines (.vtp with a FeatureType cell array) or a real DEM used as the target.

  --exemplar DEM         a DEM to copy terrain from (repeat for several)
  --sketch SKETCH        the sketch
  -o, --output OUT       .tif (GeoTIFF float32), .png (16-bit + sidecar) or .vti
  --size WxH             output size in cells (default: the sketch's pixels)
  --cell M               output cell size in metres (default: the first exemplar's)
  --patch N              patch size in cells (default 80)
  --backend B            auto (default), opencl or cpu: same result, different speed
  --merge M              new (default), poisson, shepard or cut
  --fill F               best-first (default) or concentric
  --seed N               accepted for reproducible scripts; the method is deterministic
  --report FILE.json     per-stage times, counts, costs and quality figures
  --debug-dir DIR        target field, feature trees, patch ids and seams as files
  --regions LABELS       style regions: a single-band image of labels over the output (resized to
                         it); label L is served by exemplar number L (counting from 0) unless
                         --region L=E1,E2 says otherwise (repeatable)
  --no-vertical-offset   place patches at their own heights (default: fitted to the overlap)
  --repetition P         seam-cost penalty for reusing a nearby source (default 0.5; 0 = off)
  --no-progress          no progress bar on the terminal
)";

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
)";

bool hasExtension(const std::string& path, const char* wanted)
{
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext)
  {
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return ext == wanted;
}

bool wantsHelp(const std::vector<std::string>& args)
{
  for (const auto& a : args)
  {
    if (a == "--help" || a == "-h")
    {
      return true;
    }
  }
  return false;
}

// Every value of a repeatable option, removed from the arguments.
std::vector<std::string> takeRepeated(std::vector<std::string>& args, const std::string& name)
{
  std::vector<std::string> out;
  for (std::size_t k = 0; k < args.size();)
  {
    if (args[k] == name && k + 1 < args.size())
    {
      out.push_back(args[k + 1]);
      args.erase(args.begin() + static_cast<long>(k), args.begin() + static_cast<long>(k + 2));
    }
    else if (args[k].rfind(name + "=", 0) == 0)
    {
      out.push_back(args[k].substr(name.size() + 1));
      args.erase(args.begin() + static_cast<long>(k));
    }
    else
    {
      ++k;
    }
  }
  return out;
}

struct Exemplars
{
  std::vector<Heightfield> heights;
  std::vector<FeatureGraph> graphs;
  std::vector<std::string> paths;
};

// Reads the exemplars; any whose cells differ from the output's by more than 1%
// is resampled to the output's cell size (and says so), then its features found.
Exemplars readExemplars(const std::vector<std::string>& paths, std::optional<double> cell)
{
  Exemplars ex;
  for (const std::string& p : paths)
  {
    tsynth::RasterInfo info;
    Heightfield hf = readTerrainFile(p, {}, &info);
    for (const auto& w : info.warnings)
    {
      std::cerr << "tsynth: warning: " << w << "\n";
    }
    ex.heights.push_back(std::move(hf));
    ex.paths.push_back(p);
  }
  const double cx = cell.value_or(ex.heights.front().cellX);
  const double cy = cell.value_or(ex.heights.front().cellY);
  for (std::size_t e = 0; e < ex.heights.size(); ++e)
  {
    Heightfield& hf = ex.heights[e];
    if (std::abs(hf.cellX - cx) > 0.01 * cx || std::abs(hf.cellY - cy) > 0.01 * cy)
    {
      std::cerr << "tsynth: note: " << ex.paths[e] << " has " << hf.cellX << " x " << hf.cellY
                << " m cells; resampled to the output's " << cx << " x " << cy << " m.\n";
      hf = resampleToCellSize(hf, cx, cy);
    }
    FeatureGraph g = extractFeatures(hf, FeatureType::Ridge, {}).graph;
    appendGraph(g, extractFeatures(hf, FeatureType::Valley, {}).graph);
    ex.graphs.push_back(std::move(g));
  }
  return ex;
}

// The sketch's feature graph in its own pixels, and its size; for a DEM or grey
// map also its heights (for the target field).
struct Sketch
{
  FeatureGraph graph;
  int width = 0;
  int height = 0;
  bool heights = false;
  Heightfield field;
  std::string kind;
  std::vector<std::string> warnings;
};

Sketch readSketch(const std::string& path, int patch)
{
  Sketch s;
  if (hasExtension(path, ".vtp"))
  {
    vtkNew<vtkPolyData> lines;
    readPolyDataFile(path, lines);
    std::string warning;
    const auto polylines = polyDataToPolylines(lines, 1.0, 1.0, 0.0, 0.0, &warning);
    if (!warning.empty())
    {
      s.warnings.push_back(warning);
    }
    double b[6];
    lines->GetBounds(b);
    s.width = static_cast<int>(std::ceil(b[1])) + 1;
    s.height = static_cast<int>(std::ceil(b[3])) + 1;
    s.graph = polylineFeatures(polylines, s.width, s.height, 1.0, 1.0, 1.0, 0.5 * patch);
    s.kind = "poly-lines";
    return s;
  }
  // A single-band raster that is not 8-bit is a DEM used as the target.
  bool dem = false;
  try
  {
    const RasterInfo info = readRasterInfo(path, {});
    dem = info.bands == 1 && info.dataType != "Byte";
  }
  catch (const Error&)
  {
    dem = false; // several bands: a sketch image, read below
  }
  if (dem)
  {
    s.field = readTerrainFile(path);
    s.width = s.field.width;
    s.height = s.field.height;
    s.heights = true;
    s.graph = extractFeatures(s.field, FeatureType::Ridge, {}).graph;
    appendGraph(s.graph, extractFeatures(s.field, FeatureType::Valley, {}).graph);
    s.kind = "DEM";
    return s;
  }
  const ColourImage image = readColourImage(path);
  SketchOptions so;
  so.patchSize = patch;
  so.controlRadius = 0.5 * patch;
  SketchFeatures f = sketchFeatures(image, so);
  s.graph = std::move(f.graph);
  s.warnings = f.warnings;
  s.width = image.width;
  s.height = image.height;
  if (f.kind == SketchKind::Grey)
  {
    s.heights = true;
    s.field = greyField(image);
    s.kind = "grey sketch";
  }
  else
  {
    s.kind = "stroke map";
  }
  return s;
}

class ProgressBar
{
public:
  explicit ProgressBar(bool enabled)
    : enabled_(enabled && ::isatty(STDERR_FILENO) != 0)
  {
  }
  void operator()(double f, const std::string& stage)
  {
    if (!enabled_)
    {
      return;
    }
    const int width = 30;
    const int filled = static_cast<int>(f * width + 0.5);
    std::fprintf(stderr,
      "\r[%s%s] %3d%% %-10s",
      std::string(static_cast<std::size_t>(filled), '#').c_str(),
      std::string(static_cast<std::size_t>(width - filled), ' ').c_str(),
      static_cast<int>(f * 100 + 0.5),
      stage.c_str());
    std::fflush(stderr);
    if (f >= 1.0)
    {
      std::fprintf(stderr, "\n");
    }
  }

private:
  bool enabled_;
};

std::string json(double v)
{
  if (!std::isfinite(v))
  {
    return "null";
  }
  std::ostringstream o;
  o << std::setprecision(6) << v;
  return o.str();
}

std::string evaluationJson(const TerrainEvaluation& e)
{
  std::ostringstream o;
  o << "{\"ridge_fidelity\": " << json(e.ridgeFidelity)
    << ", \"valley_fidelity\": " << json(e.valleyFidelity)
    << ", \"seam_index\": " << json(e.seamIndex)
    << ", \"slope_distance\": " << json(e.slopeDistance)
    << ", \"pit_density\": " << json(e.pitDensity) << "}";
  return o.str();
}

void printEvaluation(const char* name, const TerrainEvaluation& e)
{
  auto f = [](double v)
  {
    return v < 0 ? std::string("  -  ")
                 : (std::ostringstream() << std::fixed << std::setprecision(3) << v).str();
  };
  std::cout << std::left << std::setw(22) << name << " fidelity ridge " << f(e.ridgeFidelity)
            << " valley " << f(e.valleyFidelity) << "  seam " << f(e.seamIndex) << "  slope "
            << f(e.slopeDistance) << "  pits " << f(e.pitDensity) << "\n";
}

void writeDebug(const std::string& dir,
  const SynthesisTarget& target,
  const SynthesisResult& r,
  const Exemplars& ex)
{
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec)
  {
    throw Error("Cannot create the debug folder " + dir + ": " + ec.message() + ".");
  }
  writeTerrainFile(dir + "/target.tif", target.field);
  writeTerrainFile(dir + "/patches.tif", r.patches);
  Heightfield confidence = target.field;
  confidence.valid.clear();
  std::copy(target.weight.begin(), target.weight.end(), confidence.z.begin());
  writeTerrainFile(dir + "/target-confidence.tif", confidence);
  vtkNew<vtkPolyData> tree;
  featureGraphToPolyData(target.graph, tree);
  writePolyDataFile(dir + "/sketch-features.vtp", tree);
  for (std::size_t e = 0; e < ex.graphs.size(); ++e)
  {
    vtkNew<vtkPolyData> t;
    featureGraphToPolyData(ex.graphs[e], t);
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

} // namespace

int runSynth(std::vector<std::string> args)
{
  if (wantsHelp(args))
  {
    std::cout << kSynthHelp;
    return 0;
  }
  std::vector<std::string> exemplarPaths = takeRepeated(args, "--exemplar");
  const std::vector<std::string> regionMaps = takeRepeated(args, "--region");
  CommandLine cl(std::move(args));
  const auto regionsPath = cl.take("--regions");
  const auto sketchPath = cl.take("--sketch");
  const auto output = cl.take("--output", "-o");
  const auto size = cl.take("--size");
  const auto cell = cl.takeNumber("--cell");
  const auto patch = cl.takeNumber("--patch");
  const auto backend = cl.take("--backend");
  const auto merge = cl.take("--merge");
  const auto fill = cl.take("--fill");
  const auto seed = cl.takeNumber("--seed");
  const auto report = cl.take("--report");
  const auto debugDir = cl.take("--debug-dir");
  const bool noProgress = cl.takeFlag("--no-progress");
  const bool noOffset = cl.takeFlag("--no-vertical-offset");
  const auto repetition = cl.takeNumber("--repetition");
  if (!cl.positionals().empty())
  {
    throw UsageError("Unexpected argument \"" + cl.positionals()[0] + "\".");
  }
  if (exemplarPaths.empty())
  {
    throw UsageError("tsynth synth needs at least one --exemplar DEM.");
  }
  if (!sketchPath)
  {
    throw UsageError("tsynth synth needs a --sketch.");
  }
  if (!output)
  {
    throw UsageError("tsynth synth needs an output file: -o OUT.tif|.png|.vti.");
  }
  if (!isVtiPath(*output) && !isHeightfieldWriteExtension(*output))
  {
    throw UsageError("The output must end in .tif, .png or .vti, not " + *output + ".");
  }
  if (report && !hasExtension(*report, ".json"))
  {
    throw UsageError("--report expects a .json file.");
  }
  SynthesisOptions o;
  if (patch)
  {
    if (*patch != std::floor(*patch) || *patch < 16 || *patch > 512 ||
      static_cast<int>(*patch) % 4 != 0)
    {
      throw UsageError("--patch expects a multiple of 4 from 16 to 512.");
    }
    o.patchSize = static_cast<int>(*patch);
  }
  if (backend)
  {
    try
    {
      o.backend = parseBackend(*backend);
    }
    catch (const Error&)
    {
      throw UsageError("--backend must be auto, opencl or cpu.");
    }
  }
  if (merge)
  {
    try
    {
      o.merge = parseMergeMode(*merge);
    }
    catch (const Error&)
    {
      throw UsageError("--merge must be new, poisson, shepard or cut.");
    }
  }
  if (fill)
  {
    if (*fill != "best-first" && *fill != "concentric")
    {
      throw UsageError("--fill must be best-first or concentric.");
    }
    o.fill = *fill == "concentric" ? FillOrder::Concentric : FillOrder::BestFirst;
  }
  (void)seed;
  o.verticalOffset = !noOffset;
  if (repetition)
  {
    if (*repetition < 0.0)
    {
      throw UsageError("--repetition must not be negative.");
    }
    o.repetitionPenalty = *repetition;
  }
  if (cell && !(*cell > 0.0))
  {
    throw UsageError("--cell expects a positive number of metres.");
  }
  int width = 0;
  int height = 0;
  if (size)
  {
    char tail = 0;
    if (std::sscanf(size->c_str(), "%dx%d%c", &width, &height, &tail) != 2 || width < 1 ||
      height < 1)
    {
      throw UsageError("--size expects WxH in cells, e.g. 1024x1024.");
    }
  }

  const auto t0 = std::chrono::steady_clock::now();
  const Exemplars ex = readExemplars(exemplarPaths, cell);
  Sketch sketch = readSketch(*sketchPath, o.patchSize);
  for (const auto& w : sketch.warnings)
  {
    std::cerr << "tsynth: warning: " << w << "\n";
  }
  if (width == 0)
  {
    width = sketch.width;
    height = sketch.height;
  }
  const double cellX = cell.value_or(ex.heights.front().cellX);
  const double cellY = cell.value_or(ex.heights.front().cellY);
  // Refuse before starting what cannot fit: output, its work arrays, and each
  // exemplar's 10 oriented copies with their tables.
  double bytes = static_cast<double>(width) * height * 48.0;
  for (const Heightfield& h : ex.heights)
  {
    bytes += static_cast<double>(h.size()) * 10.0 * 2.0 * 12.0;
  }
  const double memory =
    static_cast<double>(sysconf(_SC_PHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGE_SIZE));
  if (bytes > 0.8 * memory)
  {
    throw Error("This synthesis needs about " + std::to_string(static_cast<long>(bytes / 1e9)) +
      " GB but the machine has " + std::to_string(static_cast<long>(memory / 1e9)) +
      " GB; use a smaller --size.");
  }

  std::vector<const Heightfield*> hp;
  std::vector<const FeatureGraph*> gp;
  for (std::size_t e = 0; e < ex.heights.size(); ++e)
  {
    hp.push_back(&ex.heights[e]);
    gp.push_back(&ex.graphs[e]);
  }
  const ExemplarStatistics stats = exemplarStatistics(hp, gp, o.patchSize);
  const SynthesisTarget target = makeTarget(sketch.graph,
    sketch.width,
    sketch.height,
    sketch.heights ? &sketch.field : nullptr,
    width,
    height,
    cellX,
    cellY,
    stats,
    o.patchSize,
    sketch.kind == "grey sketch" ? SketchHeights::Grey : SketchHeights::Dem);
  const FeatureGraph& graph = target.graph;
  const double prepare =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  if (regionsPath)
  {
    ReadOptions plain;
    plain.useSidecar = false;
    assignRegions(
      o, readHeightfield(*regionsPath, plain), regionMaps, width, height, ex.heights.size());
  }
  else if (!regionMaps.empty())
  {
    throw UsageError("--region needs --regions LABELS.");
  }

  ProgressBar bar(!noProgress);
  o.progress = [&](double f, const std::string& stage) { bar(f, stage); };
  const SynthesisResult r = synthesize(target, hp, gp, o);
  bar(1.0, "done");
  for (const auto& w : r.warnings)
  {
    std::cerr << "tsynth: warning: " << w << "\n";
  }
  writeTerrainFile(*output, r.terrain);
  const TerrainEvaluation quality = evaluateTerrain(r.terrain, hp, &graph);

  std::size_t features = 0;
  double seamSum = 0.0;
  for (const Placement& p : r.placements)
  {
    features += p.feature ? 1 : 0;
    seamSum += p.seamCost;
  }
  std::cout << std::fixed << std::setprecision(2) << "Synthesised " << width << " x " << height
            << " cells from a " << sketch.kind << " with " << ex.heights.size()
            << " exemplar(s): " << r.placements.size() << " patches (" << features
            << " on features), backend " << r.backend << ".\n";
  {
    const LandformStatistics& l = stats.landform;
    std::cout << std::setprecision(0) << "Landforms of the exemplars: ridges " << l.ridge.relief
              << " m high, " << std::setprecision(1) << l.ridge.width / 1000.0
              << " km to their foot; valleys " << std::setprecision(0) << l.valley.relief
              << " m deep, " << std::setprecision(1) << l.valley.width / 1000.0
              << " km to their rim; floors fall " << l.floorGradient * 100.0 << "%.\n"
              << std::setprecision(2);
  }
  std::cout << "Times: prepare " << prepare << " s, matcher setup " << r.timings.setup
            << " s, features " << r.timings.features << " s, fill " << r.timings.fill << " s.\n";
  printEvaluation("Quality:", quality);
  std::cout << "Wrote " << *output << "\n";

  if (report)
  {
    OutputFile file(*report);
    std::ofstream out(file.temporaryPath());
    out << "{\n  \"output\": \"" << *output << "\",\n  \"size\": [" << width << ", " << height
        << "],\n  \"cell_size_m\": [" << json(cellX) << ", " << json(cellY)
        << "],\n  \"sketch\": \"" << *sketchPath << "\",\n  \"sketch_kind\": \"" << sketch.kind
        << "\",\n  \"exemplars\": " << ex.heights.size() << ",\n  \"backend\": \"" << r.backend
        << "\",\n  \"patch_size\": " << o.patchSize << ",\n  \"merge\": \""
        << mergeModeName(o.merge) << "\",\n  \"times_s\": {\"prepare\": " << json(prepare)
        << ", \"setup\": " << json(r.timings.setup)
        << ", \"features\": " << json(r.timings.features) << ", \"fill\": " << json(r.timings.fill)
        << "},\n  \"placements\": " << r.placements.size()
        << ",\n  \"feature_placements\": " << features << ",\n  \"mean_seam_cost\": "
        << json(r.placements.empty() ? 0.0 : seamSum / static_cast<double>(r.placements.size()))
        << ",\n  \"quality\": " << evaluationJson(quality) << ",\n  \"placement_list\": [";
    // [order, feature, exemplar, variant, x0, y0, match cost, seam cost]
    for (std::size_t k = 0; k < r.placements.size(); ++k)
    {
      const Placement& p = r.placements[k];
      out << (k == 0 ? "" : ", ") << "[" << p.order << ", " << (p.feature ? 1 : 0) << ", "
          << p.exemplar << ", " << p.variant << ", " << p.x0 << ", " << p.y0 << ", "
          << json(p.matchCost) << ", " << json(p.seamCost) << ", " << json(p.landformMisfit) << "]";
    }
    out << "]\n}\n";
    out.close();
    if (!out)
    {
      throw Error("Cannot write " + *report + ".");
    }
    file.commit();
  }
  if (debugDir)
  {
    writeDebug(*debugDir, target, r, ex);
  }
  return 0;
}

int runEvaluate(std::vector<std::string> args)
{
  if (wantsHelp(args))
  {
    std::cout << kEvaluateHelp;
    return 0;
  }
  std::vector<std::string> exemplarPaths = takeRepeated(args, "--exemplar");
  CommandLine cl(std::move(args));
  const auto sketchPath = cl.take("--sketch");
  const bool asJson = cl.takeFlag("--json");
  const auto rest = cl.positionals();
  if (rest.size() != 1)
  {
    throw UsageError("tsynth evaluate needs one terrain file.");
  }
  if (exemplarPaths.empty())
  {
    throw UsageError("tsynth evaluate needs an --exemplar DEM to compare with.");
  }
  const Heightfield terrain = readTerrainFile(rest[0]);
  std::vector<Heightfield> exemplars;
  for (const std::string& path : exemplarPaths)
  {
    exemplars.push_back(readTerrainFile(path));
  }
  std::vector<const Heightfield*> pooled;
  for (const Heightfield& x : exemplars)
  {
    pooled.push_back(&x);
  }
  const Heightfield& exemplar = exemplars.front();
  FeatureGraph graph;
  const FeatureGraph* sketch = nullptr;
  if (sketchPath)
  {
    const Sketch s = readSketch(*sketchPath, 80);
    graph = scaleGraph(
      s.graph, s.width, s.height, terrain.width, terrain.height, terrain.cellX, terrain.cellY);
    sketch = &graph;
  }
  const TerrainEvaluation e = evaluateTerrain(terrain, pooled, sketch);
  const TerrainEvaluation tiled =
    evaluateTerrain(tiledBaseline(exemplar, terrain.width, terrain.height), exemplar, sketch);
  const TerrainEvaluation random = evaluateTerrain(
    randomPatchBaseline(exemplar, terrain.width, terrain.height, 80, 1), exemplar, sketch);
  if (asJson)
  {
    std::cout << "{\"terrain\": " << evaluationJson(e)
              << ", \"tiled_exemplar\": " << evaluationJson(tiled)
              << ", \"random_patches\": " << evaluationJson(random) << "}\n";
    return 0;
  }
  printEvaluation(rest[0].c_str(), e);
  printEvaluation("baseline: tiled", tiled);
  printEvaluation("baseline: random", random);
  return 0;
}

} // namespace tsynth::cli
