// Tests of Kernels/Optimisation/OptimisationGuide.cxx: the guide a terrain
// optimisation follows, built from a sketch as the synthesis builds its target.
#include "Core/Error.h"
#include "ErrorOf.h"
#include "Optimisation/OptimisationGuide.h"
#include "OptimisationTestData.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

namespace tsynth
{
namespace
{

using test::errorOf;
using test::optimisation::source;

// A frame of `cells` x `cells` cells of the source's size with one straight
// line of `type` across its middle, from a fifth of the way in to four fifths.
PolylineSketch oneLine(int cells, FeatureType type)
{
  const double cell = source().cellX;
  PolylineSketch s;
  s.frameWidth = cells * cell;
  s.frameHeight = cells * source().cellY;
  Polyline line;
  line.type = type;
  const double y = 0.5 * cells * source().cellY;
  line.points = { { 0.2 * cells * cell, y }, { 0.8 * cells * cell, y } };
  s.lines.push_back(line);
  return s;
}

OptimisationOptions quickRun()
{
  OptimisationOptions o;
  o.seed = 7;
  return o;
}

// The guide's height on the line's middle over the mean of its heights
// `away` cells north and south of it.
double crestOverSides(const Heightfield& field, int away)
{
  const int i = field.width / 2;
  const int j = field.height / 2;
  return field.at(i, j) - 0.5 * (field.at(i, j - away) + field.at(i, j + away));
}

} // namespace

TEST(OptimisationGuide, AStrokeGuidesWithTheSourcesOwnLandform)
{
  const int cells = 160;
  const HeightRange relief = computeHeightRange(source());
  const double span = relief.max - relief.min;
  const OptimisationGuide ridge =
    buildOptimisationGuide(source(), oneLine(cells, FeatureType::Ridge), {}, quickRun());
  ASSERT_EQ(ridge.field.width, cells);
  ASSERT_EQ(ridge.field.height, cells);
  EXPECT_EQ(ridge.kind, "poly-lines");
  ASSERT_EQ(ridge.confidence.size(), ridge.field.size());
  for (float c : ridge.confidence)
  {
    ASSERT_GE(c, 0.0f);
    ASSERT_LE(c, 1.0f);
  }
  const OptimisationGuide valley =
    buildOptimisationGuide(source(), oneLine(cells, FeatureType::Valley), {}, quickRun());
  // The line's landform stands out of its sides by a share of the source's relief.
  const int away = 12; // cells: inside the landform a 96-cell line is given
  const double ridgeRise = crestOverSides(ridge.field, away);
  const double valleyRise = crestOverSides(valley.field, away);
  std::printf(
    "relief %.0f m; ridge %.0f m, valley %.0f m over their sides\n", span, ridgeRise, valleyRise);
  EXPECT_GT(ridgeRise, 0.2 * span);
  EXPECT_LT(valleyRise, -0.1 * span);
  // Most weight where the line is, least far from it.
  const std::size_t onLine = ridge.field.index(cells / 2, cells / 2);
  const std::size_t corner = ridge.field.index(2, 2);
  EXPECT_GT(ridge.confidence[onLine], ridge.confidence[corner]);
}

TEST(OptimisationGuide, TheSameSeedGivesTheSameGuide)
{
  const PolylineSketch sketch = oneLine(120, FeatureType::Ridge);
  const OptimisationGuide a = buildOptimisationGuide(source(), sketch, {}, quickRun());
  const OptimisationGuide b = buildOptimisationGuide(source(), sketch, {}, quickRun());
  EXPECT_EQ(a.field.z, b.field.z);
  EXPECT_EQ(a.confidence, b.confidence);
}

TEST(OptimisationGuide, ADemGuideFollowsTheDemOnTheSourcesHeights)
{
  // Another part of Colorado as the target, 96 cells a side, its relief a tenth
  // and 5 km up: the guide is brought onto the source's heights.
  Heightfield target = test::optimisation::crop(source(), 40, 30, 96, 96);
  for (float& z : target.z)
  {
    z = 0.1f * z + 5000.0f;
  }
  const OptimisationGuide guide = buildOptimisationGuide(source(), target, {}, quickRun());
  EXPECT_EQ(guide.kind, "DEM");
  ASSERT_EQ(guide.field.width, target.width);
  ASSERT_EQ(guide.field.height, target.height);
  // Pearson correlation of the guide with the target over every cell.
  double mf = 0.0, mt = 0.0;
  const std::size_t n = target.size();
  for (std::size_t k = 0; k < n; ++k)
  {
    mf += guide.field.z[k];
    mt += target.z[k];
  }
  mf /= n;
  mt /= n;
  double sff = 0.0, stt = 0.0, sft = 0.0;
  for (std::size_t k = 0; k < n; ++k)
  {
    const double f = guide.field.z[k] - mf, t = target.z[k] - mt;
    sff += f * f;
    stt += t * t;
    sft += f * t;
  }
  const double correlation = sft / std::sqrt(sff * stt);
  const HeightRange guideRange = computeHeightRange(guide.field);
  const HeightRange sourceRange = computeHeightRange(source());
  const HeightRange targetRange = computeHeightRange(target);
  std::printf("correlation with the target %.4f; guide %.0f..%.0f m, source %.0f..%.0f m, "
              "target %.0f..%.0f m\n",
    correlation,
    guideRange.min,
    guideRange.max,
    sourceRange.min,
    sourceRange.max,
    targetRange.min,
    targetRange.max);
  EXPECT_GT(correlation, 0.95);
  // On the source's heights, not the target's: about the source's relief, round its middle.
  const double sourceSpan = sourceRange.max - sourceRange.min;
  EXPECT_NEAR(guideRange.max - guideRange.min, sourceSpan, 0.25 * sourceSpan);
  EXPECT_NEAR(0.5 * (guideRange.max + guideRange.min),
    0.5 * (sourceRange.max + sourceRange.min),
    0.1 * sourceSpan);
}

TEST(OptimisationGuide, RefusesWhatCannotGuideBeforeAnyWork)
{
  SetupOptionNames names;
  names.size = "--size";
  const std::string small = errorOf([&]
    { buildOptimisationGuide(source(), oneLine(60, FeatureType::Ridge), {}, quickRun(), names); });
  EXPECT_NE(small.find("60 x 60 cells"), std::string::npos) << small;
  EXPECT_NE(small.find("give a larger --size"), std::string::npos) << small;

  OptimisationOptions tight = quickRun();
  tight.memoryBudget = 1.0; // bytes
  EXPECT_THROW(
    buildOptimisationGuide(source(), oneLine(120, FeatureType::Ridge), {}, tight), Error);

  Heightfield flat(64, 64);
  flat.cellX = flat.cellY = source().cellX;
  EXPECT_THROW(
    buildOptimisationGuide(flat, oneLine(120, FeatureType::Ridge), {}, quickRun()), Error);
}

} // namespace tsynth
