// Merging a placed patch into the terrain being synthesised: graph-cut seam,
// then one of the seam-removal methods of Zhou et al. 2007 and Tasse's thesis.
// In ParaView: vtkTerrainGraphCutMerger (Terrain Graph Cut Merger), in Filters/.
#pragma once

#include "../Core/Heightfield.h"
#include "../Core/OptionTable.h"
#include "MergeLimits.h"
#include "Poisson.h"
#include "SeamCut.h"

#include <cstddef>
#include <cstdint>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

namespace tsynth
{

enum class MergeMode
{
  Cut,     // labels only: new cells take the patch heights as they are
  Poisson, // Zhou: gradients across the seam removed, Poisson solve
  Shepard, // height mismatch on the seam spread by Shepard interpolation
  New      // Tasse: gradient mismatch spread by Shepard, then Poisson (default)
};

// The merge modes' words, by value (Core/OptionTable.h).
inline constexpr const char* kMergeModeWords[] = { "cut", "poisson", "shepard", "new" };
static_assert(std::size(kMergeModeWords) == static_cast<std::size_t>(MergeMode::New) + 1);

// One of kMergeModeWords; throws tsynth::Error naming them otherwise.
MergeMode parseMergeMode(const std::string& name);
const char* mergeModeName(MergeMode mode);

struct MergeOptions
{
  MergeMode mode = MergeMode::New;
  SeamCutOptions cut;
  // Shepard radius of influence d_phi (cells; Tasse's Fig. 3.8 uses 20) and
  // exponent alpha of w = ((d_phi - d) / (d_phi d))^alpha.
  double shepardRadius = 20.0;
  double shepardPower = 2.0;
  PoissonOptions poisson;
  // Poisson and New modes stop the solve once its estimated height error is at
  // most this fraction of the window's height range (1e-4: 0.1 m on 1000 m of
  // relief, far below DEM precision), unless poisson.errorTolerance is set.
  // 0 = solve to poisson.tolerance only.
  double relativeHeightTolerance = 1e-4;
  // New mode: the spread gradient correction integrates into a tilt of the
  // patch's far side, and with its free border (new cells next to unfilled
  // ones) unanchored the next patch fits to it: on steep exemplars the tilts
  // add up patch after patch (Mont Blanc on 80-cell patches: down to -5621 m
  // where the exemplar spans 454-4810 m). A solve whose free border leaves
  // [lowestHeight, highestHeight] is therefore solved again anchored: the free
  // border farther than the Shepard radius from the seam keeps the patch's own
  // heights, shifted by the mean mismatch on the seam. anchorFreeBorder
  // anchors every solve. Anchoring every patch keeps the range but flattens
  // Colorado (slope distance 0.074 -> 0.117 over 44 syntheses): the tilts carry
  // real relief, so they are only stopped where they run away.
  float lowestHeight = -std::numeric_limits<float>::infinity();
  float highestHeight = std::numeric_limits<float>::infinity();
  bool anchorFreeBorder = false;
};

struct MergeResult
{
  // The patch window clipped to the terrain, in terrain cells.
  int x0 = 0;
  int y0 = 0;
  int width = 0;
  int height = 0;
  // Per window cell: 1 where the terrain now holds heights from the patch.
  std::vector<std::uint8_t> takeNew;
  // Per window cell: 1 on overlap cells with a cut edge.
  std::vector<std::uint8_t> seam;
  double cutCost = 0.0; // c_g
  int cutEdges = 0;
  double normalisedCost = 0.0; // c_g per cut edge (0 without a seam)
  std::size_t overlapCells = 0;
  std::size_t newCells = 0;
  PoissonStatistics poisson; // Poisson and New modes
  bool anchored = false;     // New mode: the free border was anchored (anchorFreeBorder or bounds)
};

// Reusable workspace (one per thread): merge() and seamCost() keep their
// buffers, the graph-cut storage and the multigrid hierarchy between calls.
//
// Conventions:
// - filled has terrain.size() entries; a terrain cell is "old" where filled,
//   valid and finite. Invalid or NaN cells never enter a cost, sum or average.
// - The patch (same cell size as the terrain) is placed with its cell (0, 0)
//   on terrain cell (x0, y0) and clipped to the terrain. core, if not null, has
//   patch.size() entries (1 = must come from the patch).
// - A patch entirely outside the terrain throws tsynth::Error. A patch with no
//   overlap (e.g. the first one) is a defined case: its valid cells are copied
//   into unfilled cells, blended against any old cells they touch, cost 0.
// - Only cells that take the patch are written; old terrain is the Dirichlet
//   boundary of every solve and is never changed. Patch borders next to
//   unfilled cells are left free (Neumann), so a height offset between the
//   patch and the terrain is carried away from the seam instead of squeezed.
class PatchMerger
{
public:
  MergeResult merge(Heightfield& terrain,
    std::vector<std::uint8_t>& filled,
    const Heightfield& patch,
    int x0,
    int y0,
    const std::vector<std::uint8_t>* core,
    const MergeOptions& options = {},
    const MergeResult* cut = nullptr);

