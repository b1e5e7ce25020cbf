// Resampling a heightfield to another cell size (bilinear; nodata-aware).
#pragma once

#include "Heightfield.h"

namespace tsynth
{

// The same extent on cells of cellX x cellY metres: bilinear where all four
// neighbours are valid, invalid otherwise. Georeference is dropped (the grid
// changed); the cell size is what was asked.
Heightfield resampleToCellSize(const Heightfield& hf, double cellX, double cellY);

} // namespace tsynth
