// The target of a synthesis: a feature graph on the output grid and a smooth
// heightfield T_tar with the sketched features at heights typical of the
// exemplars (Tasse's thesis: the sketch deforms a flat terrain; here a sum of
// Gaussian ridges and troughs along the stroke centre lines).
#pragma once

#include "../Core/Heightfield.h"
#include "../Features/FeatureGraph.h"

#include <string>
#include <vector>

namespace tsynth
{

// Heights the exemplars give their features and their land in general.
struct ExemplarStatistics
{
  double low = 0.0;  // 5th percentile of heights
  double high = 1.0; // 95th percentile
  double median = 0.5;
  double ridge = 1.0;  // median height of ridge nodes
  double valley = 0.0; // median height of valley nodes
};

ExemplarStatistics exemplarStatistics(const std::vector<const Heightfield*>& exemplars,
  const std::vector<const FeatureGraph*>& graphs);

struct SynthesisTarget
{
  Heightfield field;  // T_tar, metres, on the output grid
  FeatureGraph graph; // on the output grid
  std::vector<std::string> warnings;
};

// Scales a graph drawn on a sketch of sketchWidth x sketchHeight pixels onto an
// output grid of width x height cells of the given size.
FeatureGraph scaleGraph(const FeatureGraph& graph,
  int sketchWidth,
  int sketchHeight,
  int width,
  int height,
  double cellX,
  double cellY);

// From strokes or poly-lines: background at the exemplars' median height, ridges
// raised to their ridge height and valleys lowered to their valley height with
// Gaussian profiles of standard deviation `profileWidth` cells around the
// centre lines (defaultProfileWidth: 0.075 patch, 6 cells for 80-cell patches,
// narrow enough that a crest stands out against its flanks 8 cells away).
inline double defaultProfileWidth(int patchSize)
{
  return 0.075 * patchSize;
}

SynthesisTarget targetFromStrokes(const FeatureGraph& graph,
  int width,
  int height,
  double cellX,
  double cellY,
  const ExemplarStatistics& stats,
  double profileWidth);

// From a grey sketch or a DEM already on the output grid: its range mapped
// linearly onto the exemplars' 5th..95th percentile heights.
SynthesisTarget targetFromHeights(const Heightfield& heights,
  const FeatureGraph& graph,
  const ExemplarStatistics& stats);

// Cells under the chains of a graph (8-connected lines between their points).
std::vector<std::uint8_t> rasteriseChains(const FeatureGraph& graph, int width, int height);

// The target on an output grid of width x height cells from a sketch drawn on
// sketchWidth x sketchHeight pixels: its graph scaled onto the grid (with
// control points at half a patch), and the field from the sketch's heights
// (grey map or DEM, resampled) when given, else from its strokes.
SynthesisTarget makeTarget(const FeatureGraph& sketchGraph,
  int sketchWidth,
  int sketchHeight,
  const Heightfield* sketchHeights,
  int width,
  int height,
  double cellX,
  double cellY,
  const ExemplarStatistics& stats,
  int patchSize);

// Exact Euclidean distance (in cells) from every cell to the nearest seed cell
// (Felzenszwalb and Huttenlocher's two-pass transform); +inf without seeds.
std::vector<float> distanceTransform(const std::vector<std::uint8_t>& seeds, int width, int height);

} // namespace tsynth