  // Dry run for ranking candidates: the cut only; the terrain is not touched.
  // Passing its result to merge() as `cut` (same terrain, filled mask, patch,
  // placement and core) merges with that seam instead of cutting again.
  MergeResult seamCost(const Heightfield& terrain,
    const std::vector<std::uint8_t>& filled,
    const Heightfield& patch,
    int x0,
    int y0,
    const std::vector<std::uint8_t>* core,
    const SeamCutOptions& options = {});

private:
  MergeResult prepare(const Heightfield& terrain,
    const std::vector<std::uint8_t>& filled,
    const Heightfield& patch,
    int x0,
    int y0,
    const std::vector<std::uint8_t>* core,
    const SeamCutOptions& options,
    const MergeResult* given); // a seamCost() result to use instead of cutting
  // Shepard interpolation of V values per seam point (seamValue_) to the new cells.
  template<int V>
  void shepard(double radius, double power, std::vector<double>& out);
  void blendShepard(const MergeOptions& options);
  void blendPoisson(const MergeOptions& options, bool gradientShepard, MergeResult& result);
  // The Poisson solve of the new side, its free border anchored if asked.
  PoissonStatistics solveNewSide(bool gradientShepard,
    bool anchored,
    double anchorDistance,
    const PoissonOptions& poisson);
  // True if a solved free-border cell lies outside [lowest, highest].
  bool freeBorderOutside(float lowest, float highest) const;
  // Chamfer distance in cells from the seam points (seamX_, seamY_) per window cell.
  void seamDistance(std::vector<float>& out) const;
  // True if window cell k borders a cell with no terrain (or the window's edge).
  bool onFreeBorder(std::size_t k) const;

  SeamCut cut_;
  MaskedPoissonSolver poisson_;
  // Framed window (patch window clipped, plus one cell around where the
  // terrain has it): origin, size, heights of both sides and the outcome.
  int fx0_ = 0, fy0_ = 0, fw_ = 0, fh_ = 0;
  double cellX_ = 1.0, cellY_ = 1.0;
  std::vector<float> old_, new_;
  std::vector<std::uint8_t> oldMask_, newMask_, coreMask_, side_; // side: 0 none, 1 old, 2 new
  std::vector<double> out_;
  std::vector<double> gx_, gy_;
  // Shepard seam points: position and values (1 or 2 per point).
  std::vector<float> seamX_, seamY_;
  std::vector<double> seamValue_;
  std::vector<double> shepardOut_;
  std::vector<float> seamDistance_;
  // Shepard scratch: seam point per cell, the points of the current row band.
  std::vector<std::int32_t> pointAt_;
  std::vector<std::int32_t> bandX_, bandDy2_;
  std::vector<float> weight_;
  std::vector<double> bandValue_;
};

// The Graph-Cut Merger filter's options (Core/OptionTable.h), their defaults a default
// MergeOptions': the mode (the synthesis' Merge Mode words and labels) and the Shepard radius.
// No tsynth command merges one patch alone.
const std::vector<OptionRow>& mergeOptionRows();

} // namespace tsynth
