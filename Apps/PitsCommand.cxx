// tsynth pits: depression removal (breach, fill or hybrid), flow accumulation and streams.
#include "Commands.h"

#include "CliSupport.h"
#include "CommandLine.h"
#include "TerrainFileIO.h"

#include "Core/Error.h"
#include "Core/FileRoles.h"
#include "Core/HeightfieldIO.h"
#include "Hydrology/Flow.h"
#include "Hydrology/PitRemoval.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>

namespace tsynth::cli
{
namespace
{

const char* const kPitsHelp =
  R"(Usage: tsynth pits DEM -o OUT [--method M] [options]

Removes depressions so that water from every cell runs downhill to an outlet: the border,
a cell next to nodata, or a sink you keep (--sinks). Prints the pits before and after and
what changed.

  -o, --output OUT       corrected DEM: .tif, .png (+ sidecar) or .vti
  --method M             %WORDS:Method% (default %DEFAULT:Method%). Breach: carve a one-cell
                         channel from each pit to lower ground, never raising a cell (Soille
                         2004; Scott & Dodgson 2021's choice); fill: raise each depression to
                         its spill level with a tiny gradient (Barnes et al. 2014); hybrid:
                         breach where the channel stays within --max-depth and --max-length,
                         fill the rest (Lindsay 2016)
  --max-depth M          hybrid: deepest cut a breach may make, metres, %RANGE:MaxBreachDepth%
                         (default %DEFAULT:MaxBreachDepth%)
  --max-length N         hybrid: longest channel a breach may cut, cells, %RANGE:MaxBreachLength%
                         (default %DEFAULT:MaxBreachLength%)
  --sinks MASK           a raster of the DEM's size, non-zero where water may stay (lakes)
  --flow ACC.tif         also write the D8 flow accumulation (cells draining through each cell)
  --streams S.tif        also write the stream network: 1 where at least --stream-area drains
  --stream-area KM2      contributing area of a stream, km^2 (default 1)
  --max-memory GB        refuse a run estimated to need more, before any work (default: 80%
                         of the machine's memory)
)";

// Contributing area from which a cell counts as a stream by default: about where
// channels begin in humid mid-latitude land (order of 1 km^2).
constexpr double kDefaultStreamAreaKm2 = 1.0;
constexpr double kSquareMetresPerKm2 = 1.0e6;

struct PitsArguments
{
  std::string input;
  std::string output;
  std::optional<std::string> sinks;
  std::optional<std::string> flow;
  std::optional<std::string> streams;
  double streamAreaKm2 = kDefaultStreamAreaKm2;
  PitRemovalOptions options;
  ReadOptions read;
};

void requireRasterOutput(const std::string& path, const char* what)
{
  if (!isVtiPath(path) && !isHeightfieldWriteExtension(path))
  {
    throw UsageError(std::string(what) + " must end in .tif, .png or .vti, not " + path + ".");
  }
}

// The DEM and sink mask read against the terrain, flow and streams written.
void checkPitsFiles(const PitsArguments& a)
{
  FileRoles files;
  files.input(a.input, "the DEM", a.read.useSidecar);
  if (a.sinks)
  {
    files.input(*a.sinks, "--sinks");
  }
  files.output(a.output, "-o");
  if (a.flow)
  {
    files.output(*a.flow, "--flow");
  }
  if (a.streams)
  {
    files.output(*a.streams, "--streams");
  }
  files.check();
}

PitsArguments parsePitsArguments(std::vector<std::string> args)
{
  CommandLine cl(std::move(args));
  PitsArguments a;
  a.output = cl.take("--output", "-o").value_or("");
  const std::vector<OptionRow>& rows = pitRemovalOptionRows();
  if (const auto method = takeRowChoice(cl, optionRow(rows, "Method")))
  {
    a.options.method = static_cast<PitRemovalMethod>(*method);
  }
  if (const auto depth = takeRowNumber(cl, optionRow(rows, "MaxBreachDepth")))
  {
    a.options.maxBreachDepth = *depth;
  }
  if (const auto length = takeRowNumber(cl, optionRow(rows, "MaxBreachLength")))
  {
    a.options.maxBreachLength = static_cast<int>(*length);
  }
  a.sinks = cl.take("--sinks");
  a.flow = cl.take("--flow");
  a.streams = cl.take("--streams");
  if (const auto area = cl.takeNumber("--stream-area"))
  {
    if (!(*area > 0.0) || !a.streams)
    {
      throw UsageError("--stream-area expects a positive number of km^2, with --streams.");
    }
    a.streamAreaKm2 = *area;
  }
  a.options.memoryBudget = takeMemoryBudget(cl);
  a.options.memoryOption = kMemoryOption;
  a.read = takeReadOptions(cl);
  a.input = oneInput(cl, "pits");
  if (a.output.empty())
  {
    throw UsageError("tsynth pits needs an output file: -o OUT.tif|.png|.vti.");
  }
  requireRasterOutput(a.output, "The output");
  if (a.flow)
  {
    requireRasterOutput(*a.flow, "--flow");
  }
  if (a.streams)
  {
    requireRasterOutput(*a.streams, "--streams");
  }
  checkPitsFiles(a);
  return a;
}

// A grid of the DEM's frame carrying other values (NaN on its invalid cells).
template<typename Value>
Heightfield asRaster(const Heightfield& dem, const std::vector<Value>& values)
{
  Heightfield out = dem;
  for (std::size_t k = 0; k < values.size(); ++k)
  {
    out.z[k] = dem.isValid(k) ? static_cast<float>(values[k]) : std::nanf("");
  }
  out.sourceZUnit = "m";
  return out;
}

std::uint32_t streamThreshold(const Heightfield& dem, double areaKm2)
{
  const double cells = areaKm2 * kSquareMetresPerKm2 / (dem.cellX * dem.cellY);
  return static_cast<std::uint32_t>(std::clamp(std::ceil(cells), 1.0, 4294967295.0));
}

// What `tsynth pits` writes, all computed before the first file is written.
struct PitsOutputs
{
  PitRemovalResult removal;
  double seconds = 0.0;
  std::vector<std::uint32_t> accumulation; // when --flow or --streams
  std::uint32_t streamThreshold = 0;
};

PitsOutputs computePits(const PitsArguments& a, const Heightfield& dem)
{
  PitsOutputs out;
  const auto t0 = std::chrono::steady_clock::now();
  out.removal = removePits(dem, a.options);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (a.flow || a.streams)
  {
    // Flow ends at the sinks the removal kept.
    const std::vector<std::int8_t> directions = flowDirections(out.removal.dem, a.options.sinks);
    out.accumulation =
      flowAccumulation(directions, dem.width, dem.height, dem.hasMask() ? &dem.valid : nullptr);
    out.streamThreshold = streamThreshold(dem, a.streamAreaKm2);
  }
  return out;
}

void writePits(const PitsArguments& a, const Heightfield& dem, const PitsOutputs& out)
{
  const PitRemovalResult& r = out.removal;
  writeTerrainFile(a.output, r.dem);
  std::cout << std::fixed << std::setprecision(2) << "Pit removal ("
            << pitRemovalMethodName(a.options.method) << "): " << countPits(dem) << " pits before, "
            << countPits(r.dem) << " after; " << r.raisedCells << " cells raised (up to "
            << r.maxRaise << " m), " << r.loweredCells << " lowered (up to " << r.maxLower
            << " m); " << out.seconds << " s\n";
  std::cout << "Wrote " << a.output << "\n";
  if (a.flow)
  {
    writeTerrainFile(*a.flow, asRaster(dem, out.accumulation));
    std::cout << "Wrote " << *a.flow << " (flow accumulation, cells)\n";
  }
  if (a.streams)
  {
    writeTerrainFile(
      *a.streams, asRaster(dem, streamNetwork(out.accumulation, out.streamThreshold)));
    std::cout << "Wrote " << *a.streams << " (streams: " << out.streamThreshold
              << " cells or more drain)\n";
  }
}

} // namespace

int runPits(std::vector<std::string> args)
{
  if (wantsHelp(args))
  {
    std::cout << withOptionRows(kPitsHelp, pitRemovalOptionRows()) << kReadOptionsHelp;
    return 0;
  }
  PitsArguments a = parsePitsArguments(std::move(args));
  const Heightfield dem = readDem(a.input, a.read);
  checkDemToDrain(dem, a.options, a.flow || a.streams);
  std::vector<std::uint8_t> sinks;
  if (a.sinks)
  {
    ReadOptions plain;
    plain.useSidecar = false;
    sinks = sinkMaskFromRaster(readTerrainFile(*a.sinks, plain), dem.width, dem.height);
    a.options.sinks = &sinks;
  }
  // Ctrl-C stops the computation, before anything is written; once writing has begun it only
  // sets the flag, so no file is left half-written.
  const InterruptGuard interrupt;
  writePits(a, dem, computePits(a, dem));
  return 0;
}

} // namespace tsynth::cli
