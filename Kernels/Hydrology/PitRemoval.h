// Depression removal: the three standard GIS methods behind one call, so the
// command line, the ParaView filter, the terrain optimisation and the synthesis
// pipeline pick a method by name and get the same result.
//
// Sinks are as in Flow.h: border cells, cells next to nodata, and cells of an
// optional user mask (lakes and sinkholes to keep). After any method every
// valid non-sink cell drains to a sink (drainsEverywhere holds).
#pragma once

#include "../Core/Heightfield.h"

#include <cstddef>
#include <cstdint>
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

// "fill", "breach", "hybrid"; parsePitRemovalMethod throws tsynth::Error naming
// the accepted words for anything else.
std::string pitRemovalMethodName(PitRemovalMethod method);
PitRemovalMethod parsePitRemovalMethod(const std::string& name);

// The hybrid's limits, as WhiteboxTools' BreachDepressions names them: a pit is
// breached only if its channel is no deeper than maxBreachDepth metres below the
// original surface anywhere and no longer than maxBreachLength cells; otherwise
// it is filled.
struct PitRemovalOptions
{
  PitRemovalMethod method = PitRemovalMethod::Breach;
  double maxBreachDepth = 50.0; // metres (hybrid only)
  int maxBreachLength = 100;    // cells (hybrid only)
  // Optional: one byte per cell, non-zero = a sink the user keeps.
  const std::vector<std::uint8_t>* sinks = nullptr;
};

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

// Complete breaching: no cell is ever raised; each pit is joined to a sink by a
// one-cell channel lowered, one float step at a time, below the pit. Throws
// tsynth::Error if `sinks` has the wrong size.
Heightfield breachDepressions(const Heightfield& dem,
  const std::vector<std::uint8_t>* sinks = nullptr);

// Selective breaching then filling (Lindsay 2016) with the limits above.
Heightfield breachOrFillDepressions(const Heightfield& dem,
  double maxBreachDepth,
  int maxBreachLength,
  const std::vector<std::uint8_t>* sinks = nullptr);

// The chosen method, with what it changed. Throws tsynth::Error (one sentence)
// for a DEM without a valid cell, a sink mask of the wrong size, or limits that
// are not positive.
PitRemovalResult removePits(const Heightfield& dem, const PitRemovalOptions& options);

// A sink mask from a raster read like a DEM (a file or a ParaView image): 1
// where the value is finite and non-zero, 0 elsewhere (nodata is no sink).
// Throws tsynth::Error naming both sizes if it is not width x height.
std::vector<std::uint8_t> sinkMaskFromRaster(const Heightfield& raster, int width, int height);

// Cells whose flow accumulation (Flow.h) is at least `threshold` cells: a
// stream network, 1 = stream. Throws tsynth::Error for a threshold below 1.
std::vector<std::uint8_t> streamNetwork(const std::vector<std::uint32_t>& accumulation,
  std::uint32_t threshold);

} // namespace tsynth
