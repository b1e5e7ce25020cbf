// The values the distance synthesis' options may take in a front end (tsynth
// distance, the Terrain Distance Synthesis filter): light enough for the
// filter's header, whose clamp macros take them; the options table
// (distanceOptionRows, DistanceSynthesis.h) gives them to every front end. The
// kernel checks the relations between options (r below mu_w, a low fBm range
// below its high) with its own sentences.
#pragma once

namespace tsynth
{

// The least a quantity that must be positive (cell size, height scale, weights,
// scales, the fBm domain, the ridge fraction) is given: below it a run is a typing error.
constexpr double kLeastPositiveSetting = 0.001;
constexpr double kMaxMeanWeight = 100.0; // mu_w, and r below it
constexpr double kMaxSeaLevelScale = 10.0;
constexpr double kMaxBlendBias = 64.0; // about the maximum of the blended heights (eq. 3.7)
constexpr double kMaxFbmH = 10.0;
constexpr double kLeastLacunarity = 1.001; // each octave finer than the last
constexpr int kMaxFbmOctaves = 32;
constexpr double kFbmRangeLimit = 10.0; // the fBm range's ends within +-10 of the scale
constexpr int kMaxRidgeCount = 100000;
constexpr int kMaxProfileBins = 1 << 20;
constexpr double kLeastMinScaling = 1.0e-6;
constexpr int kDefaultDistanceGrid = 512; // poly-lines' grid: the thesis's resolution

} // namespace tsynth
