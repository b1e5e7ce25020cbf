// The last steps of a synthesis, once every patch is placed: gentle
// corrections that leave the patches' landforms and detail alone (the role of
// Tasse's final deformation), and exact ones for what the sketch requires.
#pragma once

#include "../Core/Heightfield.h"
#include "../Core/PatchSize.h"
#include "../Features/FeatureGraph.h"
#include "../Hydrology/PitRemoval.h"
#include "Target.h"

#include <cstddef>
#include <optional>
#include <vector>

namespace tsynth
{

// The final correction draws the target down to this share of a patch
// (Gaussian sigma; 8 cells for 80-cell patches): relief finer than it is the
// exemplars' own character, which a finer correction would replace by the
// target's (a DEM target's whole shape, a drawing's smooth flanks).
constexpr double kFinestCorrectionInPatches = 0.1;
// It follows landforms this many sigmas wide each side: strokes closer than
// 2 x 3 x 0.1 = 0.6 patches apart cannot be drawn at their own scale.
constexpr double kCorrectionSigmasPerHalfWidth = 3.0;
// So lines closer than this share of a patch are finer than patches draw.
constexpr double kFinestDrawnSpacingInPatches =
  2.0 * kCorrectionSigmasPerHalfWidth * kFinestCorrectionInPatches;

struct FinishingReport
{
  double landformCorrection = 0.0; // largest change of the landform correction, m
  std::size_t valleyCells = 0;     // sketched valley line cells
  std::size_t valleyCellsLowered = 0;
  double deepestValleyCut = 0.0; // m
  double meanValleyCut = 0.0;    // m, over the valley line cells
  bool drained = false;          // drainage was asked for; then:
  std::size_t pitsBefore = 0;    // strict local minima before it
  std::size_t pitsAfter = 0;
  double largestDrainageRaise = 0.0;    // m
  double largestDrainageLowering = 0.0; // m
  double meanDrainageChange = 0.0;      // m, mean absolute change over the terrain
  // Cells past the exemplars' range brought back within a tenth of its span
  // of it (compressIntoRange, Finishing.h).
  std::size_t cellsBroughtIntoRange = 0;
};

// How a synthesis is finished: the options of SynthesisOptions that the
// finishing follows, and the height range the placement kept to.
struct FinishingPlan
{
  int patchSize = kDefaultSynthesisPatch;
  // SynthesisOptions::correctionScale: the coarsest scale of the landform
  // correction, cells; < 0: kCorrectionScaleInPatches of a patch; 0: off.
  double correctionScale = -1.0;
  bool drainValleys = true;                 // SynthesisOptions::drainValleys
  std::optional<PitRemovalMethod> drainage; // SynthesisOptions::drainage
  // The exemplars' height range, and how far past it heights may end
  // (compressIntoRange). lowest > highest: no range.
  double lowest = 0.0;
  double highest = -1.0;
  double slack = 0.0;
};

// The finishing of a synthesis, on `out`, the placed patches with every cell
// filled, and the target they followed (its confidence per cell; empty: 1):
// 1. the landform correction: the relief coarser than each cell's scale (a
//    share of the sketched landform's half width there, at most the plan's
//    correction scale) pulled towards the target's, as far as the target is
//    confident; a drawn target's landforms in their own shape
//    (correctLandformAtScales);
// 2. where the target leaves the land free, only the drift over several
//    patches removed (correctLandform);
// 3. the sketched valleys made to drain (drainValleys), if the plan says so;
// 4. heights past the exemplars' range brought back into it (compressIntoRange);
// 5. the height constraints met exactly (meetConstraints): the user's heights win;
// 6. every cell drained by the plan's method (removePitsMultiscale), if asked.
// Returns what each step did.
FinishingReport finishSynthesis(Heightfield& out,
  const SynthesisTarget& target,
  const std::vector<float>& confidence,
  const FinishingPlan& plan);

// Pulls the output's relief coarser than `sigma` cells towards the target's
// (`smoothTarget`: the target through smoothLarge at the same sigma), by the
// target's confidence per cell (empty: 1): what drifted across many patches
// goes, the detail finer than sigma stays the patches'. Returns the largest
// change, metres.
double correctLandform(Heightfield& out,
  const Heightfield& smoothTarget,
  const std::vector<float>& confidence,
  double sigma);

// The same at a scale that varies from cell to cell: the relief coarser than
// sigma[c] cells is pulled towards the target's at cell c (`target` itself,
// not smoothed). The corrections are made at scales a factor two apart from
// `largestSigma` down to `finestSigma` and interpolated between them in log
// sigma; sigmas outside that range are taken as its ends. The scales and the
// confidence are smoothed over the finest level first, so the correction has
// no crease where they kink. Returns the largest change, metres.
//
// `targetSigma` > 0: the output's relief coarser than sigma[c] is replaced by
// the target's own shape smoothed at only `targetSigma` cells (at most
// sigma[c]), not by the target's relief coarser than sigma[c]: out + w (G_t T
// - G_s out) instead of out + w G_s (T - out). The patches' detail finer than
// sigma[c] stays on top either way; what changes is that a landform narrower
// than a few sigma keeps its full depth and its crisp crest or floor, where
// the blurred target drew it shallow and round (a valley 20 cells wide came
// out at half its depth). For drawn targets, whose shapes are the sketch's
// landforms; a DEM target's own detail would replace the exemplars'.
double correctLandformAtScales(Heightfield& out,
  const Heightfield& target,
  const std::vector<float>& confidence,
  const std::vector<float>& sigma,
  double largestSigma,
  double finestSigma,
  double targetSigma = 0.0);

struct DrainageOptions
{
  // The floor falls at least this much per metre along a valley (0.1%: gentle
  // enough for any real floor, enough for D8 to see the way).
  double minimumGradient = 0.001;
  // The channel lies this much below the cells beside it, metres per metre of
  // cell size (0.1 m for 100 m cells).
  double channelDepth = 0.001;
  // ... but a channel is cut at most this deep, metres per metre of cell size
  // (4.5 m for 90 m cells): where a line runs along a steep side, a deeper slot
  // would show as a crease, and the water finds the floor beside the line.
  double maximumChannelCut = 0.05;
  // Carving fades out over this many cells either side of the line.
  double reach = 10.0;
};

struct DrainageReport
{
  std::size_t cells = 0;   // valley line cells
  std::size_t lowered = 0; // of which were lowered
  double largest = 0.0;    // deepest cut, metres
  double mean = 0.0;       // mean cut over the line cells, metres
};

// Makes water run along the sketched valleys: along the lines (cells with a
// finite `downstream` flow distance) each cell is lowered, if need be, below
// every cell upstream of it and below the cells beside the line, and the cut
// fades out smoothly over `reach` cells (stream burning, as hydrologists
// condition a DEM to a known river). D8 flow then follows the lines. A line
// whose outlet (flow distance 0) is a closed basin is continued out of it
// first, down the way complete breaching would drain it to the border (or,
// where that way runs back up the valley's own lines, over the lowest crossing
// that leaves them alone), and that way is burnt as the lines are: its water
// leaves instead of filling a lake over the valley's lower part. Each
// connected network's floors are fitted on their own. The report counts the
// drawn lines only.
DrainageReport drainValleys(Heightfield& out,
  const std::vector<float>& downstream,
  const DrainageOptions& options = {});

// Heights past [low, high] brought back smoothly into [low - slack, high +
// slack]: z = low - slack tanh((low - z) / slack) below low, and the same
// above high, so that the terrain keeps within the exemplars' range widened by
// `slack` each way. Increasing and smooth (slope 1 at low and high): water
// runs where it ran, and nothing inside [low, high] moves. Returns the number
// of cells moved. slack <= 0 or low > high: no change.
std::size_t compressIntoRange(Heightfield& out, double low, double high, double slack);

// Height constraints (poly-line Elevation): bends the terrain so the
// constrained lines sit exactly at their heights; the correction is harmonic
// between the lines and fades to nothing `reach` cells away.
void meetConstraints(Heightfield& out, const FeatureGraph& graph, double reach);

} // namespace tsynth
