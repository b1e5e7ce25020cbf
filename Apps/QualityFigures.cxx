#include "QualityFigures.h"

#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace tsynth::cli
{

nlohmann::json evaluationJson(const TerrainEvaluation& e)
{
  nlohmann::json notes = nlohmann::json::object();
  for (const auto& [field, why] : e.notes)
  {
    notes[field] = why;
  }
  // nlohmann writes NaN (a figure that does not apply) as null; notes say why.
  return { { "ridge_fidelity", e.ridgeFidelity },
    { "valley_fidelity", e.valleyFidelity },
    { "seam_index", e.seamIndex },
    { "slope_distance", e.slopeDistance },
    { "pit_density", e.pitDensity },
    { "notes", notes } };
}

std::string figure(double v, int digits)
{
  return std::isnan(v)
    ? std::string("-")
    : (std::ostringstream() << std::fixed << std::setprecision(digits) << v).str();
}

void printLandforms(const char* name, const LandformMeasures& m)
{
  std::cout << std::left << std::setw(22) << name << " landforms: ridges "
            << figure(m.ridgeProminence, 0) << " m (x" << figure(m.ridgeProminenceRatio, 2)
            << "), valleys " << figure(m.valleyDepth, 0) << " m (x" << figure(m.valleyDepthRatio, 2)
            << "), order " << figure(m.ridgeOverValley, 3) << ", drainage "
            << figure(m.valleyDrainage, 3) << ", descent " << figure(m.valleyDescent, 3)
            << ", shedding " << figure(m.ridgeShedding, 3) << "\n";
}

nlohmann::json landformJson(const LandformMeasures& m)
{
  nlohmann::json notes = nlohmann::json::object();
  for (const auto& [field, why] : m.notes)
  {
    notes[field] = why;
  }
  return { { "ridge_prominence_m", m.ridgeProminence },
    { "ridge_prominence_ratio", m.ridgeProminenceRatio },
    { "valley_depth_m", m.valleyDepth },
    { "valley_depth_ratio", m.valleyDepthRatio },
    { "ridge_over_valley", m.ridgeOverValley },
    { "valley_drainage", m.valleyDrainage },
    { "valley_descent", m.valleyDescent },
    { "ridge_shedding", m.ridgeShedding },
    { "notes", notes } };
}

nlohmann::json legibilityJson(const Legibility& l)
{
  auto kind = [](const StrokeLegibility& k)
  {
    return nlohmann::json{ { "legible_share", k.share },
      { "samples", k.samples },
      { "median_prominence_m", k.prominence },
      { "median_threshold_m", k.threshold },
      { "median_half_width_cells", k.halfWidth },
      { "flank_agreement", k.flankAgreement } };
  };
  nlohmann::json strokes = nlohmann::json::array();
  for (const StrokeReading& r : l.strokes)
  {
    strokes.push_back({ { "type", r.type == FeatureType::Ridge ? "ridge" : "valley" },
      { "length_cells", r.length },
      { "samples", r.samples },
      { "legible_share", r.share },
      { "centre_cells", { r.centre.x, r.centre.y } } });
  }
  return { { "legible_share", l.share },
    { "flank_agreement", l.flankAgreement },
    { "ridge", kind(l.ridge) },
    { "valley", kind(l.valley) },
    { "weakest_stroke_share", l.weakestShare() },
    { "strokes", strokes } };
}

nlohmann::json correlationJson(const std::vector<BandCorrelation>& bands)
{
  nlohmann::json out = nlohmann::json::array();
  for (const BandCorrelation& b : bands)
  {
    out.push_back({ { "sigma_cells", b.sigma }, { "correlation", b.correlation } });
  }
  return out;
}

void printLegibility(const char* name, const Legibility& l)
{
  std::cout << std::left << std::setw(22) << name << " legible: " << figure(l.share, 2)
            << " of the stroke length (ridges " << figure(l.ridge.share, 2) << ", valleys "
            << figure(l.valley.share, 2) << "); flanks agree " << figure(l.flankAgreement, 2)
            << "\n";
  if (l.weakest < l.strokes.size())
  {
    const StrokeReading& w = l.strokes[l.weakest];
    std::cout << std::setw(22) << ""
              << " weakest stroke: " << figure(w.share, 2) << " legible, a "
              << (w.type == FeatureType::Ridge ? "ridge" : "valley") << " " << std::lround(w.length)
              << " cells long centred at cell (" << std::lround(w.centre.x) << ", "
              << std::lround(w.centre.y) << ") of " << l.strokes.size() << " stroke"
              << (l.strokes.size() == 1 ? "" : "s") << "\n";
  }
}

void printCorrelation(const char* name, const std::vector<BandCorrelation>& bands)
{
  std::cout << std::left << std::setw(22) << name << " band-pass correlation with the target:";
  for (const BandCorrelation& b : bands)
  {
    std::cout << " " << figure(b.correlation, 2) << " (" << b.sigma << " cells)";
  }
  std::cout << "\n";
}

void printEvaluation(const char* name, const TerrainEvaluation& e)
{
  auto f = [](double v)
  {
    return std::isnan(v) ? std::string("  -  ")
                         : (std::ostringstream() << std::fixed << std::setprecision(3) << v).str();
  };
  std::cout << std::left << std::setw(22) << name << " fidelity ridge " << f(e.ridgeFidelity)
            << " valley " << f(e.valleyFidelity) << "  seam " << f(e.seamIndex) << "  slope "
            << f(e.slopeDistance) << "  pits " << f(e.pitDensity) << "\n";
}

} // namespace tsynth::cli
