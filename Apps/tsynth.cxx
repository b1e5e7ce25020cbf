// tsynth: the TerrainSynthesis command line. Every command exits 0 on success,
// 1 with one sentence on bad input or failure, 2 on wrong usage. This file
// dispatches; each command lives in its own NameCommand.cxx (Commands.h).
#include "CliSupport.h"
#include "CommandLine.h"
#include "Commands.h"
#include "RuntimeSettings.h"

#include "Core/Error.h"
#include "Core/Memory.h"

#include <cstdlib>
#include <iostream>
#include <string>
#include <unistd.h>
#include <vector>

namespace
{

using tsynth::cli::UsageError;

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

// Run directly (not through the launcher, Launcher.cxx), synth puts its
// start-up settings (RuntimeSettings.h) in place and re-runs itself with them,
// once: the second run finds them set.
void applySynthRuntimeSettings(char** argv)
{
  if (tsynth::cli::setSynthRuntimeSettings())
  {
    execv("/proc/self/exe", argv); // returns only on failure: carry on as we are
  }
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
    return tsynth::cli::runInfo(std::move(args));
  }
  if (command == "render")
  {
    return tsynth::cli::runRender(std::move(args), argc, argv);
  }
  if (command == "convert")
  {
    return tsynth::cli::runConvert(std::move(args));
  }
  if (command == "features")
  {
    return tsynth::cli::runFeatures(std::move(args));
  }
  if (command == "synth")
  {
    applySynthRuntimeSettings(argv);
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