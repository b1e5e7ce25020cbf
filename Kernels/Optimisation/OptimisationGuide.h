// The guide of a terrain optimisation from whatever the user has: a DEM, a grey
// sketch, a stroke map or poly-lines. It is the target field the patch-based
// synthesis builds from the same sketch (Synthesis/Setup.h), so a stroke map
// drives the optimisation with the landforms of the source's own ridges and
// valleys, and a DEM or grey map is brought onto the source's heights.
#pragma once

#include "../Core/Heightfield.h"
#include "../Synthesis/Setup.h"
#include "TerrainOptimisation.h"

#include <cstdint>
#include <string>
#include <vector>

namespace tsynth
{

struct OptimisationGuide
{
  Heightfield field;             // metres, on the output grid
  std::vector<float> confidence; // per cell, 0..1 (the target's weight)
  std::string kind;              // as AnalysedSketch::kind
  std::vector<std::string> warnings;
};

// The landform scale in cells the guide is built at: the synthesis' default
// patch, the width of the cross-sections its landforms are measured over.
constexpr int kGuideLandformScale = kDefaultSynthesisPatch;

// `grid` zeros: the sketch's pixels (or the poly-lines' frame) at the source's
// cell size; the guide's ties are broken by run.seed. Throws tsynth::Error as
// prepareSynthesis does, for a source checkOptimisationSource refuses, for an
// output smaller than kGuideLandformScale a side (naming names.size to change),
// and before any work for an optimisation (`run`) estimated above
// run.memoryBudget (checkOptimisationMemory).
OptimisationGuide buildOptimisationGuide(const Heightfield& source,
  const SketchInput& sketch,
  const GridRequest& grid,
  const OptimisationOptions& run,
  const SetupOptionNames& names = {});

} // namespace tsynth
