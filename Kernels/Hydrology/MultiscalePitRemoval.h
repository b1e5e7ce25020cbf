// Pit removal through a pyramid (Scott & Dodgson 2021's multi-resolution idea,
// for a finished terrain): depressions are removed first on coarse versions of
// the terrain and each level's change is spread smoothly over the cells it
// covers, so that a wide basin is drained by a broad, gently shaped valley or
// lake rather than a one-cell slot or a plateau; the finest level then removes
// what is left at the scale of single cells, and every cell drains.
#pragma once

#include "../Core/Heightfield.h"
#include "PitRemoval.h"

#include <cstddef>

namespace tsynth
{

struct MultiscalePitRemovalOptions
{
  PitRemovalOptions pitRemoval; // method, limits and sinks of the coarse levels (sinks: all)
  // Fine cells per cell of the coarsest level; levels halve it down to 2, then
  // the fine grid itself. 1: the fine grid only.
  int coarsestFactor = 16;
  // The method on the fine grid itself, where only pits of a few cells are
  // left: filling by default, whatever the coarse levels use. A channel carved
  // one cell wide is the "pixel-wide chasm" Scott & Dodgson avoid by skipping
  // the finest level (on the bundled sketches breaching there doubled the seam
  // index, the 99.9th percentile of the Laplacian); a filled pit of a few cells
  // rises by float steps, and every cell still drains.
  PitRemovalMethod finestMethod = PitRemovalMethod::Fill;
};

struct MultiscalePitRemovalReport
{
  std::size_t pitsBefore = 0; // countPits (Flow.h)
  std::size_t pitsAfter = 0;
  int levels = 0; // including the fine grid
  std::size_t raisedCells = 0;
  std::size_t loweredCells = 0;
  double largestRaise = 0.0; // metres
  double largestLowering = 0.0;
  double meanAbsoluteChange = 0.0; // metres, over valid cells
};

// Drains `dem` in place. Throws tsynth::Error as removePits does, or for a
// coarsest factor below 1.
MultiscalePitRemovalReport removePitsMultiscale(Heightfield& dem,
  const MultiscalePitRemovalOptions& options);

} // namespace tsynth
