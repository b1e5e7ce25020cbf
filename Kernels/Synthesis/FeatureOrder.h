// The order the feature patches of a synthesis are placed in: sites along the
// target's feature tree, breadth first from its root, thinned where they crowd.
#pragma once

#include "../Matching/CandidatePool.h"
#include "Target.h"

#include <cstdint>
#include <vector>

namespace tsynth
{

// Where sites crowd, a feature site whose centre lies within this share of a
// patch of a site already placed is left to that patch: it carries the land
// there already, and a second patch would only cut the same seams again.
// Sites crowd on a DEM target's own PPA tree, whose lines lie 8-15 cells
// apart (2579 feature patches on a 648 x 648 Appalachian target, 558 with
// this, each cell under about 40 of them, for the same band-pass
// correlation), and on any drawing whose lines are closer than patches draw
// (kFinestDrawnSpacingInPatches, the fineness warning's case), such as a real
// DEM's tree used as the sketch. Drawings with room keep every site: theirs
// lie a quarter patch apart along a line (kSiteSpacingInPatches), where each
// stretch is drawn on purpose. A third of a patch rather than a quarter:
// on four DEM targets with two exemplars each, 35% fewer feature patches
// (feature placement 35-40% quicker), the band-pass correlation at 2, 4 and
// 8 cells within 0.04 either way (mean -0.005), seam and slope indices as
// before, and hillshades side by side that show the same land.
constexpr double kSiteClearanceInPatches = 1.0 / 3.0;

// Feature sites stand this share of a patch apart along a line. Each feature
// patch lays its own valley or ridge, straight or gently curved, across its
// footprint; the graph cut keeps of it what best joins its neighbours. At a
// quarter patch, every stretch of a line lies within an eighth of a patch of
// a patch's centre, where the match was made, rather than a quarter: on the
// bundled Y and meander over Colorado and Mont Blanc (44 runs,
// Testing/Benchmarks/sweep_seeds.py), the flanks agree more (0.788 against
// 0.773 at half a patch; better in 34 runs), drainage 0.889 against 0.855 and
// the seam index 0.884 against 0.902, for a legible share of 0.858 against
// 0.868; the feature patches grow by about 1.7 times (57 to 106 on a
// 1024-square Y, which takes 2-9% longer). Where sites crowd (featureSitesCrowd), spacedOut thins
// them to kSiteClearanceInPatches as before.
constexpr double kSiteSpacingInPatches = 0.25;

// The feature sites (featureSites, a quarter patch apart along each chain, each
// chain's first one shifted by a share of that drawn from the seed) in the
// order synthesise() places them: breadth first over the target's graph
// (FeatureGraph::bfsOrder), each node, then the path points of its chains not
// yet visited, walking away from the node; spaced out (spacedOut) when the
// sites crowd (featureSitesCrowd).
std::vector<FeatureSite> featurePlacementOrder(const SynthesisTarget& target,
  int patchSize,
  std::uint64_t seed);

// A DEM target, or lines closer than patches of this size draw
// (kFinestDrawnSpacingInPatches).
bool featureSitesCrowd(const SynthesisTarget& target, int patchSize);

// The sites in their order, less each one whose centre lies within
// `clearance` cells of one kept before it, on a grid of width x height cells.
std::vector<FeatureSite> spacedOut(const std::vector<FeatureSite>& sites,
  double clearance,
  int width,
  int height);

} // namespace tsynth
