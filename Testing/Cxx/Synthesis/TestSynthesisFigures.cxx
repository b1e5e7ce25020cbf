// Tests of Kernels/Synthesis/SynthesisFigures.cxx.
// The Report table's rows: each figure under the path `tsynth synth --report`
// writes it at (python.frontends compares the two), with its own value.
#include "Synthesis/SynthesisFigures.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <string>

using namespace tsynth;

namespace
{

std::map<std::string, double> rowsByName(const SynthesisFigures& f)
{
  std::map<std::string, double> rows;
  for (const FigureRow& r : figureRows(f))
  {
    EXPECT_TRUE(rows.emplace(r.name, r.value).second) << "two rows named " << r.name;
  }
  return rows;
}

} // namespace

TEST(SynthesisFigures, EachFigureIsARowUnderItsReportPath)
{
  SynthesisFigures f;
  f.quality.seamIndex = 1.25;
  f.quality.pitDensity = std::numeric_limits<double>::quiet_NaN(); // does not apply
  f.landforms.valleyDrainage = 0.875;
  f.legibility.share = 0.5;
  f.legibility.ridge.samples = 42;
  f.patchLegibility.valley.halfWidth = 3.5;
  f.lineOffset = 1.5;
  f.lineOffset90 = 4.0;
  f.correlation = { { 4.0, 0.75 }, { 16.0, 0.625 } };
  const std::map<std::string, double> rows = rowsByName(f);
  EXPECT_EQ(rows.at("quality.seam_index"), 1.25);
  EXPECT_TRUE(std::isnan(rows.at("quality.pit_density")));
  EXPECT_EQ(rows.at("landform_quality.valley_drainage"), 0.875);
  EXPECT_EQ(rows.at("legibility.legible_share"), 0.5);
  EXPECT_EQ(rows.at("legibility.ridge.samples"), 42.0);
  EXPECT_EQ(rows.at("legibility_before_corrections.valley.median_half_width_cells"), 3.5);
  EXPECT_EQ(rows.at("feature_line_offset_cells.median"), 1.5);
  EXPECT_EQ(rows.at("feature_line_offset_cells.p90"), 4.0);
  EXPECT_EQ(rows.at("target_correlation.sigma_4"), 0.75);
  EXPECT_EQ(rows.at("target_correlation.sigma_16"), 0.625);
  EXPECT_EQ(rows.count("target_correlation_before_corrections.sigma_4"), 0u)
    << "no correlation row without a DEM target";
}

TEST(SynthesisFigures, FeaturePlacementsAreTheOnesAlongTheLines)
{
  SynthesisResult r;
  for (bool feature : { true, false, true, true, false })
  {
    Placement p;
    p.feature = feature;
    r.placements.push_back(p);
  }
  EXPECT_EQ(featurePlacements(r), 3u);
  EXPECT_EQ(featurePlacements(SynthesisResult{}), 0u);
}
