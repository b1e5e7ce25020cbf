// tsynth distance: distance-based synthesis from generator strokes, no exemplar (Rusnell 2009).
#include "Commands.h"

#include "CliSupport.h"
#include "CommandLine.h"
#include "DistanceInputs.h"
#include "FeatureGraphConversion.h"
#include "TerrainFileIO.h"

#include "Core/Error.h"
#include "Core/FileRoles.h"
#include "Distance/CostScaling.h"
#include "Distance/DistanceSynthesis.h"

#include <vtkNew.h>
#include <vtkPolyData.h>

#include <atomic>
#include <chrono>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>

namespace tsynth::cli
{
namespace
{

// The thesis's default resolution, for poly-lines without --size.

std::string helpText()
{
  const DistanceOptions d;
  const DistanceSources e;
  std::ostringstream h;
  h << R"(Usage: tsynth distance --generators STROKES.png|LINES.vtp -o OUT [options]

Distance-based terrain synthesis (Rusnell, "Feature-rich distance-based terrain synthesis",
MSc thesis, 2009), no exemplar needed: every cell's height is c_s - c, where c is the
least cost of a path to it on a lattice of random edge weights from the generators (ridge
strokes, lines, points), each step scaled by the generator's cross-section profile; one
bounded search per feature, blended by h = sum h_i^(b+1) / sum h_i^b.

Inputs
  --generators FILE      a stroke map (red ridge strokes are generators, each 8-connected
                         stroke a feature; blue strokes are ignored) or poly-lines (.vtp,
                         metres; point array Cost and cell array Profile optional)
  --profiles P           cross-sections: a CSV of distance,height[,profile] rows (distance
                         in cells, heights falling; only the shape counts) or a drawn image
                         (a dark falling curve, crest on the left); none: w_s = 1
  --labels L.png         profile per stroke pixel: grey value k = profile k (same size)
  --assign colour|feature  profile per distinct ridge colour in (R,G,B) order (default), or
                         feature id mod the profile count (the thesis's f_id mod 3)
  --region-profile K     closed strokes' interiors (craters, cones) use profile K, and no
                         other feature enters or blends there
  --edge-weights IMG     edge weights from an image's grey values instead of --mu/--r
  --edge-range LO,HI     grey 0..max mapped to these weights (default )"
    << e.edgeLow << "," << e.edgeHigh << R"()
  -o, --output OUT       .tif (GeoTIFF float32), .png (16-bit + sidecar) or .vti
  --size WxH             grid of poly-lines, cells (default )"
    << kDefaultDistanceGrid << "x" << kDefaultDistanceGrid << R"(; images: their pixels)
  --cell M               metres per cell (default )"
    << d.cellSize << R"()
  --height-scale M       metres per cost unit (default )"
    << d.heightScale << R"()
  --seed N               edge weights, fBm costs and ridge cells (default )"
    << d.seed << R"()

Lattice and sea level
  --mu W                 mean edge weight mu_w > 0, steepness (default )"
    << d.meanWeight << R"()
  --r R                  edge weight deviation, 0 <= r < mu_w, roughness (default )"
    << d.roughness << R"()
  --chessboard           diagonal edges weigh as much as axis ones (the thesis's literal
                         lattice; default: sqrt(2) times more, round features)
  --s S                  sea level scale, c_s = s * c_max (default )"
    << d.seaLevelScale << R"()
  --b B                  blending bias, 0 (mean) to 64 (about the maximum) (default )"
    << d.blendBias << R"()

Profiles
  --profile-scale K      cells per profile distance unit (default )"
    << d.profileScale << R"()
  --bins N               cost bins of each scaling table (default )"
    << d.profileBins << R"(; few give "strata")

Generator costs (fBm where the input gives none; smaller cost = higher ground)
  --fbm-h H              (default )"
    << d.fbm.h << R"()
  --lacunarity L         (default )"
    << d.fbm.lacunarity << R"()
  --octaves N            (default )"
    << d.fbm.octaves << R"()
  --domain D             noise cells across the grid (default )"
    << d.fbm.domain << R"()
  --fbm-scale C          cost of the highest fBm value (default )"
    << d.fbm.scale << R"()
  --fbm-range LO,HI      share of the scale the costs span, eq. 4.1 (default )"
    << d.fbm.low << "," << d.fbm.high << R"()

Dendritic ridges
  --ridges N             trace N least-cost paths back from random cells (default )"
    << d.ridgeCount << R"()
  --ridge-fraction F     their cost share, 0 < F <= 1 (default )"
    << d.ridgeFraction << R"()
  --ridge-cost rise|cost rise: c_g + F (C_a - c_g), leaving the peak at its height (default);
                         cost: F C_a, the thesis read literally

Expert
  --eps-s E              a feature's search stops within E of c_s (default )"
    << d.seaLevelEpsilon << R"()
  --p-f P                ... or below P of the approximate height (default )"
    << d.approximateFraction << R"()
  --min-ts T             least cost-scaling value kept as it is (default )"
    << d.minScaling << R"()
  --approximate          the one multi-source search only: a fast preview with seams
  --max-memory GB        refuse a run estimated to need more, before any work (default: 80%
                         of the machine's memory)
  --no-progress          no progress bar on the terminal
)";
  return h.str();
}

struct DistanceArguments
{
  std::string generators;
  std::string output;
  std::optional<std::string> profiles;
  std::optional<std::string> labels;
  std::optional<std::string> edgeWeights;
  std::optional<std::string> size;
  DistanceSources sources;
  DistanceOptions options;
  bool progress = true;
};

std::pair<double, double> parseRange(const std::string& text, const char* option)
{
  const auto comma = text.find(',');
  const auto lo = parseNumber(text.substr(0, comma));
  const auto hi = comma == std::string::npos ? std::nullopt : parseNumber(text.substr(comma + 1));
  if (!lo || !hi)
  {
    throw UsageError(std::string(option) + " expects two numbers as LO,HI.");
  }
  return { *lo, *hi };
}

// The option of the table's row `property` into `target`, checked against the row's range.
template<class T>
void takeOption(CommandLine& cl, const char* property, T& target)
{
  if (const auto v = takeRowNumber(cl, optionRow(distanceOptionRows(), property)))
  {
    target = static_cast<T>(*v);
  }
}

void takeLatticeOptions(CommandLine& cl, DistanceOptions& o)
{
  takeOption(cl, "MeanWeight", o.meanWeight);
  takeOption(cl, "Roughness", o.roughness);
  o.sqrt2Diagonals = !cl.takeFlag("--chessboard");
  takeOption(cl, "SeaLevelScale", o.seaLevelScale);
  takeOption(cl, "BlendBias", o.blendBias);
  takeOption(cl, "SeaLevelEpsilon", o.seaLevelEpsilon);
  takeOption(cl, "ApproximateFraction", o.approximateFraction);
  takeOption(cl, "MinScaling", o.minScaling);
  takeOption(cl, "ProfileScale", o.profileScale);
  takeOption(cl, "CellSize", o.cellSize);
  takeOption(cl, "HeightScale", o.heightScale);
  takeOption(cl, "ProfileBins", o.profileBins);
  o.approximateOnly = cl.takeFlag("--approximate");
}

void takeCostOptions(CommandLine& cl, DistanceOptions& o)
{
  takeOption(cl, "FbmH", o.fbm.h);
  takeOption(cl, "FbmLacunarity", o.fbm.lacunarity);
  takeOption(cl, "FbmDomain", o.fbm.domain);
  takeOption(cl, "FbmScale", o.fbm.scale);
  takeOption(cl, "FbmOctaves", o.fbm.octaves);
  if (const auto range = cl.take("--fbm-range"))
  {
    std::tie(o.fbm.low, o.fbm.high) = parseRange(*range, "--fbm-range");
    const OptionRow& row = optionRow(distanceOptionRows(), "FbmRange");
    try
    {
      row.checkValue(o.fbm.low, row.flag);
      row.checkValue(o.fbm.high, row.flag);
    }
    catch (const Error& e)
    {
      throw UsageError(e.what());
    }
  }
  takeOption(cl, "RidgeCount", o.ridgeCount);
  takeOption(cl, "RidgeFraction", o.ridgeFraction);
  if (const auto mode = takeRowChoice(cl, optionRow(distanceOptionRows(), "RidgeCost")))
  {
    o.ridgeCost = static_cast<RidgeCost>(*mode);
  }
  if (const auto seed = cl.take("--seed"))
  {
    o.seed = parseSeed(*seed);
  }
}

DistanceArguments parseDistanceArguments(std::vector<std::string> args)
{
  CommandLine cl(std::move(args));
  DistanceArguments a;
  a.generators = cl.take("--generators").value_or("");
  a.output = cl.take("--output", "-o").value_or("");
  a.profiles = cl.take("--profiles");
  a.labels = cl.take("--labels");
  a.edgeWeights = cl.take("--edge-weights");
  a.size = cl.take("--size");
  if (const auto assign = cl.take("--assign"))
  {
    const OptionRow& row = optionRow(distanceOptionRows(), "ProfileAssignment");
    try
    {
      a.sources.assignment = static_cast<ProfileAssignment>(
        row.choices.valueOf(*assign == "color" ? "colour" : *assign, row.flag));
    }
    catch (const Error& e)
    {
      throw UsageError(e.what());
    }
  }
  takeOption(cl, "RegionProfile", a.sources.regionProfile);
  if (const auto range = cl.take("--edge-range"))
  {
    std::tie(a.sources.edgeLow, a.sources.edgeHigh) = parseRange(*range, "--edge-range");
  }
  takeLatticeOptions(cl, a.options);
  takeCostOptions(cl, a.options);
  a.options.memoryBudget = takeMemoryBudget(cl);
  a.options.memoryOption = kMemoryOption;
  a.options.sizeOption = hasExtension(a.generators, ".vtp") ? "--size" : "stroke map";
  a.progress = !cl.takeFlag("--no-progress");
  if (!cl.positionals().empty())
  {
    throw UsageError("tsynth distance takes no positional arguments (use --generators).");
  }
  if (a.generators.empty())
  {
    throw UsageError("tsynth distance needs --generators STROKES.png|LINES.vtp.");
  }
  if (a.output.empty() || (!isVtiPath(a.output) && !isHeightfieldWriteExtension(a.output)))
  {
    throw UsageError("tsynth distance needs an output file: -o OUT.tif|.png|.vti.");
  }
  FileRoles files;
  files.input(a.generators, "--generators");
  for (const auto& [input, role] : { std::pair{ a.profiles, "--profiles" },
         std::pair{ a.labels, "--labels" },
         std::pair{ a.edgeWeights, "--edge-weights" } })
  {
    if (input)
    {
      files.input(*input, role);
    }
  }
  files.output(a.output, "-o");
  files.check();
  return a;
}

DistanceTerrain synthesise(DistanceArguments& a)
{
  std::vector<std::string> warnings;
  if (a.profiles)
  {
    a.sources.profiles = readProfiles(*a.profiles);
  }
  ColourImage strokes;
  ColourImage labels;
  ColourImage weights;
  std::vector<GeneratorLine> lines;
  if (hasExtension(a.generators, ".vtp"))
  {
    GridRequest grid;
    grid.width = kDefaultDistanceGrid;
    grid.height = kDefaultDistanceGrid;
    grid = a.size ? parseSize(*a.size, grid) : grid;
    vtkNew<vtkPolyData> data;
    readPolyDataFile(a.generators, data);
    lines = polyDataToGeneratorLines(data, a.options.cellSize);
    a.sources.lines = &lines;
    a.sources.width = grid.width;
    a.sources.height = grid.height;
    if (a.labels)
    {
      throw UsageError("--labels applies to stroke maps; give poly-lines a Profile cell array.");
    }
  }
  else
  {
    if (a.size)
    {
      throw UsageError("--size applies to poly-lines; a stroke map's grid is its pixels.");
    }
    strokes = readColourImage(a.generators);
    a.sources.strokes = &strokes;
    if (a.labels)
    {
      labels = readColourImage(*a.labels);
      a.sources.labels = &labels;
    }
  }
  if (a.edgeWeights)
  {
    weights = readColourImage(*a.edgeWeights);
    a.sources.edgeWeights = &weights;
  }
  const DistanceInputs inputs = assembleDistanceInputs(a.sources, warnings);
  printWarnings(warnings);
  ProgressBar bar(a.progress);
  a.options.progress = [&](double f, const std::string& stage) { bar(f, stage); };
  DistanceTerrain t = synthesiseByDistance(inputs, a.options);
  printWarnings(t.warnings);
  return t;
}

} // namespace

int runDistance(std::vector<std::string> args)
{
  if (wantsHelp(args))
  {
    std::cout << helpText();
    return 0;
  }
  DistanceArguments a = parseDistanceArguments(std::move(args));
  const auto t0 = std::chrono::steady_clock::now();
  DistanceTerrain t;
  try
  {
    const InterruptGuard interrupt; // a stop signal ends the run between kernel steps
    t = synthesise(a);
  }
  catch (const Cancelled&)
  {
    std::cerr << "\ntsynth: stopped; nothing was written.\n";
    return interruptedExit();
  }
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  writeTerrainFile(a.output, t.heights);
  const HeightRange range = computeHeightRange(t.heights);
  std::cout << std::fixed << std::setprecision(2) << "Distance synthesis: " << t.heights.width
            << " x " << t.heights.height << " cells, " << t.features << " features, "
            << t.generators << " generator nodes (" << t.ridgeNodes << " on ridges); c_s "
            << t.seaLevelCost << "; heights " << range.min << " to " << range.max << " m; "
            << seconds << " s\n"
            << std::defaultfloat << "Wrote " << a.output << "\n";
  return 0;
}

} // namespace tsynth::cli
