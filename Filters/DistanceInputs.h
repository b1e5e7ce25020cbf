// Generator poly-lines from vtkPolyData, for the distance-synthesis front ends
// (tsynth distance, vtkTerrainDistanceSynthesis); the rest of their inputs is
// assembled by Kernels/Distance/DistanceSources.h.
#pragma once

#include "Core/HeightfieldIO.h"
#include "Distance/DistanceSources.h"

#include <string>
#include <vector>

class vtkPolyData;

namespace tsynth
{

// Poly-line and vertex cells as generator lines: points in metres (column =
// x / cellSize, row = y / cellSize); the optional point array "Cost" gives
// per-node costs (NaN: fBm), the optional cell array "Profile" each line's
// profile id (negative: feature id mod the profile count).
std::vector<GeneratorLine> polyDataToGeneratorLines(vtkPolyData* input, double cellSize);

} // namespace tsynth
