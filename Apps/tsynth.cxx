// tsynth: the TerrainSynthesis command line. Every command exits 0 on success,
// 1 with one sentence on bad input or failure, 2 on wrong usage.
#include "CliSupport.h"
#include "CommandLine.h"
#include "ConvertCommand.h"
#include "DistanceCommand.h"
#include "HydrologyCommands.h"
#include "Render3D.h"
#include "SynthCommands.h"
#include "TerrainFileIO.h"

#include "Analysis/Hillshade.h"
#include "Analysis/ReliefImage.h"
#include "Core/Error.h"
#include "Core/FileRoles.h"
#include "Core/HeightfieldIO.h"
#include "Core/Memory.h"
#include "FeatureGraphConversion.h"
#include "Features/Ppa.h"
#include "Features/Sketch.h"
#include "Synthesis/Setup.h"

#include <nlohmann/json.hpp>
#include <vtkNew.h>
#include <vtkPolyData.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <dlfcn.h>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <type_traits>
#include <unistd.h>
#include <vector>

namespace
{

using tsynth::hasExtension;
using tsynth::cli::CommandLine;
using tsynth::cli::kReadOptionsHelp;
using tsynth::cli::oneInput;
using tsynth::cli::readDem;
using tsynth::cli::takeCount;
using tsynth::cli::takeReadOptions;
using tsynth::cli::UsageError;
using tsynth::cli::wantsHelp;
using tsynth::cli::withPatchDefault;

// The 3D view's picture size: smaller shows nothing; larger than most
// OpenGL implementations' largest framebuffer.
constexpr int kMinPictureSide = 16;
constexpr int kMaxPictureSide = 8192;

const char* const kMainHelp = R"(tsynth: example-based terrain synthesis from real DEMs.

Usage: tsynth COMMAND [options]

Commands:
  info DEM               size, cell size, height range, CRS and units of a DEM
  render DEM -o PNG      hillshade picture with a colour ramp; --3d for an oblique 3D view
  convert DEM -o OUT     write a DEM as GeoTIFF float32 (.tif), 16-bit PNG + sidecar (.png) or .vti;
                         --tile-size N: tiles sharing their edges (GeoTIFF + .vrt, engine PNG/RAW)
  features DEM -o F.vtp  ridge (or valley) lines as a feature tree (PPA); --sketch for sketches
  synth --exemplar DEM --sketch SKETCH -o OUT   synthesise a terrain that follows a sketch
  evaluate TERRAIN --exemplar DEM [--sketch S]  quality figures, with baselines
  pits DEM -o OUT        remove depressions (breach, fill or hybrid); flow accumulation, streams
  optimise --exemplar DEM --guide GUIDE -o OUT  terrain optimisation (Scott & Dodgson 2021)
  distance --generators STROKES -o OUT  distance-based synthesis, no exemplar (Rusnell 2009)

Run "tsynth COMMAND --help" for a command's options.
)";

const char* const kInfoHelp = R"(Usage: tsynth info DEM [--json] [read options]

Prints the size, cell size (metres), height range (metres), nodata share, CRS and
units of a DEM. --json prints the same as a JSON object.
)";

const char* const kRenderHelp = R"(Usage: tsynth render DEM -o OUT.png [--3d] [options]

Writes a picture of the terrain: a multi-directional hillshade tinted by height,
one pixel per cell. With --3d, an oblique lit 3D view instead (needs an X display;
without one tsynth re-runs itself under xvfb-run).

  -o, --output PNG       the picture to write (.png)
  --3d                   oblique 3D view
  --grey                 the hillshade alone, in grey (the map only)
  --exaggeration F       vertical exaggeration, from 0.001 to 1000 (default 1 for the map,
                         2 for --3d)
  --altitude DEG         sun elevation for the map, from 0 to 90 (default 45)
  --azimuth DEG          single light from this direction, clockwise from north, 0 to 360
  --size WxH             3D picture size in pixels (default 1600x1000)
)";

const char* const kFeaturesHelp =
  R"(Usage: tsynth features DEM -o FEATURES.vtp [--valleys | --both] [options]
       tsynth features SKETCH --sketch -o FEATURES.vtp [options]

