// The values PPA's options (PpaOptions) may take in a front end (tsynth
// features, the Terrain Feature Extractor filter): light enough for the filter's
// header, whose clamp macros take them; the options table (ppaOptionRows, Ppa.h)
// gives them to every front end. Beyond them a run is a typing error.
#pragma once

namespace tsynth
{

constexpr int kMaxHalfProfileLength = 100;    // cells
constexpr double kMaxMinimumDip = 1.0e6;      // metres
constexpr double kMaxSignificanceNoise = 100; // noise sigmas
constexpr int kMaxSignificanceRadius = 1000;  // cells
constexpr double kMaxPresmoothSigma = 100.0;  // cells
constexpr int kMaxEndReductions = 1000;
constexpr int kMaxBranchLength = 100000; // cells
constexpr int kMaxTreeSize = 100000000;  // cells
constexpr int kMaxSmoothingPasses = 100;
constexpr double kMaxControlRadius = 10000.0; // cells

} // namespace tsynth
