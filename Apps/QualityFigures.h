// The quality figures `tsynth synth` and `tsynth evaluate` both print and
// write: one line each on stdout, or JSON objects (NaN, a figure that does not
// apply, is "-" in print and null in JSON).
#pragma once

#include "Metrics/LandformMetrics.h"
#include "Metrics/Legibility.h"
#include "Metrics/TerrainMetrics.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace tsynth::cli
{

// v with `digits` decimals, or "-" for NaN.
std::string figure(double v, int digits);

// One line each, led by `name` in a column of its own.
void printEvaluation(const char* name, const TerrainEvaluation& e);
void printLandforms(const char* name, const LandformMeasures& m);
void printLegibility(const char* name, const Legibility& l);
void printCorrelation(const char* name, const std::vector<BandCorrelation>& bands);

nlohmann::json evaluationJson(const TerrainEvaluation& e);
nlohmann::json landformJson(const LandformMeasures& m);
nlohmann::json legibilityJson(const Legibility& l);
nlohmann::json correlationJson(const std::vector<BandCorrelation>& bands);

} // namespace tsynth::cli
