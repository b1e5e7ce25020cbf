// What the distance-synthesis front ends (tsynth distance, vtkTerrainDistanceSynthesis)
// share: generator poly-lines from vtkPolyData and the assembly of the kernel's
// inputs from a stroke map or lines, profiles, labels, regions and edge weights.
#pragma once

#include "Core/HeightfieldIO.h"
#include "Distance/DistanceSynthesis.h"

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

struct DistanceSources
{
  const ColourImage* strokes = nullptr;              // a stroke map, or ...
  const std::vector<GeneratorLine>* lines = nullptr; // ... lines on a width x height grid
  int width = 0;
  int height = 0;
  std::vector<MonotoneProfile> profiles;
  ProfileAssignment assignment = ProfileAssignment::ByColour;
  const ColourImage* labels = nullptr; // profile per stroke pixel (grey value), stroke maps only
  int regionProfile = kNoProfile;      // >= 0: closed strokes' interiors use it, exclusively
  const ColourImage* edgeWeights = nullptr; // grey -> [edgeLow, edgeHigh], replaces mu_w and r
  double edgeLow = 0.25;                    // the thesis's EW range
  double edgeHigh = 2.5;
};

// Throws tsynth::Error for images of the wrong size, a region profile that does
// not exist or no generators; adds warnings (valley strokes ignored, ...).
DistanceInputs assembleDistanceInputs(const DistanceSources& sources,
  std::vector<std::string>& warnings);

} // namespace tsynth