Extracts ridge lines (or valleys, or both) as a feature tree with PPA and writes it
as VTK poly-lines in metres (open it in ParaView over the DEM; colour by NodeKind).
With --sketch the input is a sketch: a grey sketch map or an RGB stroke map (red
ridges, blue valleys), or a .vtp of poly-lines with a FeatureType cell array.

  -o, --output F.vtp         the feature tree
  --valleys | --both         valleys instead of ridges, or both
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

int runInfo(std::vector<std::string> args)
{
  if (wantsHelp(args))
  {
    std::cout << kInfoHelp << kReadOptionsHelp;
    return 0;
  }
  CommandLine cl(std::move(args));
  const bool json = cl.takeFlag("--json");
  const tsynth::ReadOptions options = takeReadOptions(cl);
  const std::string path = oneInput(cl, "info");

  tsynth::RasterInfo info;
  const tsynth::Heightfield hf = readDem(path, options, &info);
  const tsynth::HeightRange range = tsynth::computeHeightRange(hf);
  const std::size_t invalid = hf.size() - range.validCells;
  const double invalidShare = 100.0 * static_cast<double>(invalid) / static_cast<double>(hf.size());
  const std::string crs = info.crsName.empty() ? "none" : info.crsName;

  if (json)
  {
    // nlohmann escapes quotes, backslashes and control characters in paths and
    // replaces bytes that are not UTF-8, so the output is always valid JSON.
    const nlohmann::ordered_json doc = { { "file", path },
      { "format", info.driver },
      { "data_type", info.dataType },
      { "width", hf.width },
      { "height", hf.height },
      { "cell_size_m", { hf.cellX, hf.cellY } },
      { "cell_size_source", info.cellSizeSource },
      { "z_min_m", range.min },
      { "z_max_m", range.max },
      { "z_mean_m", range.mean },
      { "source_z_unit", tsynth::zUnitName(info.zUnit) },
      { "z_unit_source", info.zUnitSource },
      { "normalised", info.normalised },
      { "nodata_cells", invalid },
      { "crs", crs },
      { "geographic", info.georef.isGeographic },
      { "sidecar", info.sidecarPath } };
    std::cout << doc.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
    return 0;
  }
  std::cout << std::fixed;
  std::cout << "File:       " << path << "\n";
  std::cout << "Format:     " << info.driver << ", " << info.dataType
            << (info.bands > 1 ? ", " + std::to_string(info.bands) + " bands" : std::string())
            << "\n";
  std::cout << "Size:       " << hf.width << " x " << hf.height << " cells ("
            << std::setprecision(2) << hf.width * hf.cellX / 1000.0 << " x "
            << hf.height * hf.cellY / 1000.0 << " km)\n";
  std::cout << "Cell size:  " << std::setprecision(3) << hf.cellX << " x " << hf.cellY << " m ("
            << info.cellSizeSource << ")\n";
  std::cout << "Heights:    " << std::setprecision(2) << range.min << " to " << range.max
            << " m, mean " << range.mean << " m\n";
  std::cout << "Stored in:  " << (info.zUnit == tsynth::ZUnit::Feet ? "feet" : "metres") << " ("
            << info.zUnitSource << ")"
            << "\n";
  if (info.normalised)
  {
    std::cout << "Range:      codes map linearly onto " << std::setprecision(2) << info.zMin
              << " to " << info.zMax << " " << tsynth::zUnitName(info.zUnit) << "\n";
  }
  std::cout << "Nodata:     " << invalid << " cells (" << std::setprecision(2) << invalidShare
            << "%)\n";
  std::cout << "CRS:        " << crs << (info.georef.isGeographic ? " (geographic)" : "") << "\n";
  if (!info.sidecarPath.empty())
  {
    std::cout << "Sidecar:    " << info.sidecarPath << "\n";
  }
  return 0;
}

