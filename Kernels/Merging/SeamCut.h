// Graph-cut seam between old terrain A and a new patch B on their overlap
// window (Kwatra et al. 2003 as used by Zhou et al. 2007 and Tasse): which
// overlap pixels take the new patch, the seam, and its cost c_g.
#pragma once

#include "GridMaxFlow.h"

#include <cstdint>
#include <vector>

namespace tsynth
{

// What the cut may decide for a window pixel.
enum class SeamConstraint : std::uint8_t
{
  Outside = 0,  // not in the overlap (one input missing): not a graph node
  Free = 1,     // decided by the cut
  ForceOld = 2, // must keep the old terrain
  ForceNew = 3  // must take the new patch
};

// Builds the terminal constraints of a window from masks of the same size
// (1 = true): pixels valid in both are overlap pixels; an overlap pixel with a
// 4-neighbour that only the old terrain covers is forced old, one with a
// 4-neighbour only the patch covers, or inside the protected core, is forced
// new. Where both apply, the core wins, otherwise old wins (the existing
// terrain is never cut away next to itself). Give the window a one-cell frame
// beyond the patch (patch invalid there) so that filled terrain around the
// patch counts as old-only. core may be null.
std::vector<SeamConstraint> buildSeamConstraints(int width,
  int height,
  const std::uint8_t* oldMask,
  const std::uint8_t* newMask,
  const std::uint8_t* core);

struct SeamCutOptions
{
  // eps = relativeEpsilon * (mean over the overlap's edges of the Kwatra
  // denominator), floored at absoluteEpsilon (slope units, m/m). Relative so the
  // cost does not depend on how rough the data are; large enough that a flat
  // area weighs at most 1 / relativeEpsilon times a typical one.
  double relativeEpsilon = 0.01;
  double absoluteEpsilon = 1e-6;
  // false: plain Zhou cost |A(s)-B(s)| + |A(t)-B(t)| (no gradient term).
  bool gradientTerm = true;
};

struct SeamCutResult
{
  int width = 0;
  int height = 0;
  // Per window pixel: 1 if the pixel ends up with the new patch (overlap pixels
  // the cut gives to B, forced-new pixels). 0 elsewhere, including Outside.
  std::vector<std::uint8_t> takeNew;
  // Per window pixel: 1 if one of its overlap edges is cut.
  std::vector<std::uint8_t> seam;
  double cost = 0.0; // c_g: sum of the Kwatra weights of the cut edges
  int cutEdges = 0;
  double flow = 0.0; // max-flow value of the reduced graph (equals cost up to rounding)
  // Cost per cut edge, for ranking candidates with seams of different lengths.
  double normalisedCost() const { return cutEdges > 0 ? cost / cutEdges : 0.0; }
};

// Kwatra edge weights of a window, stored per pixel for the +x and +y edge:
// wx[k] is the edge (i,j)-(i+1,j), wy[k] the edge (i,j)-(i,j+1); NaN where the
// edge is not an overlap edge. Exposed for tests and reference solvers.
struct SeamWeights
{
  std::vector<double> wx;
  std::vector<double> wy;
  double epsilon = 0.0;
};

// A reusable graph-cut workspace: hold one per thread and call cut() for each
// candidate; buffers are resized only when the window grows.
class SeamCut
{
public:
  // A and B: window heights, row-major width x height (row 0 south); NaN in
  // either makes a pixel Outside whatever its constraint says. cellX, cellY in
  // metres scale the gradients. constraints may be null (every overlap pixel
  // Free).
  const SeamCutResult& cut(int width,
    int height,
    const float* oldZ,
    const float* newZ,
    const SeamConstraint* constraints,
    double cellX,
    double cellY,
    const SeamCutOptions& options = {});

  const SeamCutResult& result() const { return result_; }
  // The weights of the last cut() call.
  const SeamWeights& weights() const { return weights_; }

  // Only computes the weights (with NaN-masked constraints applied).
  static void computeWeights(int width,
    int height,
    const float* oldZ,
    const float* newZ,
    const std::vector<SeamConstraint>& constraints,
    double cellX,
    double cellY,
    const SeamCutOptions& options,
    SeamWeights& out);

private:
  GridMaxFlow flow_;
  SeamWeights weights_;
  std::vector<SeamConstraint> constraints_;
  SeamCutResult result_;
};

} // namespace tsynth
