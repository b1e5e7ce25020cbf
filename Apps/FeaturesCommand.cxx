// tsynth features: ridge and valley lines of a DEM (PPA) or of a sketch, as a
// feature tree of VTK poly-lines.
#include "Commands.h"

#include "CliSupport.h"
#include "CommandLine.h"
#include "FeatureGraphConversion.h"
#include "TerrainFileIO.h"

#include "Core/Error.h"
#include "Core/FileRoles.h"
#include "Core/HeightfieldIO.h"
#include "Core/PatchSize.h"
#include "Features/Ppa.h"
#include "Features/Sketch.h"
#include "Synthesis/Setup.h"

#include <vtkNew.h>
#include <vtkPolyData.h>

#include <chrono>
#include <iomanip>
#include <iostream>
#include <optional>
#include <type_traits>

namespace tsynth::cli
{
namespace
{

// The patch sizes `tsynth features` accepts: its control radius is half the
// patch, and a sketch must be at least one patch. Wider than the synthesis'
// own range (Core/PatchSize.h): PPA works at any scale.
constexpr int kMinFeaturePatch = 8;
constexpr int kMaxFeaturePatch = 4096;

const char* const kFeaturesHelp =
  R"(Usage: tsynth features DEM -o FEATURES.vtp [--features ridges|valleys|both] [options]
       tsynth features SKETCH --sketch -o FEATURES.vtp [options]

Extracts ridge and valley lines (or one kind) as a feature tree with PPA and writes it
as VTK poly-lines in metres (open it in ParaView over the DEM; colour by NodeKind).
With --sketch the input is a sketch: a grey sketch map or an RGB stroke map (red
ridges, blue valleys), or a .vtp of poly-lines with a FeatureType cell array.

