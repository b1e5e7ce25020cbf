// Quality figures of a synthesised terrain: how well it follows the sketch,
// whether seams show, whether it looks like its exemplar.
#pragma once

#include "../Core/Heightfield.h"
#include "../Features/FeatureGraph.h"

#include <limits>
#include <map>
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
// together (each exemplar counts by its area), as for slopeDistance. NaN when
// there is nothing to compare with: the exemplars have no curvature (flat) or
// no cell with four valid neighbours, or the output has no such cell.
double seamIndex(const Heightfield& output, const Heightfield& exemplar);
double seamIndex(const Heightfield& output, const std::vector<const Heightfield*>& exemplars);

// Wasserstein-1 distance between the slope-angle distributions (degrees) of
// output and exemplar, divided by the exemplar's mean slope. NaN when the
// exemplars are flat (no mean slope to scale by) or either side has no slope.
double slopeDistance(const Heightfield& output, const Heightfield& exemplar);
double slopeDistance(const Heightfield& output, const std::vector<const Heightfield*>& exemplars);

// Strict local minima (8 neighbours, interior cells) per 1000 valid cells; NaN
// without a valid interior cell.
double pitDensity(const Heightfield& hf);

// A figure that does not apply is NaN (JSON null), never a number that reads as
// a score (0 would read as perfect seams or slopes), with its reason in notes.
struct TerrainEvaluation
{
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

  double ridgeFidelity = kNaN; // featureFidelity; NaN when no ridge is sketched
  double valleyFidelity = kNaN;
  double seamIndex = kNaN;
  double slopeDistance = kNaN;
  double pitDensity = kNaN;
  double exemplarPitDensity = kNaN;
  // Why a field is NaN, keyed by the field's name (e.g. "seamIndex").
  std::map<std::string, std::string> notes;
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
