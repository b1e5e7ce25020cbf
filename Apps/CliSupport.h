// What the command line's sub-commands share: help detection, warnings, the
// sketch reader, a progress bar, and the parsers of --size and --seed.
#pragma once

#include "CommandLine.h"

#include "Core/Cancellation.h"
#include "Core/HeightfieldIO.h"
#include "Synthesis/Setup.h"

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
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

// The help text of the DEM read options takeReadOptions parses.
extern const char* const kReadOptionsHelp;

// --z-unit, --cell, --z-range and --no-sidecar.
ReadOptions takeReadOptions(CommandLine& cl);

// Reads a DEM and passes on the reader's warnings, one line each.
Heightfield readDem(const std::string& path,
  const ReadOptions& options,
  RasterInfo* info = nullptr);

// The one positional argument (a DEM) of `command`; UsageError if missing or more.
std::string oneInput(const CommandLine& cl, const char* command);

// A whole-number option from lo to hi, if given (UsageError otherwise).
std::optional<int> takeCount(CommandLine& cl, const std::string& name, int lo, int hi);

// tsynth::Error unless a file can be written at `path` (checkOutputPath: its
// folder exists and takes a new file), checked before any work, so that a long
// run never ends in an unwritable path.
void requireFolder(const std::string& path);

// tsynth::Error unless the folder `path` exists or can be created (its nearest
// existing ancestor is a writable folder), checked before any work.
void requireCreatableFolder(const std::string& path);

// The exit status of a run stopped by Ctrl-C (128 + SIGINT, as shells report it).
constexpr int kInterruptedExit = 130;

// For the whole run of a command: Ctrl-C (SIGINT) or SIGTERM outside an InterruptGuard
// removes the temporaries of the files being written (OutputFile) and ends the process as the
// signal would, so no partial file is left behind.
void removePartialFilesOnSignals();

// While it lives, Ctrl-C (SIGINT) only sets a flag, which long commands poll
// (check() throws tsynth::Cancelled), and so do the kernels' own long loops through the
// cancellation scope it opens (Core/Cancellation.h); the previous handler comes back after.
class InterruptGuard
{
public:
  InterruptGuard();
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;
  bool interrupted() const;
  void check() const;

private:
  void (*previous_)(int);
  CancellationScope scope_;
};

// --max-memory GB, in bytes (0 if not given: the kernels' default budget, 80% of
// this machine's memory); UsageError unless a positive finite number.
double takeMemoryBudget(CommandLine& cl);
// The option's name, as the kernels' refusals name it.
constexpr const char* kMemoryOption = "--max-memory";

// "WxH" as two whole numbers of digits only (no sign, no spaces, nothing after);
// a side too large for an int comes back as INT_MAX, beyond any range. nullopt
// for anything else.
std::optional<std::pair<int, int>> parseSides(const std::string& text);

// "WxH" in cells, each side from 1 to kMaxOutputSide (UsageError otherwise).
GridRequest parseSize(const std::string& text, GridRequest grid);

// A whole number from 0 to 2^64 - 1 (UsageError otherwise).
std::uint64_t parseSeed(const std::string& text);

} // namespace tsynth::cli
