// The Shepard radius the Graph-Cut Merger filter takes (MergeOptions::shepardRadius,
// cells): light enough for its header, whose clamp macro takes it; the options
// table (mergeOptionRows, PatchMerger.h) gives it to the plugin XML's check.
#pragma once

namespace tsynth
{

// Below a cell the mismatch is not spread at all; beyond 10000 cells it reaches past any patch.
constexpr double kMinShepardRadius = 1.0;
constexpr double kMaxShepardRadius = 10000.0;

} // namespace tsynth
