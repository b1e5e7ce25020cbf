// The target of a synthesis: a feature graph on the output grid and a smooth
// heightfield T_tar at the scale of the drawing (Tasse's thesis: the sketch
// deforms a flat terrain). Stroke and poly-line sketches become landforms with
// the exemplars' own cross-sections (Landform.h); a grey map's strokes too,
// over its background; a DEM target keeps its own shape.
#pragma once

#include "../Core/Heightfield.h"
#include "../Core/PatchSize.h"
#include "../Features/FeatureGraph.h"
#include "Landform.h"

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
  double ridge = 1.0;          // median height of ridge nodes
  double valley = 0.0;         // median height of valley nodes
  LandformStatistics landform; // cross-sections of the major ridges and valleys
};

// `patchSize` sets how far out the landform cross-sections are measured.
ExemplarStatistics exemplarStatistics(const std::vector<const Heightfield*>& exemplars,
  const std::vector<const FeatureGraph*>& graphs,
  int patchSize = kDefaultSynthesisPatch);

struct SynthesisTarget
{
  Heightfield field;  // T_tar, metres, on the output grid
  FeatureGraph graph; // on the output grid
  // The lines a drawing implies (ImpliedLines.h): the divides between drawn
  // valleys, the troughs between drawn ridges, shaped in `field` like drawn
  // lines (for looking at: nothing is placed, measured or constrained on
  // them). Empty for a DEM target, whose own lines are all in `graph`.
  FeatureGraph implied;
  // How far apart the drawn lines are: the median over their cells of half
  // the spacing to the facing line (cells; +inf when most face none). 0 for a
  // DEM target, whose lines' spacing is its halfWidth (typicalHalfWidth).
  double lineHalfSpacing = 0.0;
  // Confidence in T_tar per cell (0..1): 1 near the sketched lines (or all over
  // a DEM target), 0 where the sketch leaves the land free.
  std::vector<float> weight;
  // Per cell: the scale (cells) the result should follow T_tar at: the half
  // width of the nearest sketched landform (LandformField::halfWidth); empty:
  // a quarter patch everywhere.
  std::vector<float> halfWidth;
  // The factors the sketched ridges' and valleys' relief was raised by to
  // stand out of the land's own relief (LandformField::ridgeRaise).
  double ridgeRaise = 1.0;
  double valleyRaise = 1.0;
  // Per cell of the sketched valley lines, the flow distance to their outlet
  // (metres, NaN elsewhere): water runs towards smaller values.
  std::vector<float> downstream;
  std::vector<std::string> warnings;
  // The field is real terrain (a DEM target), whose roughness the fill
  // matches; a drawing's field is smooth and says nothing of roughness.
  bool detailed = false;
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

// From strokes or poly-lines on the output grid: the exemplars' landforms
// along them (landformField), poly-line Elevation as crest and floor heights.
SynthesisTarget targetFromStrokes(const FeatureGraph& graph,
  int width,
  int height,
  double cellX,
  double cellY,
  const ExemplarStatistics& stats,
  int patchSize,
  std::uint64_t seed = 0);

// From a DEM already on the output grid: its range mapped linearly onto the
// exemplars' 5th..95th percentile heights; confidence 1 everywhere.
SynthesisTarget targetFromHeights(const Heightfield& heights,
  const FeatureGraph& graph,
  const ExemplarStatistics& stats);

// From a grey sketch already on the output grid (brighter is higher): its
// strokes become landforms whose crests and floors take the sketch's heights
// (mapped onto the exemplars' 5th..95th percentiles), standing on the sketch's
// smoothed background.
SynthesisTarget targetFromGreySketch(const Heightfield& grey,
  const FeatureGraph& graph,
  const ExemplarStatistics& stats,
  int patchSize,
  std::uint64_t seed = 0);

// What the sketch's heights are, when it has them.
enum class SketchHeights
{
  None, // strokes or poly-lines
  Grey, // a grey sketch map: brighter is higher
  Dem   // a real DEM used as the target
};

// The target on an output grid of width x height cells from a sketch drawn on
// sketchWidth x sketchHeight pixels: its graph scaled onto the grid (with
// control points at half a patch), and the field from the sketch's heights
// (grey map or DEM, resampled) when given, else from its strokes. Sketched
// landforms get `landformRelief` times the exemplars' relief (a DEM target
// keeps its own).
SynthesisTarget makeTarget(const FeatureGraph& sketchGraph,
  int sketchWidth,
  int sketchHeight,
  const Heightfield* sketchHeights,
  int width,
  int height,
  double cellX,
  double cellY,
  const ExemplarStatistics& stats,
  int patchSize,
  SketchHeights kind = SketchHeights::Dem,
  std::uint64_t seed = 0,
  double landformRelief = 1.0);

// The median over the target's line cells of its half width (cells): half the
// typical spacing of its strokes, or of a DEM target's ridges and valleys; 0
// without lines.
double typicalHalfWidth(const SynthesisTarget& target);

// The typical spacing of the target's own lines, in cells: twice their half
// spacing (a drawing's strokes, not the lines it implies between them), or
// twice typicalHalfWidth for a DEM target; 0 without lines.
double lineSpacing(const SynthesisTarget& target);

} // namespace tsynth
