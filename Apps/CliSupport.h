// What the command line's sub-commands share: help detection, warnings, the
// a progress bar, and the parsers of --size and --seed.
#pragma once

#include "CommandLine.h"

#include "Core/Cancellation.h"
#include "Core/HeightfieldIO.h"
#include "Core/OptionTable.h"
#include "Core/OutputFile.h"
#include "Synthesis/Setup.h"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace tsynth::cli
{

// A help text with every %PATCH% replaced by the synthesis patch's default
// (Core/PatchSize.h), and %DEFAULT:P%, %RANGE:P% and %WORDS:P% by the default,
// the range and the words of the synthesis option whose property is P
// (Synthesis/SynthesisRequest.h), so the help cannot drift from them.
std::string withPatchDefault(std::string help);
// The same for another algorithm's table.
std::string withOptionRows(std::string help, const std::vector<OptionRow>& rows);

// True if the arguments ask for --help (or -h).
bool wantsHelp(const std::vector<std::string>& args);

// Prints each as "tsynth: warning: ..." on stderr.
void printWarnings(const std::vector<std::string>& warnings);

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

// tsynth::Error unless the folder `path` exists or can be created (its nearest
// existing ancestor is a writable folder), checked before any work.
void requireCreatableFolder(const std::string& path);

// A command stopped by a signal exits 128 + the signal's number, as shells report it.
constexpr int kSignalExitBase = 128;
// The exit status of a run stopped by Ctrl-C (128 + SIGINT).
constexpr int kInterruptedExit = 130;

// For the whole run of a command: a terminating signal (SIGINT, SIGTERM, SIGHUP, SIGQUIT,
// SIGPIPE, SIGALRM, SIGUSR1, SIGUSR2, SIGXCPU, SIGXFSZ, SIGVTALRM) outside an InterruptGuard
// removes the temporaries of the files being written and staged (OutputFile, Publication)
// and ends the process as the signal would, so no partial file is left behind.
void removePartialFilesOnSignals();

// While it lives, SIGINT (Ctrl-C), SIGTERM, SIGHUP and SIGQUIT only set a flag, which long
// commands poll (check() throws tsynth::Cancelled), and so do the kernels' own long loops
// through the cancellation scope it opens (Core/Cancellation.h); the previous handlers come
// back after. The flag stays set after the guard: the command's outputs are then not
// published (stopRequested).
class InterruptGuard
{
public:
  InterruptGuard();
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;
  bool interrupted() const;
  void check() const;
  // Installs this guard's handlers again, and the partial-file handlers for the other
  // terminating signals: a library may have replaced them. LLVM (which PoCL compiles kernels
  // with) does, and its handlers swallow SIGQUIT, SIGUSR1, SIGXCPU and SIGXFSZ.
  void reclaim() const;

  // SIGINT, SIGTERM, SIGHUP and SIGQUIT.
  static constexpr std::size_t kStopSignalCount = 4;

private:
  void (*previous_[kStopSignalCount])(int) = {};
  CancellationScope scope_;
};

// After a command returned `status`: its outputs (staged in `outputs`) are published if it
// succeeded, no stop signal came, and standard output took everything printed to it;
// otherwise they are discarded with the Publication. Returns the exit status; throws
// tsynth::Error if standard output or a rename failed.
int publishOutputs(int status, Publication& outputs);

// True once a stop signal reached an InterruptGuard in this run.
bool stopRequested();
// 128 + the stop signal an InterruptGuard received (130 for Ctrl-C).
int interruptedExit();

// An option of an algorithm's table (Core/OptionTable.h) under its row's flag: a number
// checked against the row's range, or one of the row's words as its value. UsageError, naming
// the range or the words, for anything else.
std::optional<double> takeRowNumber(CommandLine& cl, const OptionRow& row);
std::optional<int> takeRowChoice(CommandLine& cl, const OptionRow& row);

// --max-memory GB, in bytes (0 if not given: the kernels' default budget, 80% of
// this machine's memory); UsageError unless a positive number up to kMaxMemoryBudgetGB.
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
