// Quality figures of a synthesised terrain: how well it follows the sketch,
// whether seams show, whether it looks like its exemplar.
#pragma once

#include "../Core/Heightfield.h"
#include "../Features/FeatureGraph.h"

#include <string>
#include <vector>

namespace tsynth
{

// Share of samples along the chains of `type` (one a cell) where the terrain
// has a crest (ridges) or trough (valleys) across the line: the extreme within
// 2 cells of the line beats both sides at 8 cells. -1 if there is no chain.
double featureFidelity(const Heightfield& terrain, const FeatureGraph& graph, FeatureType type);

// 99.9th percentile of |Laplacian| (cell-size aware, 1/m) over valid cells.
double laplacianPercentile(const Heightfield& hf, double fraction = 0.999);

// Seam index: laplacianPercentile(output) / laplacianPercentile(exemplar).
// With several exemplars the reference is the percentile over all their cells
// together (each exemplar counts by its area), as for slopeDistance.
double seamIndex(const Heightfield& output, const Heightfield& exemplar);
double seamIndex(const Heightfield& output, const std::vector<const Heightfield*>& exemplars);

// Wasserstein-1 distance between the slope-angle distributions (degrees) of
// output and exemplar, divided by the exemplar's mean slope.
double slopeDistance(const Heightfield& output, const Heightfield& exemplar);
double slopeDistance(const Heightfield& output, const std::vector<const Heightfield*>& exemplars);

// Strict local minima (8 neighbours, interior cells) per 1000 valid cells.
double pitDensity(const Heightfield& hf);

struct TerrainEvaluation
{
  double ridgeFidelity = -1.0;
  double valleyFidelity = -1.0;
  double seamIndex = 0.0;
  double slopeDistance = 0.0;
  double pitDensity = 0.0;
  double exemplarPitDensity = 0.0;
};

TerrainEvaluation evaluateTerrain(const Heightfield& output,
  const Heightfield& exemplar,
  const FeatureGraph* sketch);
// Against several exemplars pooled (a synthesis from all of them).
TerrainEvaluation evaluateTerrain(const Heightfield& output,
  const std::vector<const Heightfield*>& exemplars,
  const FeatureGraph* sketch);

// Baselines for scale: the exemplar repeated over the output's size (seams where
// copies meet), and random exemplar patches pasted edge to edge with no blending.
Heightfield tiledBaseline(const Heightfield& exemplar, int width, int height);
Heightfield randomPatchBaseline(const Heightfield& exemplar,
  int width,
  int height,
  int patch,
  unsigned seed);

} // namespace tsynth