// Re-runs this command under xvfb-run when there is no X display for --3d.
// True if an X server answers at $DISPLAY. Asked through libX11 (loaded here, as VTK's
// window would load it): VTK's own attempt aborts the process when nothing answers.
bool displayAnswers()
{
  void* x11 = dlopen("libX11.so.6", RTLD_NOW | RTLD_LOCAL);
  if (x11 == nullptr)
  {
    return false;
  }
  using OpenDisplay = void* (*)(const char*);
  using CloseDisplay = int (*)(void*);
  const auto open = reinterpret_cast<OpenDisplay>(dlsym(x11, "XOpenDisplay"));
  const auto close = reinterpret_cast<CloseDisplay>(dlsym(x11, "XCloseDisplay"));
  void* connection = open != nullptr && close != nullptr ? open(nullptr) : nullptr;
  if (connection != nullptr)
  {
    close(connection);
  }
  dlclose(x11);
  return connection != nullptr;
}

void ensureDisplay(int argc, char** argv)
{
  const char* display = std::getenv("DISPLAY");
  if (display != nullptr && *display != '\0')
  {
    if (displayAnswers())
    {
      return;
    }
    if (std::getenv("TSYNTH_UNDER_XVFB") != nullptr)
    {
      throw tsynth::Error("--3d needs an X display and xvfb-run did not provide one.");
    }
    std::cerr << "tsynth: warning: no X server answers at DISPLAY=" << display
              << "; rendering under xvfb-run instead.\n";
    unsetenv("DISPLAY");
  }
  if (std::getenv("TSYNTH_UNDER_XVFB") != nullptr)
  {
    throw tsynth::Error("--3d needs an X display and xvfb-run did not provide one.");
  }
  setenv("TSYNTH_UNDER_XVFB", "1", 1);
  std::vector<char*> command = { const_cast<char*>("xvfb-run"),
    const_cast<char*>("-a"),
    const_cast<char*>("-s"),
    const_cast<char*>("-screen 0 1920x1200x24") };
  for (int k = 0; k < argc; ++k)
  {
    command.push_back(argv[k]);
  }
  command.push_back(nullptr);
  execvp("xvfb-run", command.data());
  throw tsynth::Error("--3d needs an X display: set DISPLAY or install xvfb (xvfb-run).");
}

// Settings the C library and OpenMP read once at start-up, so synth re-runs
// itself with them (once: the second run finds them set):
// - glibc.malloc.hugetlb=1 (GLIBC_TUNABLES): malloc asks for transparent huge
//   pages, where the system gives them on request (THP mode "madvise", as
//   here). A 1024^2 synthesis touches 270 MB of fresh memory; in 4 KB pages
//   that was 67,000 page faults and 0.3-0.4 s of a 5.7 s run, in 2 MB pages
//   4,000. Left alone if the user set the tunable either way.
// - OMP_WAIT_POLICY=passive unless the user chose a policy or --backend cpu:
//   libgomp's threads spin for milliseconds after each parallel region and
//   took the cores PoCL's threads need (fill 20% faster passive), and on a
//   machine busy with other work the cores everything else needs (a preview,
//   all small parallel regions, took 2.9 s instead of 0.2 s beside another
//   run with spinning threads). On an idle machine spinning gains a few
//   percent on the CPU backend, which --backend cpu keeps.
void tuneRuntimes(const std::vector<std::string>& args, char** argv)
{
  bool changed = false;
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  const std::string given = tunables != nullptr ? tunables : "";
  if (given.find("glibc.malloc.hugetlb") == std::string::npos)
  {
    const std::string hugePages = "glibc.malloc.hugetlb=1";
    setenv("GLIBC_TUNABLES", (given.empty() ? hugePages : given + ":" + hugePages).c_str(), 1);
    changed = true;
  }
  bool cpu = false;
  for (std::size_t k = 0; k + 1 < args.size(); ++k)
  {
    cpu = cpu || (args[k] == "--backend" && args[k + 1] == "cpu");
  }
  if (!cpu && std::getenv("OMP_WAIT_POLICY") == nullptr)
  {
    setenv("OMP_WAIT_POLICY", "passive", 1);
    changed = true;
  }
  if (changed)
  {
    execv("/proc/self/exe", argv); // returns only on failure: carry on as we are
  }
}

