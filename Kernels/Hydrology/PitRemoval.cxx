#include "PitRemoval.h"

#include "../Core/Cancellation.h"
#include "../Core/Error.h"
#include "../Core/Memory.h"
#include "Breach.h"
#include "Flow.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace tsynth
{
namespace
{

// Peak resident memory of `tsynth pits` measured with /usr/bin/time -v on DEMs
// of fBm-like noise (30 m cells), the same within 1% for breach, fill and
// hybrid: 109 / 162 / 371 MB at 1024^2 / 2048^2 / 4096^2 cells, and with --flow
// and --streams 121 / 200 / 488 MB. Between the two largest that is 16.6 bytes
// per cell (the DEM read twice over, the corrected copy, the flood's queue and
// links) and 6.3 more with flow routing; about 100 MB before any cell (the
// program, GDAL, VTK). Rounded up for a margin: the estimate is 1.25 to 1.4
// times the measured peak.
constexpr double kPitsBaseBytes = 128.0e6;
constexpr double kPitsBytesPerCell = 20.0;
constexpr double kFlowBytesPerCell = 8.0;

} // namespace

std::string pitRemovalMethodName(PitRemovalMethod method)
{
  return choicesOf(kPitRemovalMethodWords).wordOf(static_cast<int>(method), "Pit removal method");
}

const std::vector<OptionRow>& pitRemovalOptionRows()
{
  static const std::vector<OptionRow> rows = []
  {
    const PitRemovalOptions d;
    using T = OptionType;
    return std::vector<OptionRow>{
      choiceRow("Method",
        "--method",
        static_cast<int>(d.method),
        choicesOf(kPitRemovalMethodWords),
        { "Fill", "Breach", "Hybrid" }),
      numberRow("MaxBreachDepth",
        "--max-depth",
        T::Real,
        d.maxBreachDepth,
        kMinBreachDepthLimit,
        kMaxBreachDepthLimit),
      numberRow(
        "MaxBreachLength", "--max-length", T::Integer, d.maxBreachLength, 1, kMaxBreachLengthLimit),
      memoryBudgetRow(d.memoryBudget),
    };
  }();
  return rows;
}

Choices offOrMethodChoices()
{
  // Static: rows and callers keep pointers to the words.
  static const std::vector<const char*> words = []
  {
    std::vector<const char*> w{ "off" };
    w.insert(w.end(), std::begin(kPitRemovalMethodWords), std::end(kPitRemovalMethodWords));
    return w;
  }();
  return { words.data(), words.size() };
}

std::vector<std::string> offOrMethodLabels()
{
  std::vector<std::string> labels{ "Off" };
  const std::vector<std::string>& methods = optionRow(pitRemovalOptionRows(), "Method").labels;
  labels.insert(labels.end(), methods.begin(), methods.end());
  return labels;
}

std::optional<PitRemovalMethod> offOrMethod(int value)
{
  offOrMethodChoices().wordOf(value, "Pit removal"); // throws for a value without a word
  if (value == 0)
  {
    return std::nullopt;
  }
  return static_cast<PitRemovalMethod>(value - 1);
}

int offOrMethodValue(const std::optional<PitRemovalMethod>& method)
{
  return method ? static_cast<int>(*method) + 1 : 0;
}

PitRemovalMethod parsePitRemovalMethod(const std::string& name)
{
  return static_cast<PitRemovalMethod>(
    choicesOf(kPitRemovalMethodWords).valueOf(name, "The pit removal method"));
}

namespace
{

void checkSinks(const Heightfield& dem, const std::vector<std::uint8_t>* sinks)
{
  if (sinks != nullptr && sinks->size() != dem.size())
  {
    throw Error("The sink mask has " + std::to_string(sinks->size()) + " cells but the DEM has " +
      std::to_string(dem.size()) + ": give a mask of the DEM's size.");
  }
}

void checkLimits(double maxBreachDepth, int maxBreachLength)
{
  if (!(maxBreachDepth > 0.0 && maxBreachLength > 0))
  {
    throw Error("The hybrid method needs a positive maximum breach depth and length.");
  }
}

} // namespace

Heightfield breachDepressions(const Heightfield& dem, const std::vector<std::uint8_t>* sinks)
{
  checkSinks(dem, sinks);
  return breachFlood(dem, sinks);
}

Heightfield breachOrFillDepressions(const Heightfield& dem,
  double maxBreachDepth,
  int maxBreachLength,
  const std::vector<std::uint8_t>* sinks)
{
  checkSinks(dem, sinks);
  checkLimits(maxBreachDepth, maxBreachLength);
  return hybridFlood(dem, maxBreachDepth, static_cast<std::size_t>(maxBreachLength), sinks);
}

namespace
{

void checkInputs(const Heightfield& dem, const PitRemovalOptions& options)
{
  if (dem.validCount() == 0 ||
    std::none_of(dem.z.begin(), dem.z.end(), [](float v) { return std::isfinite(v); }))
  {
    throw Error("The DEM has no valid cell: there is nothing to drain.");
  }
  checkSinks(dem, options.sinks);
  if (options.method == PitRemovalMethod::Hybrid)
  {
    checkLimits(options.maxBreachDepth, options.maxBreachLength);
  }
}

Heightfield runMethod(const Heightfield& dem, const PitRemovalOptions& options)
{
  switch (options.method)
  {
    case PitRemovalMethod::Fill:
      return fillDepressions(dem, options.sinks);
    case PitRemovalMethod::Breach:
      return breachDepressions(dem, options.sinks);
    case PitRemovalMethod::Hybrid:
      return breachOrFillDepressions(
        dem, options.maxBreachDepth, options.maxBreachLength, options.sinks);
  }
  return fillDepressions(dem, options.sinks);
}

// The changed-cell codes of PitRemovalResult::changed.
constexpr std::uint8_t kUnchanged = 0;
constexpr std::uint8_t kRaised = 1;
constexpr std::uint8_t kLowered = 2;

} // namespace

PitRemovalResult removePits(const Heightfield& dem, const PitRemovalOptions& options)
{
  checkCancellation(); // before the flood's work arrays, a second's allocating on large DEMs
  checkInputs(dem, options);
  PitRemovalResult r;
  r.dem = runMethod(dem, options);
  r.changed.assign(dem.size(), kUnchanged);
  for (std::size_t k = 0; k < dem.size(); ++k)
  {
    if (!isUsableCell(dem, k))
    {
      continue;
    }
    const double change = static_cast<double>(r.dem.z[k]) - dem.z[k];
    if (change > 0.0)
    {
      r.changed[k] = kRaised;
      ++r.raisedCells;
      r.maxRaise = std::max(r.maxRaise, change);
    }
    else if (change < 0.0)
    {
      r.changed[k] = kLowered;
      ++r.loweredCells;
      r.maxLower = std::max(r.maxLower, -change);
    }
  }
  return r;
}

double pitRemovalMemoryEstimate(int width, int height, bool flowRouting)
{
  const double cells = static_cast<double>(width) * static_cast<double>(height);
  return kPitsBaseBytes + cells * (kPitsBytesPerCell + (flowRouting ? kFlowBytesPerCell : 0.0));
}

void checkDemToDrain(const Heightfield& dem, const PitRemovalOptions& options, bool flowRouting)
{
  const HeightRange range = computeHeightRange(dem);
  if (range.validCells == 0)
  {
    throw Error("The DEM has no valid cell: there is nothing to drain.");
  }
  if (range.max == range.min)
  {
    std::ostringstream height;
    height << range.min;
    throw Error("The DEM is flat (every valid cell at " + height.str() +
      " m): there is no depression to remove and no slope for water to follow.");
  }
  checkMemoryBudget(pitRemovalMemoryEstimate(dem.width, dem.height, flowRouting),
    options.memoryBudget,
    "This pit removal of " + std::to_string(dem.width) + " x " + std::to_string(dem.height) +
      " cells" + (flowRouting ? " with flow routing" : ""),
    "give a smaller DEM",
    options.memoryOption);
}

std::vector<std::uint8_t> sinkMaskFromRaster(const Heightfield& raster, int width, int height)
{
  if (raster.width != width || raster.height != height)
  {
    throw Error("The sink mask is " + std::to_string(raster.width) + " x " +
      std::to_string(raster.height) + " cells but the DEM is " + std::to_string(width) + " x " +
      std::to_string(height) + ": give a mask of the DEM's size.");
  }
  std::vector<std::uint8_t> sinks(raster.size(), 0);
  for (std::size_t k = 0; k < raster.size(); ++k)
  {
    sinks[k] = raster.isValid(k) && std::isfinite(raster.z[k]) && raster.z[k] != 0.0f ? 1 : 0;
  }
  return sinks;
}

std::vector<std::uint8_t> streamNetwork(const std::vector<std::uint32_t>& accumulation,
  std::uint32_t threshold)
{
  if (threshold < 1)
  {
    throw Error("The stream threshold must be at least 1 cell.");
  }
  std::vector<std::uint8_t> streams(accumulation.size(), 0);
  for (std::size_t k = 0; k < accumulation.size(); ++k)
  {
    streams[k] = accumulation[k] >= threshold ? 1 : 0;
  }
  return streams;
}

} // namespace tsynth
