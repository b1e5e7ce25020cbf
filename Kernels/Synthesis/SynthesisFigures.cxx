#include "SynthesisFigures.h"

#include "../Core/Heightfield.h"

#include <algorithm>
#include <cmath>
#include <future>
#include <utility>

namespace tsynth
{

SynthesisFigures measureSynthesis(const SynthesisSetup& setup,
  const SynthesisResult& r,
  int patchSize)
{
  SynthesisFigures f;
  // The quality and landform figures on threads of their own while this one
  // reads the legibility and correlations: they share nothing but const
  // inputs, and most of their work is serial.
  auto quality = std::async(std::launch::async,
    [&] { return evaluateTerrain(r.terrain, setup.exemplarPointers(), &setup.target.graph); });
  auto landforms = std::async(std::launch::async,
    [&]
    {
      LandformOptions lo;
      lo.patchSize = patchSize;
      return evaluateLandforms(
        r.terrain, setup.target.graph, setup.exemplarPointers(), setup.graphPointers(), lo);
    });
  LegibilityOptions go;
  go.loneHalfWidth = kLoneHalfWidthInPatches * patchSize;
  const LegibilityMeter legibility(setup.target.graph, setup.landform.land, go);
  f.legibility = legibility.measure(r.terrain);
  f.patchLegibility = legibility.measure(r.patches);
  if (setup.sketchKind == "DEM")
  {
    const BandPassTarget target(setup.target.field, defaultCorrelationScales());
    f.correlation = target.correlate(r.terrain);
    f.patchCorrelation = target.correlate(r.patches);
  }
  f.quality = quality.get();
  f.landforms = landforms.get();
  std::vector<float> offsets;
  for (const Placement& p : r.placements)
  {
    if (p.feature && !std::isnan(p.lineOffset))
    {
      offsets.push_back(p.lineOffset);
    }
  }
  if (!offsets.empty())
  {
    f.lineOffset = percentile(offsets, 0.5);
    f.lineOffset90 = percentile(offsets, 0.9);
  }
  return f;
}

namespace
{

void addQuality(std::vector<FigureRow>& rows, const TerrainEvaluation& e)
{
  rows.push_back({ "quality.ridge_fidelity", e.ridgeFidelity });
  rows.push_back({ "quality.valley_fidelity", e.valleyFidelity });
  rows.push_back({ "quality.seam_index", e.seamIndex });
  rows.push_back({ "quality.slope_distance", e.slopeDistance });
  rows.push_back({ "quality.pit_density", e.pitDensity });
}

void addLandforms(std::vector<FigureRow>& rows, const LandformMeasures& m)
{
  const std::string at = "landform_quality.";
  rows.push_back({ at + "ridge_prominence_m", m.ridgeProminence });
  rows.push_back({ at + "ridge_prominence_ratio", m.ridgeProminenceRatio });
  rows.push_back({ at + "valley_depth_m", m.valleyDepth });
  rows.push_back({ at + "valley_depth_ratio", m.valleyDepthRatio });
  rows.push_back({ at + "ridge_over_valley", m.ridgeOverValley });
  rows.push_back({ at + "valley_drainage", m.valleyDrainage });
  rows.push_back({ at + "valley_descent", m.valleyDescent });
  rows.push_back({ at + "ridge_shedding", m.ridgeShedding });
}

void addLegibility(std::vector<FigureRow>& rows, const std::string& at, const Legibility& l)
{
  rows.push_back({ at + ".legible_share", l.share });
  rows.push_back({ at + ".flank_agreement", l.flankAgreement });
  rows.push_back({ at + ".weakest_stroke_share", l.weakestShare() });
  for (const auto& [kind, k] :
    { std::pair{ ".ridge", &l.ridge }, std::pair{ ".valley", &l.valley } })
  {
    rows.push_back({ at + kind + ".legible_share", k->share });
    rows.push_back({ at + kind + ".samples", static_cast<double>(k->samples) });
    rows.push_back({ at + kind + ".median_prominence_m", k->prominence });
    rows.push_back({ at + kind + ".median_threshold_m", k->threshold });
    rows.push_back({ at + kind + ".median_half_width_cells", k->halfWidth });
    rows.push_back({ at + kind + ".flank_agreement", k->flankAgreement });
  }
}

void addCorrelation(std::vector<FigureRow>& rows,
  const std::string& at,
  const std::vector<BandCorrelation>& bands)
{
  for (const BandCorrelation& b : bands)
  {
    rows.push_back(
      { at + ".sigma_" + std::to_string(static_cast<int>(std::lround(b.sigma))), b.correlation });
  }
}

} // namespace

std::vector<FigureRow> figureRows(const SynthesisFigures& f)
{
  std::vector<FigureRow> rows;
  addQuality(rows, f.quality);
  addLandforms(rows, f.landforms);
  addLegibility(rows, "legibility", f.legibility);
  addLegibility(rows, "legibility_before_corrections", f.patchLegibility);
  rows.push_back({ "feature_line_offset_cells.median", f.lineOffset });
  rows.push_back({ "feature_line_offset_cells.p90", f.lineOffset90 });
  addCorrelation(rows, "target_correlation", f.correlation);
  addCorrelation(rows, "target_correlation_before_corrections", f.patchCorrelation);
  return rows;
}

std::size_t featurePlacements(const SynthesisResult& r)
{
  return static_cast<std::size_t>(std::count_if(
    r.placements.begin(), r.placements.end(), [](const Placement& p) { return p.feature; }));
}

} // namespace tsynth