int runRender(std::vector<std::string> args, int argc, char** argv)
{
  if (wantsHelp(args))
  {
    std::cout << kRenderHelp << kReadOptionsHelp;
    return 0;
  }
  CommandLine cl(std::move(args));
  const std::optional<std::string> output = cl.take("--output", "-o");
  const bool threeD = cl.takeFlag("--3d");
  const bool grey = cl.takeFlag("--grey");
  const std::vector<tsynth::OptionRow>& rows = tsynth::hillshadeOptionRows();
  const std::optional<double> exaggeration = takeRowNumber(cl, tsynth::optionRow(rows, "ZFactor"));
  const std::optional<double> altitude = takeRowNumber(cl, tsynth::optionRow(rows, "Altitude"));
  const std::optional<double> azimuth = takeRowNumber(cl, tsynth::optionRow(rows, "Azimuth"));
  const std::optional<std::string> size = cl.take("--size");
  const tsynth::ReadOptions options = takeReadOptions(cl);
  const std::string path = oneInput(cl, "render");
  if (!output)
  {
    throw UsageError("tsynth render needs an output picture: -o OUT.png.");
  }
  if (!hasExtension(*output, ".png"))
  {
    throw UsageError("The picture must be a .png file, not " + *output + ".");
  }
  if (size && !threeD)
  {
    throw UsageError("--size applies to the 3D view (--3d); the map has one pixel per cell.");
  }
  if (grey && threeD)
  {
    throw UsageError("--grey shades the map; the 3D view has its own colours.");
  }
  if ((altitude || azimuth) && threeD)
  {
    throw UsageError("--altitude and --azimuth light the map; the 3D view has its own lights.");
  }
  tsynth::Render3DOptions view;
  if (size)
  {
    const auto sides = tsynth::cli::parseSides(*size);
    const auto inRange = [](int v) { return v >= kMinPictureSide && v <= kMaxPictureSide; };
    if (!sides || !inRange(sides->first) || !inRange(sides->second))
    {
      throw UsageError("--size expects WxH between " + std::to_string(kMinPictureSide) + " and " +
        std::to_string(kMaxPictureSide) + " pixels, e.g. 1600x1000, not \"" + *size + "\".");
    }
    view.width = sides->first;
    view.height = sides->second;
  }
  tsynth::FileRoles files;
  files.input(path, "the DEM", options.useSidecar);
  files.output(*output, "-o", tsynth::FileRoles::Content::Other);
  files.check();

  const tsynth::Heightfield hf = readDem(path, options);
  if (threeD)
  {
    ensureDisplay(argc, argv);
    view.exaggeration = exaggeration.value_or(2.0);
    tsynth::render3D(hf, *output, view);
  }
  else
  {
    tsynth::HillshadeOptions shading;
    shading.zFactor = exaggeration.value_or(shading.zFactor);
    shading.altitudeDeg = altitude.value_or(shading.altitudeDeg);
    if (azimuth)
    {
      shading.multidirectional = false;
      shading.azimuthDeg = *azimuth;
    }
    const tsynth::ShadedRelief relief = tsynth::computeHillshade(hf, shading);
    tsynth::writeRgbPng(*output,
      hf.width,
      hf.height,
      grey ? tsynth::renderGreyRelief(hf, relief) : tsynth::renderRelief(hf, relief));
  }
  std::cout << "Wrote " << *output << "\n";
  return 0;
}

