// Height profiles around feature nodes, sampled for the matcher: along each
// chain from the node to its control point, and across the chain there.
#pragma once

#include "../Core/Heightfield.h"
#include "FeatureGraph.h"

#include <vector>

namespace tsynth
{

struct ProfileOptions
{
  int alongSamples = 16;          // from the node (first) to the control point (last)
  int acrossSamples = 17;         // odd: the middle sample is on the chain
  double acrossHalfLength = 20.0; // cells each side of the chain
};

struct ChainProfile
{
  int chain = -1;
  std::vector<float> along;  // NaN where the heightfield is invalid or outside
  std::vector<float> across; // left (counter-clockwise side) to right
};

// One profile per control point of every node, in the order of node.controls.
std::vector<std::vector<ChainProfile>> sampleProfiles(const FeatureGraph& graph,
  const Heightfield& heights,
  const ProfileOptions& options = {});

// Bilinear height at a point in cell coordinates; NaN if any corner is invalid or outside.
float sampleBilinear(const Heightfield& hf, double x, double y);

} // namespace tsynth
