// Can the sketch be read off the terrain? Measured at each stroke's own scale,
// not the patch's: for each sample along a sketched ridge (valley), the
// terrain's cross-section out to half the distance to the neighbouring
// strokes (Features/StrokeSpacing.h) must show a crest (trough) that stands
// out over both sides by a margin over the land's own relief at that scale
// (Features/CrossSections.h): the exemplars' land, or the terrain's own land
// away from the strokes where that is rougher. And it must do so along a
// stretch of the stroke at least as long as its half width: scattered samples
// that stand out read as knobs, not as a line. For a real DEM used as the
// target, the band-pass correlation with it at a few scales. Beside the
// legible share, how consistently the flanks next to each line slope as the
// landform's do (flankAgreement): what a hillshade shows at a glance.
// Distances in cells of the terrain's grid (row 0 south), heights in metres.
#pragma once

#include "../Core/Heightfield.h"
#include "../Features/CrossSections.h"
#include "../Features/FeatureGraph.h"
#include "../Features/StrokeSpacing.h"

#include <cstddef>
#include <limits>
#include <vector>

namespace tsynth
{

struct LegibilityOptions
{
  // A stroke no other faces is looked at out to this many cells each side:
  // half an 80-cell patch, the width of a landform one patch draws.
  double loneHalfWidth = 40.0;
  // Cross-sections narrower than this (cells each side) say nothing: strokes
  // drawn touching are one landform.
  double minHalfWidth = 3.0;
  // Where the crest or floor is looked for.
  SectionReading reading;
  // A sample stands out when its prominence (sectionProminence) is at least
  // `margin` times the land's relief at its half width (LandRelief: the root
  // mean square relief of random cross-sections of the exemplars' land, or of
  // the terrain's own land farther than loneHalfWidth from every stroke, the
  // larger), and is legible when it stands out in a run along the stroke. At 1,
  // on hillshades of a valley network synthesised from Everest, a terrain with
  // no landform scores 0.04 and the peer's (whose branches a person traces)
  // 0.52 (before the terrain's own land and the runs entered the measure);
  // at 2 nothing but the sketch's own field scores much.
  double margin = 1.0;
};

struct StrokeLegibility
{
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  double share = kNaN;      // legible share of the samples (every cell along the lines)
  std::size_t samples = 0;  // samples with a valid cross-section
  double prominence = kNaN; // median, m
  double threshold = kNaN;  // median of margin x the land's relief at the samples' half widths, m
  double halfWidth = kNaN;  // median half width looked at, cells
  // Mean over the samples of how the land on the line's flanks slopes: the
  // cosine between its gradient and the way a crest's (floor's) flank would
  // fall (rise), over the cells from kFlankNearestCells to a third of the
  // half width out, both sides. 1: every flank cell slopes as the landform's
  // does, a clean light-and-shade edge along the line in a hillshade; 0: no
  // more than land without it. A stroke can stand out of the land at its own
  // scale (share) while patches' spurs and gullies cross it: over Mont Blanc
  // a ring and a straight valley stood out along 0.76 of their length in ours
  // and 0.61 in Tasse's, whose ring a person reads at once and ours not
  // (flanks 0.71 against 0.80).
  double flankAgreement = kNaN;
  std::size_t flankSamples = 0; // samples with flank cells to read, behind flankAgreement
};

// One connected stroke of the sketch (connectedChainSets: a letter's strokes
// together, a whole valley network), as read.
struct StrokeReading
{
  FeatureType type = FeatureType::Ridge;
  double length = 0.0;     // cells
  std::size_t samples = 0; // with a valid cross-section
  double share = StrokeLegibility::kNaN;
  Point2 centre; // the middle of its lines' extent, cells (row 0 south)
};

// The eye reads a sketch stroke by stroke: a letter lost beside a long valley
// network is a failed sketch, though it is a tenth of the stroke length (the
// T of a "TS" over Colorado, faint where the network read, left the share of
// legible length at 0.76). Strokes with fewer samples than this are too
// short to be read as a line at all and do not count as the weakest.
constexpr std::size_t kMinWeakestStrokeSamples = 20;

struct Legibility
{
  StrokeLegibility ridge;
  StrokeLegibility valley;
  // Both kinds together, each sample counting once (share of all stroke length).
  double share = StrokeLegibility::kNaN;
  double flankAgreement = StrokeLegibility::kNaN; // both kinds, each sample counting once
  // Every connected stroke, in the order of their first chains ...
  std::vector<StrokeReading> strokes;
  // ... and the least legible of those with kMinWeakestStrokeSamples samples
  // or more (its index into strokes; strokes.size() if none has).
  std::size_t weakest = 0;
  double weakestShare() const
  {
    return weakest < strokes.size() ? strokes[weakest].share : StrokeLegibility::kNaN;
  }
};

// Measures terrains against one sketch: the strokes' spacing (StrokeSpacing,
// the costly part) is read once, for all the terrains measured. `sketch` on the
// terrains' grid (as scaled for a synthesis); `land` the exemplars' relief the
// strokes must stand out of (at the terrains' cell size). Both must outlive the
// meter. Throws tsynth::Error for options out of range.
class LegibilityMeter
{
public:
  LegibilityMeter(const FeatureGraph& sketch,
    const LandRelief& land,
    const LegibilityOptions& options = {});
  // Throws tsynth::Error for a terrain on another grid than the sketch's.
  Legibility measure(const Heightfield& terrain) const;

private:
  const FeatureGraph& sketch_;
  const LandRelief& land_;
  LegibilityOptions options_;
  StrokeSpacing spacing_;
};

// One terrain: LegibilityMeter(sketch, land, options).measure(terrain).
Legibility evaluateLegibility(const Heightfield& terrain,
  const FeatureGraph& sketch,
  const LandRelief& land,
  const LegibilityOptions& options = {});

// Scales (Gaussian sigma, cells) at which a DEM target is compared.
std::vector<double> defaultCorrelationScales();

struct BandCorrelation
{
  double sigma = 0.0;       // cells
  double correlation = 0.0; // Pearson, over the cells valid in both
};

// Correlation of the two heightfields' band-passes G(sigma) - G(2 sigma) (the
// relief between sigma and twice sigma cells) at each scale. Throws
// tsynth::Error if the grids differ in size.
std::vector<BandCorrelation> bandPassCorrelation(const Heightfield& terrain,
  const Heightfield& target,
  const std::vector<double>& sigmas);

// The same against one target for several terrains: the target's band-passes
// are computed once. Each Gaussian is computed once per field, however many
// bands share it (sigma 4 is the coarse half of band 2 and the fine half of
// band 4): 6 instead of 10 for the default scales.
class BandPassTarget
{
public:
  BandPassTarget(const Heightfield& target, std::vector<double> sigmas);
  // bandPassCorrelation(terrain, target, sigmas), same numbers.
  std::vector<BandCorrelation> correlate(const Heightfield& terrain) const;

private:
  int width_ = 0;
  int height_ = 0;
  std::vector<double> sigmas_;
  std::vector<std::vector<float>> bands_; // per sigma, NaN where invalid
};

} // namespace tsynth
