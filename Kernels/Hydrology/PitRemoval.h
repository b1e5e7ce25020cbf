// Depression removal: the three standard GIS methods behind one call, so the
// command line, the ParaView filter, the terrain optimisation and the synthesis
// pipeline pick a method by name and get the same result.
//
// Sinks are as in Flow.h: border cells, cells next to nodata, and cells of an
// optional user mask (lakes and sinkholes to keep). After any method every
// valid non-sink cell drains to a sink (drainsEverywhere holds).
// In ParaView: vtkTerrainPitRemoval (Terrain Pit Removal), in Filters/.
#pragma once

#include "../Core/Heightfield.h"
#include "../Core/OptionTable.h"
#include "BreachLimits.h"

#include <cstddef>
#include <cstdint>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

namespace tsynth
{

enum class PitRemovalMethod
{
  Fill,   // Priority-Flood+epsilon (Barnes et al. 2014): raise depressions to their spill level
  Breach, // complete breaching (Soille 2004, as Scott & Dodgson 2021): carve a channel out of each
          // pit
  Hybrid  // selective breaching (Lindsay 2016): breach within the limits, fill the rest
};

// The methods' words, by value (Core/OptionTable.h); parsePitRemovalMethod
// throws tsynth::Error naming them for anything else.
inline constexpr const char* kPitRemovalMethodWords[] = { "fill", "breach", "hybrid" };
static_assert(
  std::size(kPitRemovalMethodWords) == static_cast<std::size_t>(PitRemovalMethod::Hybrid) + 1);
std::string pitRemovalMethodName(PitRemovalMethod method);
PitRemovalMethod parsePitRemovalMethod(const std::string& name);

// The hybrid's limits, as WhiteboxTools' BreachDepressions names them: a
// depression is breached only if its channel is no deeper than maxBreachDepth
// metres below the original surface anywhere and no longer than maxBreachLength
// cells (the most cells one carve of it lowers: the channel from its deepest
// cell to where the path was already low enough); otherwise it is filled.
struct PitRemovalOptions
{
  PitRemovalMethod method = PitRemovalMethod::Breach;
  // 20 m / 50 cells: on 10 real DEMs 97.8% of 18606 pits breached, the 418 deepest/longest filled
  double maxBreachDepth = 20.0; // metres (hybrid only)
  int maxBreachLength = 50;     // cells (hybrid only)
  // Optional: one byte per cell, non-zero = a sink the user keeps.
  const std::vector<std::uint8_t>* sinks = nullptr;
  // What checkDemToDrain refuses: a run whose pitRemovalMemoryEstimate is above
  // this many bytes (0: defaultMemoryBudget()), with a sentence naming
  // memoryOption (the front end's option) to raise.
  double memoryBudget = 0.0;
  std::string memoryOption = "the memory budget";
};

// The limits a front end takes for maxBreachDepth and maxBreachLength: BreachLimits.h.

// The options `tsynth pits` and the Terrain Pit Removal filter share (Core/OptionTable.h): the
// method, the hybrid's limits and the memory budget (in GB), their defaults a default
// PitRemovalOptions'.
const std::vector<OptionRow>& pitRemovalOptionRows();

// A pit removal that may be off, as the synthesis' Drainage and the optimisation's PitRemoval
// offer it: "off", then kPitRemovalMethodWords (ParaView: "Off", then the Method's labels).
Choices offOrMethodChoices();
std::vector<std::string> offOrMethodLabels();
// Its value (0: off) as a method, and back. offOrMethod throws tsynth::Error for a value
// without a word.
std::optional<PitRemovalMethod> offOrMethod(int value);
int offOrMethodValue(const std::optional<PitRemovalMethod>& method);

// Peak memory in bytes of removing the pits of a width x height DEM as `tsynth
// pits` and the Terrain Pit Removal filter run it: the DEM read (its values and
// mask as GDAL delivers them and as a heightfield), any of the three methods'
// work (flood queue, links, the corrected copy and its change map), and with
// flowRouting the D8 directions, the accumulation and the stream map with their
// output rasters; plus the program itself. Measured (PitRemoval.cxx) and
// rounded up: within a factor 1.4 above the measured peak from 1024^2 cells on.
double pitRemovalMemoryEstimate(int width, int height, bool flowRouting);

struct PitRemovalResult
{
  Heightfield dem; // the corrected heights (invalid cells unchanged)
  std::vector<std::uint8_t>
    changed; // per cell: 0 unchanged, 1 raised (filled), 2 lowered (breached)
  std::size_t raisedCells = 0;
  std::size_t loweredCells = 0;
  double maxRaise = 0.0; // metres
  double maxLower = 0.0; // metres
};

// Complete breaching (Soille 2004): a priority flood from the sinks on the
// original heights, in (height, index) order, each cell remembering the cell it
// was reached from; a cell reached lower than that cell is drained by carving
// back along those links, each cell one float step (nextafter) below the one
// before, until a cell already lower or a sink. No cell is ever raised; flats
// of the original stay flat (water crosses them, as drainsEverywhere allows).
// Sinks on the border or next to nodata are lowered when a channel needs it
// (water leaves the grid there). A user sink keeps its height whenever any
// other outlet can be reached: a pit that could only drain by lowering one is
// given a channel to another sink instead; only if every outlet of its region
// is a user sink is one lowered. Invalid cells are never crossed nor changed.
// Deterministic. Throws tsynth::Error if `sinks` has the wrong size.
Heightfield breachDepressions(const Heightfield& dem,
  const std::vector<std::uint8_t>* sinks = nullptr);

// Selective breaching (Lindsay 2016): complete breaching is measured first;
// each depression (the cells the flood reaches below its spill level) whose
// channel is within both limits is breached as above, the others are filled to
// their spill level with the epsilon gradient, cells reached below the flood
// level going one float step above the cell they were reached from. No lowered
// cell is cut deeper than maxBreachDepth, no carve lowers more than
// maxBreachLength cells, user sinks are never lowered (a depression that would
// need it is filled), and the result drains. With limits no channel reaches it
// equals breachDepressions; with limits below one float step it only raises.
// Throws tsynth::Error for a sink mask of the wrong size or limits that are not
// positive.
Heightfield breachOrFillDepressions(const Heightfield& dem,
  double maxBreachDepth,
  int maxBreachLength,
  const std::vector<std::uint8_t>* sinks = nullptr);

// The chosen method, with what it changed. Throws tsynth::Error (one sentence)
// for a DEM without a valid cell, a sink mask of the wrong size, or limits that
// are not positive.
PitRemovalResult removePits(const Heightfield& dem, const PitRemovalOptions& options);

// What the front ends (tsynth pits, the Terrain Pit Removal filter) refuse
// before any work, with one sentence: a DEM without a valid cell, a flat one
// (every valid cell at one height: no depression to remove, no slope to follow),
// or a run (with flow routing if flowRouting) whose pitRemovalMemoryEstimate is
// above options.memoryBudget (checkMemoryBudget's sentence, with the estimate).
// removePits itself accepts flat grids (the coarse levels of a pyramid can be).
void checkDemToDrain(const Heightfield& dem,
  const PitRemovalOptions& options = {},
  bool flowRouting = false);

// A sink mask from a raster read like a DEM (a file or a ParaView image): 1
// where the value is finite and non-zero, 0 elsewhere (nodata is no sink).
// Throws tsynth::Error naming both sizes if it is not width x height.
std::vector<std::uint8_t> sinkMaskFromRaster(const Heightfield& raster, int width, int height);

// Cells whose flow accumulation (Flow.h) is at least `threshold` cells: a
// stream network, 1 = stream. Throws tsynth::Error for a threshold below 1.
std::vector<std::uint8_t> streamNetwork(const std::vector<std::uint32_t>& accumulation,
  std::uint32_t threshold);

} // namespace tsynth
