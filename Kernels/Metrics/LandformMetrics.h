// Landform-scale measures of a terrain against a sketch's feature lines: are
// the sketched ridges mountain ridges (prominent, above the valleys, shedding
// water) and the sketched valleys draining valleys (deep, collecting their
// flanks' water, descending to an outlet)? Distances are in cells of the
// terrain's grid (x east, y north, row 0 south), heights in metres.
#pragma once

#include "../Core/Heightfield.h"
#include "../Core/PatchSize.h"
#include "../Features/FeatureGraph.h"
#include "../Features/Ppa.h"

#include <cstddef>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace tsynth
{

struct LandformOptions
{
  // The synthesis patch size in cells: the landform scale.
  double patchSize = kDefaultSynthesisPatch;
  // D, the distance across the line (each side) at which the surroundings are
  // taken; <= 0 means patchSize.
  double distance = 0.0;
  // Cells around a sample searched for the channel, the crest or the floor:
  // sketched lines are drawn by hand and thinned strokes wander a cell or two.
  double tolerance = 2.0;
  // Valley drainage: a valley point at distance L (cells, along the longest
  // sketched path from a head) must collect at least the area of a strip this
  // fraction of the patch wide along L: drainageStripFraction * patchSize * L
  // cells. Where there is no channel the line collects about one cell per cell
  // of length: flow on a hillside runs in parallel lines down it, and on a
  // filled lake's flat surface too (1-2 cells per cell on the real DEMs' own
  // valley lines that miss a channel). Valleys collect their flanks: measured on
  // the landform-scale valleys of Colorado and Mont Blanc (their own PPA lines
  // after smoothing at 2 cells), a median of 25-28 cells per cell of length, a
  // quarter of the samples under 12-13. An eighth of a patch (10 cells at 80: 5
  // cells of flank on each side) is 5-10 times the no-channel figure and passes
  // 79-84% of the bundled DEMs' samples; a quarter of a patch passes 61-64%.
  double drainageStripFraction = 0.125;
  // Ridge shedding: every cell within `tolerance` of a ridge sample must collect
  // at most this many patch widths of cells (sheddingPatchWidths * patchSize).
  // On a crest water leaves down the flanks at once: the cells within two cells
  // of the bundled DEMs' own PPA ridges collect a median of 3 cells (90th
  // percentile 8-10), while a channel crossing or running along the line gathers
  // a catchment of hundreds to thousands. Two patch widths (160 cells at 80)
  // keep a wide margin above crests that descend along their length.
  double sheddingPatchWidths = 2.0;
  // Valley descent: consecutive floor samples a quarter patch apart count as
  // descending if the downstream floor is at most this many metres higher
  // (flat floors and DEM noise).
  double descentSlack = 1.0;

  double crossDistance() const { return distance > 0.0 ? distance : patchSize; }
};

struct LandformMeasures
{
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

  // Prominence of sketched ridges (depth of sketched valleys) at landform scale:
  // median over samples every cell along the lines of z(line point) minus the
  // mean of z at distance D on both sides, perpendicular to the line, with the
  // sign that makes a ridge above its surroundings (a valley below them)
  // positive; metres. Samples whose three heights are not all valid are skipped.
  double ridgeProminence = kNaN;
  double valleyDepth = kNaN;
  // The same divided by the exemplars' own figure (typicalProminence on their
  // lines): 1 = like the exemplars' own features.
  double ridgeProminenceRatio = kNaN;
  double valleyDepthRatio = kNaN;
  // Probability that a random ridge sample is higher than a random valley
  // sample (Mann-Whitney AUC, ties count half): 1 = every ridge above every valley.
  double ridgeOverValley = kNaN;
  // Share of sketched valley length along which D8 flow on the depression-filled
  // terrain has accumulated: a sample counts if a cell within `tolerance` has
  // accumulation >= drainageStripFraction * patchSize * L (see LandformOptions).
  double valleyDrainage = kNaN;
  // Share of sketched ridge length that sheds water: every cell within
  // `tolerance` of the sample collects at most sheddingPatchWidths * patchSize.
  double ridgeShedding = kNaN;
  // Share of consecutive sample pairs along the valleys, a quarter patch apart
  // and ordered downstream, whose floor (lowest height within `tolerance`)
  // descends or rises by at most descentSlack metres.
  double valleyDescent = kNaN;

  // The exemplars' typical figures the ratios divide by (NaN if not computed).
  double referenceRidgeProminence = kNaN;
  double referenceValleyDepth = kNaN;
  // Samples behind the figures.
  std::size_t ridgeSamples = 0; // prominence samples (all three heights valid)
  std::size_t valleySamples = 0;
  std::size_t drainageSamples = 0; // valley samples every cell
  std::size_t sheddingSamples = 0; // ridge samples every cell
  std::size_t descentPairs = 0;
  // Why a field is NaN, keyed by the field's name (e.g. "valleyDrainage").
  std::map<std::string, std::string> notes;
};

// Median signed prominence (ridges) or depth (valleys) at cross distance
// `distance` (cells) of the chains of `type` in `lines` on `heights`, as in
// LandformMeasures::ridgeProminence; NaN if there is no valid sample.
double typicalProminence(const Heightfield& heights,
  const FeatureGraph& lines,
  FeatureType type,
  double distance);

// Pooled over several exemplars: the median of all their samples together, so
// each exemplar weighs by the length of its lines. lines[i] belongs to
// exemplars[i]; throws tsynth::Error if the counts differ.
double typicalProminence(const std::vector<const Heightfield*>& exemplars,
  const std::vector<const FeatureGraph*>& lines,
  FeatureType type,
  double distance);

// An exemplar's own feature lines: PPA ridges and valleys in one graph.
FeatureGraph ownFeatureLines(const Heightfield& dem, const PpaOptions& options = {});

// Every measure of `terrain` against the ridges and valleys of `sketch` (on the
// terrain's grid). Ratios use the exemplars' own lines (exemplarLines[i] holds
// the ridges and valleys of exemplars[i]; both may be empty, giving NaN ratios).
// Each valley chain drains towards the lower of its two end nodes (the lowest
// terrain within `tolerance`; ties to the lower node id), so a network drawn
// across a divide drains both ways from it; paths from the heads continue
// through the nodes where chains meet. Throws tsynth::Error if a graph's grid
// size differs from its heightfield's, the exemplar and line counts differ, or
// an option is out of range.
LandformMeasures evaluateLandforms(const Heightfield& terrain,
  const FeatureGraph& sketch,
  const std::vector<const Heightfield*>& exemplars,
  const std::vector<const FeatureGraph*>& exemplarLines,
  const LandformOptions& options = {});

} // namespace tsynth
