// Resampling a heightfield to another cell size (bilinear; nodata-aware).
#pragma once

#include "Heightfield.h"

namespace tsynth
{

// The same extent on cells of cellX x cellY metres: bilinear where all four
// neighbours are valid, invalid otherwise. Georeference is dropped (the grid
// changed); the cell size is what was asked.
Heightfield resampleToCellSize(const Heightfield& hf, double cellX, double cellY);

// The same extent on a grid of width x height cells, each taking the value of
// the input cell it falls in (nearest neighbour; nodata stays nodata). Cell
// sizes and georeference are the caller's to set.
Heightfield resampleNearest(const Heightfield& hf, int width, int height);

} // namespace tsynth