// The PPA options of `tsynth features` (control radius half the patch).
tsynth::PpaOptions takePpaOptions(CommandLine& cl, int patch)
{
  tsynth::PpaOptions ppa;
  ppa.controlRadius = 0.5 * patch;
  const std::vector<tsynth::OptionRow>& rows = tsynth::ppaOptionRows();
  const auto take = [&](const char* property, auto& target)
  {
    if (const auto v = takeRowNumber(cl, tsynth::optionRow(rows, property)))
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
tsynth::FeatureGraph polylineSketchFeatures(const std::string& path,
  double cell,
  int patch,
  std::vector<std::string>& warnings)
{
  vtkNew<vtkPolyData> lines;
  tsynth::readPolyDataFile(path, lines);
  std::string warning;
  const tsynth::PolylineSketch sketch = tsynth::polyDataToPolylineSketch(lines, &warning);
  if (!warning.empty())
  {
    warnings.push_back(warning);
  }
  tsynth::SetupOptionNames names;
  names.cell = "--cell";
  names.patch = "--patch";
  const tsynth::OutputGrid grid =
    tsynth::outputGrid(tsynth::polylineExtent(sketch), {}, cell, cell, patch, names);
  tsynth::AnalysedSketch analysed = tsynth::analyseSketch(sketch, grid, patch);
  warnings.insert(warnings.end(), analysed.warnings.begin(), analysed.warnings.end());
  return std::move(analysed.graph);
}

int runFeatures(std::vector<std::string> args)
{
  if (wantsHelp(args))
  {
    std::cout << withPatchDefault(kFeaturesHelp) << kReadOptionsHelp;
    return 0;
  }
  CommandLine cl(std::move(args));
  const std::optional<std::string> output = cl.take("--output", "-o");
  const std::optional<std::string> controlOutput = cl.take("--control-points");
  const bool valleys = cl.takeFlag("--valleys");
  const bool both = cl.takeFlag("--both");
  const bool sketch = cl.takeFlag("--sketch");
  const int patch = takeCount(cl, "--patch", 8, 4096).value_or(80);
  const tsynth::PpaOptions ppa = takePpaOptions(cl, patch);
  const tsynth::ReadOptions options = takeReadOptions(cl);
  const std::string path = oneInput(cl, "features");
  if (!output)
  {
    throw UsageError("tsynth features needs an output file: -o FEATURES.vtp.");
  }
  if (!hasExtension(*output, ".vtp") || (controlOutput && !hasExtension(*controlOutput, ".vtp")))
  {
    throw UsageError("Feature trees are written as .vtp files.");
  }
  if (valleys && both)
  {
    throw UsageError("Give --valleys or --both, not both.");
  }
  tsynth::FileRoles files;
  files.input(path, sketch ? "the sketch" : "the DEM", options.useSidecar);
  files.output(*output, "-o");
  if (controlOutput)
  {
    files.output(*controlOutput, "--control-points");
  }
  files.check();

  // Ctrl-C stops the extraction (tsynth::Cancelled) before anything is written; once writing
  // has begun it only sets the flag, so no file is left half-written.
  const tsynth::cli::InterruptGuard interrupt;
  const auto t0 = std::chrono::steady_clock::now();
  tsynth::FeatureGraph graph;
  std::vector<std::string> warnings;
  tsynth::PpaStatistics significance;
  if (sketch && hasExtension(path, ".vtp"))
  {
    graph =
      polylineSketchFeatures(path, options.cellX > 0.0 ? options.cellX : 1.0, patch, warnings);
  }
  else if (sketch)
  {
    tsynth::SketchOptions so;
    so.patchSize = patch;
    so.controlRadius = ppa.controlRadius;
    so.cellSize = options.cellX > 0.0 ? options.cellX : 1.0;
    tsynth::SketchFeatures s = tsynth::sketchFeatures(tsynth::readColourImage(path), so);
    graph = std::move(s.graph);
    warnings = s.warnings;
  }
  else
  {
    tsynth::Heightfield hf;
    try
    {
      hf = readDem(path, options);
    }
    catch (const tsynth::Error& e)
    {
      const std::string message = e.what();
      if (message.find("bands") != std::string::npos)
      {
        throw tsynth::Error(message + " For a sketch image add --sketch.");
      }
      throw;
    }
    graph.width = hf.width;
    graph.height = hf.height;
    graph.cellX = hf.cellX;
    graph.cellY = hf.cellY;
    for (tsynth::FeatureType type : { tsynth::FeatureType::Ridge, tsynth::FeatureType::Valley })
    {
      const bool wanted = both || (type == tsynth::FeatureType::Valley) == valleys;
      if (wanted)
      {
        tsynth::FeatureExtraction e = tsynth::extractFeatures(hf, type, ppa);
        significance = e.statistics; // the relief and drop are the same for both types
        tsynth::appendGraph(graph, e.graph);
        warnings.insert(warnings.end(), e.warnings.begin(), e.warnings.end());
      }
    }
  }
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  for (const std::string& w : warnings)
  {
    std::cerr << "tsynth: warning: " << w << "\n";
  }
  vtkNew<vtkPolyData> tree;
  tsynth::featureGraphToPolyData(graph, tree);
  tsynth::writePolyDataFile(*output, tree);
  if (controlOutput)
  {
    vtkNew<vtkPolyData> controls;
    tsynth::controlPointsToPolyData(graph, controls);
    tsynth::writePolyDataFile(*controlOutput, controls);
  }
  std::cout << std::fixed << std::setprecision(2) << "Features: " << graph.nodes.size()
            << " nodes (" << graph.countKind(tsynth::NodeKind::Branch) << " branch, "
            << graph.countKind(tsynth::NodeKind::End) << " end, "
            << graph.countKind(tsynth::NodeKind::Path) << " loop anchors), " << graph.chains.size()
            << " chains in " << graph.componentCount << " trees; " << seconds << " s\n";
  if (significance.significantDrop > 0.0)
  {
    std::cout << "Significance: features stand " << significance.significantDrop
              << " m above their sides within " << ppa.significanceRadius << " cells (relief "
              << significance.relief << " m, noise sigma " << significance.noise << " m)\n";
  }
  std::cout << "Wrote " << *output << "\n";
  return 0;
}

// Runs the command; false in `known` if there is no such command (UsageError).
int dispatch(const std::string& command,
  std::vector<std::string> args,
  int argc,
  char** argv,
  bool& known)
{
  if (command == "info")
  {
    return runInfo(std::move(args));
  }
  if (command == "render")
  {
    return runRender(std::move(args), argc, argv);
  }
  if (command == "convert")
  {
    return tsynth::cli::runConvert(std::move(args));
  }
  if (command == "features")
  {
    return runFeatures(std::move(args));
  }
  if (command == "synth")
  {
    tuneRuntimes(args, argv);
    return tsynth::cli::runSynth(std::move(args));
  }
  if (command == "pits")
  {
    return tsynth::cli::runPits(std::move(args));
  }
  if (command == "optimise" || command == "optimize")
  {
    return tsynth::cli::runOptimise(std::move(args));
  }
  if (command == "distance")
  {
    return tsynth::cli::runDistance(std::move(args));
  }
  if (command == "evaluate")
  {
    return tsynth::cli::runEvaluate(std::move(args));
  }
  known = false;
  throw UsageError("Unknown command \"" + command + "\".");
}

} // namespace

int main(int argc, char** argv)
{
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help")
  {
    std::cout << kMainHelp;
    return args.empty() ? 2 : 0;
  }
  const std::string command = args[0];
  args.erase(args.begin());
  tsynth::cli::removePartialFilesOnSignals();
  tsynth::reuseFreedWorkMemory();
  bool knownCommand = true; // until no command matched: then the help to see is the main one
  // Every file the command writes is staged here and appears only when the command succeeded.
  tsynth::Publication outputs;
  try
  {
    const int status = dispatch(command, std::move(args), argc, argv, knownCommand);
    return tsynth::cli::publishOutputs(status, outputs);
  }
  catch (const UsageError& e)
  {
    std::cerr << "tsynth: " << e.what()
              << " See \"tsynth " + (knownCommand ? command + " --help" : std::string("--help"))
              << "\".\n";
    return 2;
  }
  catch (const tsynth::Cancelled&)
  {
    std::cerr << "\ntsynth: stopped; nothing was written.\n";
    return tsynth::cli::interruptedExit();
  }
  catch (const tsynth::Error& e)
  {
    std::cerr << "tsynth: " << e.what() << "\n";
    return 1;
  }
  catch (const std::exception& e)
  {
    std::cerr << "tsynth: unexpected failure: " << e.what() << "\n";
    return 1;
  }
}
