// Hillshade and slope of a heightfield, cell-size aware, nodata-safe.
// In ParaView: vtkTerrainHillshade (Terrain Hillshade), in Filters/.
#pragma once

#include "../Core/Heightfield.h"
#include "../Core/OptionTable.h"
#include "HillshadeLimits.h"

#include <vector>

namespace tsynth
{

struct HillshadeOptions
{
  double altitudeDeg = 45.0;    // sun elevation above the horizon
  double azimuthDeg = 315.0;    // direction the light comes from, clockwise from north
  bool multidirectional = true; // blend lights from 225, 270, 315 and 360 deg by aspect
  double zFactor = 1.0;         // vertical exaggeration applied to gradients
};

struct ShadedRelief
{
  int width = 0;
  int height = 0;
  std::vector<float> shade;    // 0 (dark) .. 1 (lit); NaN where the height is invalid
  std::vector<float> slopeDeg; // slope angle in degrees; NaN where invalid
};

// Gradients use Horn's 3x3 weights divided by the cell size in x and y; a
// neighbour outside the grid or invalid is extrapolated from the opposite one
// (or the centre), so nodata never enters the result.
ShadedRelief computeHillshade(const Heightfield& hf, const HillshadeOptions& options = {});

// The options tsynth render (its map) and the Terrain Hillshade filter share
// (Core/OptionTable.h), their defaults a default HillshadeOptions'. tsynth render
// turns Multidirectional off when given an --azimuth, and --exaggeration is its ZFactor.
const std::vector<OptionRow>& hillshadeOptionRows();

} // namespace tsynth
