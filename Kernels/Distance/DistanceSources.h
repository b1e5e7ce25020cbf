// The distance synthesis' inputs assembled from what a front end read: a stroke
// map or generator lines, profiles, labels, a region profile and edge weights.
// What tsynth distance and the Terrain Distance Synthesis filter share.
// In ParaView: vtkTerrainDistanceSynthesis (Terrain Distance Synthesis), in Filters/.
#pragma once

#include "../Core/HeightfieldIO.h"
#include "DistanceSynthesis.h"

#include <string>
#include <vector>

namespace tsynth
{

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

// The options tsynth distance and the Terrain Distance Synthesis filter share
// (Core/OptionTable.h), their defaults a default DistanceOptions' and
// DistanceSources': the grid, lattice, sea level, profiles, fBm, ridges, the
// expert settings and the memory budget (GB). The kernel checks the relations
// between them (r below mu_w, the fBm range's order).
const std::vector<OptionRow>& distanceOptionRows();

} // namespace tsynth