  -o, --output F.vtp         the feature tree
  --features W               which lines: %WORDS:Features% (default %DEFAULT:Features%, as
                             the Terrain Feature Extractor); --valleys and --both
                             are short for --features valleys and --features both
  --control-points CP.vtp    also write the control points
  --profile-length N         PPA half profile length in cells (default 3)
  --relative-dip F           dip as a fraction of the local relief (default 0.1)
  --min-dip M                minimum dip in metres (default 0)
  --smooth SIGMA             Gaussian pre-smoothing in cells (default 0)
  --significance F           a target must also stand out at landform scale: on both
                             sides of one axis the ground drops, before rising as
                             much, within the radius by F times the DEM's relief
                             (1st-99th percentile range) and at least K noise sigmas
                             (default 0.02; 0 = off, PPA as before; DEMs only)
  --significance-noise K     that drop's floor in sigmas of the DEM's cell-scale
                             noise (default 4; 0 = no floor)
  --significance-radius N    cells searched for that drop (default 20)
  --end-reductions N         end-cell removal passes (default 3)
  --min-branch N             shortest dangling branch kept, cells (default 15)
  --min-tree N               smallest tree kept, cells (default 30)
  --patch P                  patch size in cells (default %PATCH%): control radius P/2,
                             and sketches must be at least one patch
)";

// The PPA options of `tsynth features` (control radius half the patch).
PpaOptions takePpaOptions(CommandLine& cl, int patch)
{
  PpaOptions ppa;
  ppa.controlRadius = 0.5 * patch;
  const std::vector<OptionRow>& rows = ppaOptionRows();
  const auto take = [&](const char* property, auto& target)
  {
    if (const auto v = takeRowNumber(cl, optionRow(rows, property)))
    {
      target = static_cast<std::remove_reference_t<decltype(target)>>(*v);
    }
  };
  take("HalfProfileLength", ppa.halfProfileLength);
  take("EndReductions", ppa.endReductions);
  take("MinimumBranchLength", ppa.minBranchLength);
  take("MinimumTreeSize", ppa.minTreeSize);
  take("RelativeDip", ppa.relativeDip);
  take("MinimumDip", ppa.minDip);
  take("PresmoothSigma", ppa.presmoothSigma);
  take("Significance", ppa.significance);
  take("SignificanceNoise", ppa.significanceNoise);
  take("SignificanceRadius", ppa.significanceRadius);
  return ppa;
}

// The feature tree of a .vtp sketch in metres, on the grid of `cell` metres its
// lines reach (or their GridSize frame): the synthesis' own checks refuse
// coordinates that are not finite, lie west or south of the frame, or reach
// beyond any grid.
FeatureGraph polylineSketchFeatures(const std::string& path,
  double cell,
  int patch,
  std::vector<std::string>& warnings)
{
  vtkNew<vtkPolyData> lines;
  readPolyDataFile(path, lines);
  std::string warning;
  const PolylineSketch sketch = polyDataToPolylineSketch(lines, &warning);
  if (!warning.empty())
  {
    warnings.push_back(warning);
  }
  SetupOptionNames names;
  names.cell = "--cell";
  names.patch = "--patch";
  const OutputGrid grid = outputGrid(polylineExtent(sketch), {}, cell, cell, patch, names);
  AnalysedSketch analysed = analyseSketch(sketch, grid, patch);
  warnings.insert(warnings.end(), analysed.warnings.begin(), analysed.warnings.end());
  return std::move(analysed.graph);
}

// --features WORD, or its shorthands --valleys and --both; the table's default without any.
FeatureSelection takeFeatureSelection(CommandLine& cl)
{
  const OptionRow& row = optionRow(ppaOptionRows(), "Features");
  const std::optional<int> word = takeRowChoice(cl, row);
  const bool valleys = cl.takeFlag("--valleys");
  const bool both = cl.takeFlag("--both");
  const int given = (word ? 1 : 0) + (valleys ? 1 : 0) + (both ? 1 : 0);
  if (given > 1)
  {
    throw UsageError("Give one of --features, --valleys and --both.");
  }
  if (valleys || both)
  {
    return valleys ? FeatureSelection::Valleys : FeatureSelection::Both;
  }
  return static_cast<FeatureSelection>(word.value_or(static_cast<int>(row.defaultValue)));
}

// Everything `tsynth features` was asked to do, checked.
struct FeaturesArguments
{
  std::string input;
  std::string output;
  std::optional<std::string> controlOutput;
  FeatureSelection selection = FeatureSelection::Both;
  bool sketch = false;
  int patch = kDefaultSynthesisPatch;
  PpaOptions ppa;
  ReadOptions read;
};

FeaturesArguments parseFeaturesArguments(std::vector<std::string> args)
{
  CommandLine cl(std::move(args));
  FeaturesArguments a;
  const std::optional<std::string> output = cl.take("--output", "-o");
  a.controlOutput = cl.take("--control-points");
  a.selection = takeFeatureSelection(cl);
  a.sketch = cl.takeFlag("--sketch");
  a.patch =
    takeCount(cl, "--patch", kMinFeaturePatch, kMaxFeaturePatch).value_or(kDefaultSynthesisPatch);
  a.ppa = takePpaOptions(cl, a.patch);
  a.read = takeReadOptions(cl);
  a.input = oneInput(cl, "features");
  if (!output)
  {
    throw UsageError("tsynth features needs an output file: -o FEATURES.vtp.");
  }
  a.output = *output;
  if (!hasExtension(a.output, ".vtp") ||
    (a.controlOutput && !hasExtension(*a.controlOutput, ".vtp")))
  {
    throw UsageError("Feature trees are written as .vtp files.");
  }
  return a;
}

// The lines found, with the reader's and the extraction's warnings.
struct ExtractedFeatures
{
  FeatureGraph graph;
  std::vector<std::string> warnings;
  PpaStatistics significance; // of a DEM's ridges or valleys; zero for sketches
};

// The sketch's cell size: --cell, or 1 m when not given.
double sketchCell(const ReadOptions& read)
{
  return read.cellX > 0.0 ? read.cellX : 1.0;
}

ExtractedFeatures imageSketchFeatures(const FeaturesArguments& a)
{
  SketchOptions so;
  so.patchSize = a.patch;
  so.controlRadius = a.ppa.controlRadius;
  so.cellSize = sketchCell(a.read);
  SketchFeatures s = sketchFeatures(readColourImage(a.input), so);
  ExtractedFeatures out;
  out.graph = std::move(s.graph);
  out.warnings = std::move(s.warnings);
  return out;
}

// A DEM read for its lines; a colour image gets a hint that it may be a sketch.
Heightfield readFeatureDem(const FeaturesArguments& a)
{
  try
  {
    return readDem(a.input, a.read);
  }
  catch (const Error& e)
  {
    const std::string message = e.what();
    if (message.find("bands") != std::string::npos)
    {
      throw Error(message + " For a sketch image add --sketch.");
    }
    throw;
  }
}

ExtractedFeatures demFeatures(const FeaturesArguments& a)
{
  FeatureExtraction e = extractSelectedFeatures(readFeatureDem(a), a.selection, a.ppa);
  ExtractedFeatures out;
  out.graph = std::move(e.graph);
  out.warnings = std::move(e.warnings);
  out.significance = e.statistics;
  return out;
}

ExtractedFeatures extractAnyFeatures(const FeaturesArguments& a)
{
  if (a.sketch && hasExtension(a.input, ".vtp"))
  {
    ExtractedFeatures out;
    out.graph = polylineSketchFeatures(a.input, sketchCell(a.read), a.patch, out.warnings);
    return out;
  }
  return a.sketch ? imageSketchFeatures(a) : demFeatures(a);
}

void writeFeatures(const FeaturesArguments& a, const FeatureGraph& graph)
{
  vtkNew<vtkPolyData> tree;
  featureGraphToPolyData(graph, tree);
  writePolyDataFile(a.output, tree);
  if (a.controlOutput)
  {
    vtkNew<vtkPolyData> controls;
    controlPointsToPolyData(graph, controls);
    writePolyDataFile(*a.controlOutput, controls);
  }
}

void printFeatureSummary(const ExtractedFeatures& f, const PpaOptions& ppa, double seconds)
{
  const FeatureGraph& graph = f.graph;
  std::cout << std::fixed << std::setprecision(2) << "Features: " << graph.nodes.size()
            << " nodes (" << graph.countKind(NodeKind::Branch) << " branch, "
            << graph.countKind(NodeKind::End) << " end, " << graph.countKind(NodeKind::Path)
            << " loop anchors), " << graph.chains.size() << " chains in " << graph.componentCount
            << " trees; " << seconds << " s\n";
  if (f.significance.significantDrop > 0.0)
  {
    std::cout << "Significance: features stand " << f.significance.significantDrop
              << " m above their sides within " << ppa.significanceRadius << " cells (relief "
              << f.significance.relief << " m, noise sigma " << f.significance.noise << " m)\n";
  }
}

} // namespace

int runFeatures(std::vector<std::string> args)
{
  if (wantsHelp(args))
  {
    std::cout << withOptionRows(withPatchDefault(kFeaturesHelp), ppaOptionRows())
              << kReadOptionsHelp;
    return 0;
  }
  const FeaturesArguments a = parseFeaturesArguments(std::move(args));
  FileRoles files;
  files.input(a.input, a.sketch ? "the sketch" : "the DEM", a.read.useSidecar);
  files.output(a.output, "-o");
  if (a.controlOutput)
  {
    files.output(*a.controlOutput, "--control-points");
  }
  files.check();

  // Ctrl-C stops the extraction (tsynth::Cancelled) before anything is written; once writing
  // has begun it only sets the flag, so no file is left half-written.
  const InterruptGuard interrupt;
  const auto t0 = std::chrono::steady_clock::now();
  const ExtractedFeatures f = extractAnyFeatures(a);
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  printWarnings(f.warnings);
  writeFeatures(a, f.graph);
  printFeatureSummary(f, a.ppa, seconds);
  std::cout << "Wrote " << a.output << "\n";
  return 0;
}

} // namespace tsynth::cli
