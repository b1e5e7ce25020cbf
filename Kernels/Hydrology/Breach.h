// Internal to the hydrology kernels (PitRemoval.cxx and the benchmark): the
// breaching flood behind breachDepressions and breachOrFillDepressions, and the
// per-depression figures the hybrid decides on.
#pragma once

#include "../Core/Heightfield.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace tsynth
{

// One depression as complete breaching would carve it: the cells the flood
// reaches below its level from the first carve there until it climbs above
// that level again (one connected excursion below a spill level), and the
// channel that drains them.
struct DepressionChannel
{
  float spill = 0.0f;          // the flood level at which it was entered (metres)
  std::size_t cells = 0;       // cells below that level
  double maxCut = 0.0;         // deepest cut of its channel below the original surface (metres)
  std::size_t maxLength = 0;   // most cells one carve of its channel lowered
  bool lowersUserSink = false; // breaching it would lower a user sink
};

// Complete breaching as documented in PitRemoval.h (checks done by the caller).
Heightfield breachFlood(const Heightfield& dem, const std::vector<std::uint8_t>* sinks);

// Selective breaching as documented in PitRemoval.h (checks done by the caller).
Heightfield hybridFlood(const Heightfield& dem,
  double maxBreachDepth,
  std::size_t maxBreachLength,
  const std::vector<std::uint8_t>* sinks);

// Every depression of `dem` with the channel complete breaching would give it,
// in the order the flood meets them.
std::vector<DepressionChannel> surveyDepressions(const Heightfield& dem,
  const std::vector<std::uint8_t>* sinks);

} // namespace tsynth
