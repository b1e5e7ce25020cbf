// Style regions (Zhou et al. 2007's Middle-earth): a label image over the
// output chooses which exemplars may serve each region.
#pragma once

#include "../Core/Heightfield.h"
#include "Synthesiser.h"

#include <string>
#include <vector>

namespace tsynth
{

// Sets options.regionLabels (labels resampled nearest onto width x height;
// invalid cells -1) and options.regionExemplars from maps "L=E1,E2" (exemplar
// numbers from 0); a label without a map is served by exemplar L. Throws
// tsynth::Error naming the problem: a malformed map, an exemplar number out of
// range, or a label in use that has no exemplar.
void assignRegions(SynthesisOptions& options,
  const Heightfield& labels,
  const std::vector<std::string>& maps,
  int width,
  int height,
  std::size_t exemplars);

} // namespace tsynth
