// The quality figures of one synthesis, as `tsynth synth` prints and reports them and the
// Terrain Synthesis filter lists them in its Report output: of the terrain, and of the patches
// before the final corrections (do the patches themselves follow the sketch?).
#pragma once

#include "../Metrics/LandformMetrics.h"
#include "../Metrics/Legibility.h"
#include "../Metrics/TerrainMetrics.h"
#include "Setup.h"
#include "Synthesiser.h"

#include <limits>
#include <string>
#include <vector>

namespace tsynth
{

// A stroke no other faces is read half a patch each side (LegibilityOptions::loneHalfWidth).
constexpr double kLoneHalfWidthInPatches = 0.5;

struct SynthesisFigures
{
  TerrainEvaluation quality;
  LandformMeasures landforms;
  Legibility legibility;
  Legibility patchLegibility;
  std::vector<BandCorrelation> correlation; // DEM targets only
  std::vector<BandCorrelation> patchCorrelation;
  // Feature placements' line offsets (cells): median and 90th percentile; NaN without any.
  double lineOffset = std::numeric_limits<double>::quiet_NaN();
  double lineOffset90 = std::numeric_limits<double>::quiet_NaN();
};

SynthesisFigures measureSynthesis(const SynthesisSetup& setup,
  const SynthesisResult& r,
  int patchSize);

// One figure by name: the names are the paths of `tsynth synth --report`'s JSON, joined by
// dots ("quality.seam_index", "legibility.ridge.legible_share"; a DEM target's band-pass
// correlations "target_correlation.sigma_4"). NaN where a figure does not apply.
struct FigureRow
{
  std::string name;
  double value = 0.0;
};

// The figures as rows: the Terrain Synthesis filter's Report table.
std::vector<FigureRow> figureRows(const SynthesisFigures& f);

// Count of the result's feature placements (those along the sketch's lines).
std::size_t featurePlacements(const SynthesisResult& r);

} // namespace tsynth
