// The values the hybrid pit removal's limits (PitRemovalOptions::maxBreachDepth
// and maxBreachLength) may take in a front end: light enough for the Terrain Pit
// Removal filter's header, whose clamp macros take them.
#pragma once

namespace tsynth
{

// Below a millimetre a breach could cut nothing; 1000 km or a million cells are typing errors.
constexpr double kMinBreachDepthLimit = 1.0e-3;
constexpr double kMaxBreachDepthLimit = 1.0e6;
constexpr int kMaxBreachLengthLimit = 1000000;

} // namespace tsynth
