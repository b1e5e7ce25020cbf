// What the command line's sub-commands share: help detection, warnings, the
// sketch reader, a progress bar, and the parsers of --size and --seed.
#pragma once

#include "CommandLine.h"

#include "Synthesis/Setup.h"

#include <cstdint>
#include <string>
#include <vector>

namespace tsynth::cli
{

// True if the file name ends in `wanted` (".json"), ignoring case.
bool hasExtension(const std::string& path, const char* wanted);

// True if the arguments ask for --help (or -h).
bool wantsHelp(const std::vector<std::string>& args);

// Prints each as "tsynth: warning: ..." on stderr.
void printWarnings(const std::vector<std::string>& warnings);

// The sketch file as the set-up takes it: .vtp poly-lines (metres in the raster
// frame), a DEM used as the target, or a sketch image (stroke map or grey map).
SketchInput readSketchInput(const std::string& path, std::vector<std::string>& warnings);

// A one-line progress bar on stderr when it is a terminal.
class ProgressBar
{
public:
  explicit ProgressBar(bool enabled);
  void operator()(double f, const std::string& stage);

private:
  bool enabled_;
};

// "WxH" in cells, each side from 1 to kMaxOutputSide (UsageError otherwise).
GridRequest parseSize(const std::string& text, GridRequest grid);

// A whole number from 0 to 2^64 - 1 (UsageError otherwise).
std::uint64_t parseSeed(const std::string& text);

} // namespace tsynth::cli
