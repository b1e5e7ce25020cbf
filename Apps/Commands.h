// tsynth's commands, one file each: `tsynth NAME` runs runName in NameCommand.cxx.
// Each takes the arguments after the command's name and returns the exit code
// (0 done); wrong usage throws UsageError (exit 2), bad input or failure
// tsynth::Error (exit 1, one sentence), Ctrl-C tsynth::Cancelled.
#pragma once

#include <string>
#include <vector>

namespace tsynth::cli
{

int runInfo(std::vector<std::string> args);     // InfoCommand.cxx
int runConvert(std::vector<std::string> args);  // ConvertCommand.cxx
int runFeatures(std::vector<std::string> args); // FeaturesCommand.cxx
int runSynth(std::vector<std::string> args);    // SynthCommand.cxx
int runEvaluate(std::vector<std::string> args); // EvaluateCommand.cxx
int runPits(std::vector<std::string> args);     // PitsCommand.cxx
int runOptimise(std::vector<std::string> args); // OptimiseCommand.cxx
int runDistance(std::vector<std::string> args); // DistanceCommand.cxx
// RenderCommand.cxx. argc and argv: --3d without an X display re-runs the
// whole command line under xvfb-run.
int runRender(std::vector<std::string> args, int argc, char** argv);

} // namespace tsynth::cli
