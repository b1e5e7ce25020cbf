#include "CliSupport.h"

#include "FeatureGraphConversion.h"
#include "TerrainFileIO.h"

#include "Core/Error.h"
#include "Core/HeightfieldIO.h"
#include "Core/Memory.h"
#include "Core/OutputFile.h"
#include "Core/PatchSize.h"
#include "Synthesis/SynthesisRequest.h"

#include <vtkNew.h>
#include <vtkPolyData.h>

#include <atomic>
#include <cctype>
#include <charconv>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <iterator>
#include <limits>
#include <unistd.h>

namespace tsynth::cli
{
namespace
{

// The signal that stopped the run inside an InterruptGuard, 0 if none.
std::atomic<int> gInterruptSignal{ 0 };

extern "C" void onInterrupt(int sig)
{
  gInterruptSignal = sig;
}

// The signals by which a user, a terminal or a job system asks a command to stop: inside an
// InterruptGuard they stop it cleanly, between kernel steps.
constexpr int kStopSignals[] = { SIGINT, SIGTERM, SIGHUP, SIGQUIT };
static_assert(std::size(kStopSignals) == InterruptGuard::kStopSignalCount);

// Every signal that ends a process by default, other than a crash: outside an InterruptGuard
// (and for those a guard does not take) the temporaries are removed before the process dies.
constexpr int kTerminatingSignals[] = { SIGHUP,
  SIGINT,
  SIGQUIT,
  SIGTERM,
  SIGPIPE,
  SIGALRM,
  SIGUSR1,
  SIGUSR2,
  SIGXCPU,
  SIGXFSZ,
  SIGVTALRM };

using Handler = void (*)(int);

Handler installHandler(int sig, Handler handler)
{
  struct sigaction action
  {
  };
  struct sigaction previous
  {
  };
  action.sa_handler = handler;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  sigaction(sig, &action, &previous);
  return previous.sa_handler;
}

} // namespace

namespace
{

void replaceAll(std::string& text, const std::string& key, const std::string& value)
{
  for (std::size_t at = text.find(key); at != std::string::npos; at = text.find(key, at))
  {
    text.replace(at, key.size(), value);
    at += value.size();
  }
}

std::string defaultText(const OptionRow& row)
{
  if (row.type == OptionType::Choice)
  {
    return row.choices.wordOf(static_cast<int>(row.defaultValue), row.property);
  }
  return numberText(row.defaultValue);
}

} // namespace

std::string withPatchDefault(std::string help)
{
  replaceAll(help, "%PATCH%", std::to_string(kDefaultSynthesisPatch));
  replaceAll(help, "%DEMPATCH%", std::to_string(kDefaultDemTargetPatch));
  replaceAll(help, "%PATCHMIN%", std::to_string(kMinSynthesisPatch));
  replaceAll(help, "%PATCHMAX%", std::to_string(kMaxSynthesisPatch));
  return withOptionRows(help, synthesisOptionRows());
}

std::string withOptionRows(std::string help, const std::vector<OptionRow>& rows)
{
  for (const OptionRow& row : rows)
  {
    replaceAll(help, "%DEFAULT:" + row.property + "%", defaultText(row));
    replaceAll(help, "%RANGE:" + row.property + "%", row.rangeText());
    replaceAll(help, "%WORDS:" + row.property + "%", row.choices.list());
  }
  return help;
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

void printWarnings(const std::vector<std::string>& warnings)
{
  for (const auto& w : warnings)
  {
    std::cerr << "tsynth: warning: " << w << "\n";
  }
}

// The sketch file as the set-up takes it: .vtp poly-lines (metres in the raster
// frame), a DEM used as the target, or a sketch image (stroke map or grey map).
ProgressBar::ProgressBar(bool enabled)
  : enabled_(enabled && ::isatty(STDERR_FILENO) != 0)
{
}

void ProgressBar::operator()(double f, const std::string& stage)
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

std::optional<std::pair<int, int>> parseSides(const std::string& text)
{
  const std::size_t x = text.find('x');
  if (x == std::string::npos)
  {
    return std::nullopt;
  }
  auto side = [&](std::size_t from, std::size_t to) -> std::optional<int>
  {
    int v = 0;
    const char* end = text.data() + to;
    const auto r = std::from_chars(text.data() + from, end, v);
    const bool digits = from < to && std::isdigit(static_cast<unsigned char>(text[from])) != 0;
    if (!digits || r.ptr != end)
    {
      return std::nullopt;
    }
    if (r.ec == std::errc::result_out_of_range)
    {
      return std::numeric_limits<int>::max(); // too large for any range
    }
    return r.ec == std::errc() ? std::optional<int>(v) : std::nullopt;
  };
  const std::optional<int> w = side(0, x);
  const std::optional<int> h = side(x + 1, text.size());
  if (!w || !h)
  {
    return std::nullopt;
  }
  return std::make_pair(*w, *h);
}

// "WxH" in cells, each side from 1 to kMaxOutputSide.
GridRequest parseSize(const std::string& text, GridRequest grid)
{
  const std::optional<std::pair<int, int>> sides = parseSides(text);
  if (!sides || sides->first < 1 || sides->second < 1)
  {
    throw UsageError("--size expects WxH in cells, e.g. 1024x1024, not \"" + text + "\".");
  }
  if (sides->first > kMaxOutputSide || sides->second > kMaxOutputSide)
  {
    throw UsageError("--size " + text + " is beyond any machine: at most " +
      std::to_string(kMaxOutputSide) + " cells a side.");
  }
  grid.width = sides->first;
  grid.height = sides->second;
  return grid;
}

std::optional<double> takeRowNumber(CommandLine& cl, const OptionRow& row)
{
  const std::optional<double> value = cl.takeNumber(row.flag);
  if (value)
  {
    try
    {
      row.checkValue(*value, row.flag);
    }
    catch (const Error& e)
    {
      throw UsageError(e.what());
    }
  }
  return value;
}

std::optional<int> takeRowChoice(CommandLine& cl, const OptionRow& row)
{
  const std::optional<std::string> word = cl.take(row.flag);
  if (!word)
  {
    return std::nullopt;
  }
  try
  {
    return row.choices.valueOf(*word, row.flag);
  }
  catch (const Error& e)
  {
    throw UsageError(e.what());
  }
}

double takeMemoryBudget(CommandLine& cl)
{
  const std::optional<double> budget = cl.takeNumber(kMemoryOption);
  if (!budget)
  {
    return 0.0;
  }
  if (!(*budget > 0.0 && *budget <= kMaxMemoryBudgetGB))
  {
    throw UsageError(std::string(kMemoryOption) + " expects a positive number of GB, at most " +
      std::to_string(static_cast<long long>(kMaxMemoryBudgetGB)) + ".");
  }
  return *budget * kBytesPerGB;
}

// A whole number from 0 to 2^64 - 1.
std::uint64_t parseSeed(const std::string& text)
{
  std::uint64_t seed = 0;
  const char* end = text.data() + text.size();
  const auto r = std::from_chars(text.data(), end, seed);
  if (text.empty() || r.ec != std::errc() || r.ptr != end)
  {
    throw UsageError("--seed expects a whole number from 0 to " +
      std::to_string(std::numeric_limits<std::uint64_t>::max()) + ", not \"" + text + "\".");
  }
  return seed;
}

const char* const kReadOptionsHelp = R"(
Options for reading DEMs (override the NAME.json sidecar and the file):
  --z-unit m|ft          unit of the stored heights (feet are converted to metres)
  --cell M | MX,MY       cell size in metres
  --z-range MIN,MAX      8/16-bit image storing a normalised range: value 0 is MIN, the largest MAX
  --no-sidecar           ignore NAME.json beside the file
)";

namespace
{

// "MIN,MAX" or, with `same` for a single number, "V" (both V); nullopt unless numbers.
std::optional<std::pair<double, double>> parsePair(const std::string& text, bool same)
{
  const std::size_t comma = text.find(',');
  const auto first = parseNumber(text.substr(0, comma));
  const auto second = comma == std::string::npos ? (same ? first : std::nullopt)
                                                 : parseNumber(text.substr(comma + 1));
  if (!first || !second)
  {
    return std::nullopt;
  }
  return std::make_pair(*first, *second);
}

// --cell M or MX,MY: positive, at most the CellSize row's maximum (0 is the filter's "from
// the file", which the option expresses by its absence).
void takeCellSize(CommandLine& cl, ReadOptions& o)
{
  const auto cell = cl.take("--cell");
  if (!cell)
  {
    return;
  }
  const double most = optionRow(readOptionRows(), "CellSize").max;
  const auto xy = parsePair(*cell, true);
  const auto fits = [most](double v) { return v > 0.0 && v <= most; };
  if (!xy || !fits(xy->first) || !fits(xy->second))
  {
    throw UsageError("--cell expects a positive number of metres (at most " + numberText(most) +
      ") or X,Y, not \"" + *cell + "\".");
  }
  o.cellX = xy->first;
  o.cellY = xy->second;
}

// --z-range MIN,MAX within the ZMin and ZMax rows' range, MAX above MIN.
void takeNormalisedRange(CommandLine& cl, ReadOptions& o)
{
  const auto range = cl.take("--z-range");
  if (!range)
  {
    return;
  }
  const auto lohi = parsePair(*range, false);
  if (!lohi || !(lohi->second > lohi->first))
  {
    throw UsageError("--z-range expects MIN,MAX with MAX > MIN, not \"" + *range + "\".");
  }
  try
  {
    optionRow(readOptionRows(), "ZMin").checkValue(lohi->first, "--z-range's MIN");
    optionRow(readOptionRows(), "ZMax").checkValue(lohi->second, "--z-range's MAX");
  }
  catch (const Error& e)
  {
    throw UsageError(e.what());
  }
  o.zMin = lohi->first;
  o.zMax = lohi->second;
}

} // namespace

ReadOptions takeReadOptions(CommandLine& cl)
{
  ReadOptions o;
  if (auto unit = cl.take("--z-unit"))
  {
    const auto parsed = parseZUnit(*unit);
    if (!parsed)
    {
      throw UsageError("--z-unit must be " + optionRow(readOptionRows(), "ZUnit").choices.list() +
        ", not \"" + *unit + "\".");
    }
    o.zUnit = *parsed;
  }
  takeCellSize(cl, o);
  takeNormalisedRange(cl, o);
  o.useSidecar = !cl.takeFlag("--no-sidecar");
  return o;
}

// Reads a DEM and passes on the reader's warnings, one line each.
Heightfield readDem(const std::string& path, const ReadOptions& options, RasterInfo* info)
{
  RasterInfo local;
  RasterInfo& used = info != nullptr ? *info : local;
  Heightfield hf = readTerrainFile(path, options, &used);
  for (const std::string& warning : used.warnings)
  {
    std::cerr << "tsynth: warning: " << warning << "\n";
  }
  return hf;
}

std::string oneInput(const CommandLine& cl, const char* command)
{
  const std::vector<std::string> rest = cl.positionals();
  if (rest.empty())
  {
    throw UsageError(std::string("tsynth ") + command + " needs a DEM file.");
  }
  if (rest.size() > 1)
  {
    throw UsageError("Unexpected argument \"" + rest[1] + "\".");
  }
  return rest[0];
}

std::optional<int> takeCount(CommandLine& cl, const std::string& name, int lo, int hi)
{
  const std::optional<double> v = cl.takeNumber(name);
  if (!v)
  {
    return std::nullopt;
  }
  if (*v != std::floor(*v) || *v < lo || *v > hi)
  {
    throw UsageError(name + " expects a whole number from " + std::to_string(lo) + " to " +
      std::to_string(hi) + ".");
  }
  return static_cast<int>(*v);
}

namespace
{
extern "C" void onFatalSignal(int sig)
{
  OutputFile::removeLiveTemporaries();
  installHandler(sig, SIG_DFL);
  std::raise(sig);
}
} // namespace

void removePartialFilesOnSignals()
{
  for (int sig : kTerminatingSignals)
  {
    installHandler(sig, onFatalSignal);
  }
}

InterruptGuard::InterruptGuard()
  : scope_([] { return gInterruptSignal.load() != 0; })
{
  gInterruptSignal = 0;
  for (std::size_t k = 0; k < std::size(kStopSignals); ++k)
  {
    previous_[k] = installHandler(kStopSignals[k], onInterrupt);
  }
}

InterruptGuard::~InterruptGuard()
{
  for (std::size_t k = 0; k < std::size(kStopSignals); ++k)
  {
    installHandler(kStopSignals[k], previous_[k]);
  }
}

void InterruptGuard::reclaim() const
{
  removePartialFilesOnSignals();
  for (int sig : kStopSignals)
  {
    installHandler(sig, onInterrupt);
  }
}

bool InterruptGuard::interrupted() const
{
  return gInterruptSignal.load() != 0;
}

void InterruptGuard::check() const
{
  if (interrupted())
  {
    throw Cancelled();
  }
}

int interruptedExit()
{
  const int sig = gInterruptSignal.load();
  return kSignalExitBase + (sig != 0 ? sig : SIGINT);
}

bool stopRequested()
{
  return gInterruptSignal.load() != 0;
}

int publishOutputs(int status, Publication& outputs)
{
  if (status != 0)
  {
    return status;
  }
  if (stopRequested())
  {
    std::cerr << "\ntsynth: stopped; nothing was written.\n";
    return interruptedExit();
  }
  std::cout.flush();
  if (!std::cout || std::fflush(stdout) != 0 || std::ferror(stdout) != 0)
  {
    throw Error("Cannot write to standard output (closed, or its disk is full); nothing was "
                "written.");
  }
  outputs.publish();
  return 0;
}

void requireCreatableFolder(const std::string& path)
{
  std::filesystem::path existing(path);
  std::error_code ec;
  while (!existing.empty() && !std::filesystem::exists(existing, ec))
  {
    existing = existing.parent_path();
  }
  if (existing.empty())
  {
    existing = ".";
  }
  if (!std::filesystem::is_directory(existing, ec))
  {
    throw Error(
      "Cannot create the folder " + path + ": " + existing.string() + " is a file, not a folder.");
  }
  checkOutputPath((existing / ".tsynth-folder-probe").string());
}

} // namespace tsynth::cli
