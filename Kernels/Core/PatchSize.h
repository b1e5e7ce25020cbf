// The synthesis patch's size: its default and the sizes taken, written once for
// every stage (features, candidates, matcher, landforms, synthesis), front end
// (tsynth --patch, the filters' PatchSize) and plugin XML (checked by
// Testing/Cxx/TestFilters.cxx against these numbers).
#pragma once

#include <string>

namespace tsynth
{

// 80 cells suit 90 m data (Tasse's patches): 7.2 km, about one landform across.
constexpr int kDefaultSynthesisPatch = 80;
// Sizes taken: multiples of kPatchSizeStep (the dense search compares 4 x 4
// blocks first) from kMinSynthesisPatch to kMaxSynthesisPatch cells.
constexpr int kMinSynthesisPatch = 16;
constexpr int kMaxSynthesisPatch = 512;
constexpr int kPatchSizeStep = 4;

// Throws tsynth::Error naming `name` (the front end's option: --patch, Patch Size) for a patch
// size outside those taken. Front ends refuse such a size; none is ever rounded or clamped.
void checkPatchSize(int patchSize, const std::string& name);

// The lower-left cell of the patch-sized window centred on `centre` (cells),
// on either axis: where a patch matched there is placed.
int windowCorner(double centre, int patchSize);

// The same for the stage filters that take any size in the range (the candidate builder and the
// matcher: a size off the step is searched exhaustively, slower, same ranking).
void checkPatchSizeInRange(int patchSize, const std::string& name);

} // namespace tsynth
