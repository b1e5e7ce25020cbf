// Matching at one place of a target, as the Terrain Patch Matcher filter shows
// it: the best candidates for the patch-sized window around a site, as a
// feature match at the nearest target feature site (the synthesis' feature
// placements) or as a dense match (its fill placements), and a map of the
// lowest cost of a candidate centred on each cell of the first exemplar.
// In ParaView: vtkTerrainPatchMatcher (Terrain Patch Matcher), in Filters/.
#pragma once

#include "../Core/Heightfield.h"
#include "PatchMatcher.h"

#include <cstdint>
#include <string>
#include <vector>

namespace tsynth
{

struct SiteMatchResult
{
  std::vector<PatchCandidate> candidates; // best first
  bool atFeature = false;                 // matched at a target feature site
  double centreX = 0.0;                   // cells: where the window was centred
  double centreY = 0.0;
  // Per cell of exemplar 0: the lowest cost of a candidate centred there (feature
  // mode: the candidates of the pool; dense mode: the coarse cost of the
  // unrotated exemplar, block by block); NaN where none is.
  std::vector<float> costMap;
  std::vector<std::string> warnings;
};

// `known` has one byte per target cell (1: the window may use it); the site
// (siteX, siteY) is in target cells. In feature mode the target's ridges and
// valleys are found with PPA (the default options, as a DEM target gets in the
// synthesis) and the nearest feature site within half a patch is used; if none
// is that near, a dense match is made and a warning says so. Throws
// tsynth::Error for a target smaller than a patch or a `known` of the wrong size.
SiteMatchResult matchAtSite(PatchMatcher& matcher,
  const Heightfield& target,
  const std::vector<std::uint8_t>& known,
  double siteX,
  double siteY,
  bool featureMode,
  int patchSize);

} // namespace tsynth
