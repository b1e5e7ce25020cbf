// The bounds of the synthesis options that are not the patch size's
// (Core/PatchSize.h) or the memory budget's (Core/Memory.h): light enough for the filters' headers,
// whose clamp macros take them. The options table (SynthesisRequest.h) gives them to every front
// end.
#pragma once

namespace tsynth
{

// The landform relief a user may ask for, in multiples of the exemplars' own.
constexpr double kMinLandformRelief = 0.1;
constexpr double kMaxLandformRelief = 5.0;
constexpr double kDefaultLandformRelief = 1.0; // sketched landforms as bold as the exemplars'

// A penalty per seam edge far above any seam's own cost (graph-cut costs per
// edge are normalised to about 1): larger values change nothing more.
constexpr double kMaxRepetitionPenalty = 100.0;

// A front end's placement limit (ParaView's Placement Limit, tsynth synth --placements) that asks
// for every placement and then the finishing (SynthesisOptions::placementLimit).
constexpr int kAllPlacementsNumber = -1;

} // namespace tsynth
