// The synthesis patch's size: its default and the sizes taken, written once for
// every stage (features, candidates, matcher, landforms, synthesis), front end
// (tsynth --patch, the filters' PatchSize) and plugin XML (checked by
// Testing/Cxx/TestFilters.cxx against these numbers).
#pragma once

namespace tsynth
{

// 80 cells suit 90 m data (Tasse's patches): 7.2 km, about one landform across.
constexpr int kDefaultSynthesisPatch = 80;
// Sizes taken: multiples of kPatchSizeStep (the dense search compares 4 x 4
// blocks first) from kMinSynthesisPatch to kMaxSynthesisPatch cells.
constexpr int kMinSynthesisPatch = 16;
constexpr int kMaxSynthesisPatch = 512;
constexpr int kPatchSizeStep = 4;

} // namespace tsynth
