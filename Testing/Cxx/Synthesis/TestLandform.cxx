// Tests of Kernels/Synthesis/Landform.cxx.
// Landforms at the scale of the drawing: cross-sections measured on analytic
// exemplars with known answers (and a sanity range on a real DEM), and the
// target field a sketch's lines make from hand-made statistics.
#include "Core/Error.h"
#include "Core/HeightfieldIO.h"
#include "Features/ImpliedLines.h"
#include "Features/Ppa.h"
#include "Features/Sketch.h"
#include "LandformTestData.h"
#include "Synthesis/Landform.h"
#include "TestData.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <set>
#include <string>

using namespace tsynth;
using tsynth::test::landform::kCell;
using tsynth::test::landform::terrain;

namespace
{

constexpr int kPatch = 32; // cells

// Ridges and valleys as the synthesis reads them off an exemplar (every PPA
// line, significance 0, as Setup's exemplarPpaOptions).
FeatureGraph ridgesAndValleys(const Heightfield& hf)
{
  PpaOptions o;
  o.significance = 0.0;
  FeatureGraph g = extractFeatures(hf, FeatureType::Ridge, o).graph;
  appendGraph(g, extractFeatures(hf, FeatureType::Valley, o).graph);
  return g;
}

bool hasWarning(const std::vector<std::string>& warnings, const std::string& part)
{
  return std::any_of(warnings.begin(),
    warnings.end(),
    [&](const std::string& w) { return w.find(part) != std::string::npos; });
}

// ---------------------------------------------------------------------------
// The analytic exemplar: parallel north-south Gaussian ridges (sign +1) or
// valleys (-1) of height kH and width kS cells on a plain at kBase, 100 cells
// apart, so the plain between them is flat for 25 cells (4 kS from each line).

constexpr double kBase = 1000.0;
constexpr double kH = 300.0;
constexpr double kS = 6.0;
constexpr int kSpacing = 100;
constexpr int kExW = 300;
constexpr int kExH = 200;

double bump(double cells)
{
  return std::exp(-cells * cells / (2.0 * kS * kS));
}

// Sign per line at x = 50, 150, 250.
Heightfield parallelLines(const std::array<double, 3>& signs)
{
  return terrain(kExW,
    kExH,
    [&](int i, int)
    {
      double z = kBase;
      for (std::size_t l = 0; l < signs.size(); ++l)
      {
        z += signs[l] * kH * bump(i - (kSpacing / 2.0 + kSpacing * static_cast<double>(l)));
      }
      return z;
    });
}

// The analytic section of a ridge at d metres: -kH (1 - exp(-d^2 / 2 s^2)).
double analyticRidge(double metres)
{
  return -kH * (1.0 - bump(metres / kCell));
}

LandformMeasureOptions measureOptions()
{
  LandformMeasureOptions o;
  o.patchSize = kPatch;
  return o;
}

// The measured section against the analytic one. The cells of distance bin b
// lie b cells from these axis-aligned lines but the bin stands at b + 1/2:
// the measured value may lie anywhere between f(d) and f(d - cell / 2).
void expectSection(const MonotoneProfile& section, double sign, const std::string& what)
{
  constexpr double kTolerance = 0.02 * kH;
  ASSERT_FALSE(section.empty()) << what;
  for (double cells = 1.0; cells <= 40.0; cells += 1.0)
  {
    const double d = cells * kCell;
    const double a = sign * analyticRidge(d);
    const double b = sign * analyticRidge(d - 0.5 * kCell);
    EXPECT_GE(section(d), std::min(a, b) - kTolerance) << what << " at " << d << " m";
    EXPECT_LE(section(d), std::max(a, b) + kTolerance) << what << " at " << d << " m";
  }
}

// Distance at which the Gaussian makes 90% of its relief: s sqrt(2 ln 10).
const double kAnalyticWidth = kS * std::sqrt(2.0 * std::log(10.0)) * kCell;

} // namespace

TEST(MeasureLandforms, GaussianRidgesGiveTheirReliefSectionAndWidth)
{
  const Heightfield ex = parallelLines({ 1.0, 1.0, 1.0 });
  const FeatureGraph g = ridgesAndValleys(ex);
  ASSERT_GT(g.chains.size(), 0u);
  const LandformStatistics s = measureLandforms({ &ex }, { &g }, measureOptions());
  std::printf("ridges: level %.1f m, relief %.1f m, width %.0f m (analytic %.0f m), "
              "%.0f m of line; base %.1f m\n",
    s.ridge.level,
    s.ridge.relief,
    s.ridge.width,
    kAnalyticWidth,
    s.ridge.lineLength,
    s.base);
  EXPECT_NEAR(s.ridge.level, kBase + kH, 0.5);
  EXPECT_NEAR(s.ridge.relief, kH, 0.02 * kH);
  expectSection(s.ridge.section, 1.0, "ridge");
  // Half a cell of binning either way.
  EXPECT_NEAR(s.ridge.width, kAnalyticWidth, kCell);
  // Three ridges nearly the height of the map.
  EXPECT_GT(s.ridge.lineLength, 3 * 0.8 * kExH * kCell);
  EXPECT_LT(s.ridge.lineLength, 3 * 1.0 * kExH * kCell);
  // No valleys: mirrored, and said so.
  EXPECT_TRUE(hasWarning(s.warnings, "no major valleys")) << s.warnings.size();
  EXPECT_NEAR(s.base, kBase, 0.02 * kH);
  EXPECT_NEAR(s.valley.relief, s.ridge.relief, 1e-9);
  EXPECT_NEAR(s.valley.level, s.base - s.ridge.relief, 1e-9);
  EXPECT_EQ(s.valley.lineLength, 0.0);
  for (double d : { 100.0, 300.0, 600.0 })
  {
    EXPECT_NEAR(s.valley.section(d), -s.ridge.section(d), 1e-9) << d;
  }
  EXPECT_EQ(s.floorGradient, 0.01) << "no valleys: the fallback descent";
}

TEST(MeasureLandforms, GaussianValleysMirrorToRidges)
{
  const Heightfield ex = parallelLines({ -1.0, -1.0, -1.0 });
  const FeatureGraph g = ridgesAndValleys(ex);
  const LandformStatistics s = measureLandforms({ &ex }, { &g }, measureOptions());
  EXPECT_NEAR(s.valley.level, kBase - kH, 0.5);
  EXPECT_NEAR(s.valley.relief, kH, 0.02 * kH);
  expectSection(s.valley.section, -1.0, "valley");
  EXPECT_NEAR(s.valley.width, kAnalyticWidth, kCell);
  EXPECT_TRUE(hasWarning(s.warnings, "no major ridges"));
  EXPECT_NEAR(s.base, kBase, 0.02 * kH);
  EXPECT_NEAR(s.ridge.level, s.base + s.valley.relief, 1e-9);
  // Flat floors descend by nothing.
  EXPECT_NEAR(s.floorGradient, 0.0, 1e-6);
}

TEST(MeasureLandforms, RidgesAndValleysShareOneBase)
{
  // Ridges at x = 50 and 250, a valley between them: both kinds measured, their
  // reliefs reconciled on the plain they share.
  const Heightfield ex = parallelLines({ 1.0, -1.0, 1.0 });
  const FeatureGraph g = ridgesAndValleys(ex);
  const LandformStatistics s = measureLandforms({ &ex }, { &g }, measureOptions());
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
  EXPECT_NEAR(s.ridge.level, kBase + kH, 0.5);
  EXPECT_NEAR(s.valley.level, kBase - kH, 0.5);
  EXPECT_NEAR(s.base, kBase, 0.02 * kH);
  EXPECT_NEAR(s.ridge.relief, s.ridge.level - s.base, 1e-9);
  EXPECT_NEAR(s.valley.relief, s.base - s.valley.level, 1e-9);
  expectSection(s.ridge.section, 1.0, "ridge");
  expectSection(s.valley.section, -1.0, "valley");
  EXPECT_GT(s.valley.lineLength, 0.8 * kExH * kCell);
}

TEST(MeasureLandforms, FloorGradientOfDescendingValleys)
{
  // The valleys' floors descend northwards at 2%: the lowest quarter of the
  // valley cells (the major ones) all lie on that slope.
  constexpr double kGradient = 0.02;
  const Heightfield flat = parallelLines({ -1.0, -1.0, -1.0 });
  Heightfield ex = flat;
  for (int j = 0; j < ex.height; ++j)
  {
    for (int i = 0; i < ex.width; ++i)
    {
      ex.at(i, j) = static_cast<float>(flat.at(i, j) + kGradient * kCell * (ex.height - 1 - j));
    }
  }
  const FeatureGraph g = ridgesAndValleys(ex);
  const LandformStatistics s = measureLandforms({ &ex }, { &g }, measureOptions());
  EXPECT_NEAR(s.floorGradient, kGradient, 0.1 * kGradient);
}

TEST(MeasureLandforms, AFeaturelessExemplarFallsBackWithAWarning)
{
  // A tilted plane: no PPA lines; sketched features get half the 5-95% height
  // range over half a patch.
  const Heightfield ex = terrain(200, 150, [](int i, int) { return 1000.0 + 0.5 * i; });
  const FeatureGraph g = ridgesAndValleys(ex);
  ASSERT_TRUE(g.chains.empty());
  const LandformStatistics s = measureLandforms({ &ex }, { &g }, measureOptions());
  EXPECT_TRUE(hasWarning(s.warnings, "no ridges or valleys"));
  const double range = 0.5 * 199.0;
  EXPECT_NEAR(s.base, 1000.0 + 0.5 * range, 1.0);
  EXPECT_NEAR(s.ridge.relief, 0.5 * 0.9 * range, 1.0);
  EXPECT_NEAR(s.ridge.level, s.base + s.ridge.relief, 1e-9);
  EXPECT_NEAR(s.valley.level, s.base - s.valley.relief, 1e-9);
  EXPECT_DOUBLE_EQ(s.ridge.width, 0.5 * kPatch * kCell);
  EXPECT_DOUBLE_EQ(s.ridge.section(s.ridge.width), -s.ridge.relief);
  EXPECT_DOUBLE_EQ(s.valley.section(s.valley.width), s.valley.relief);
  EXPECT_EQ(s.floorGradient, 0.01);
  // A flat exemplar: relief kept above zero.
  const Heightfield level(120, 120, 500.0f);
  const FeatureGraph none;
  const LandformStatistics f = measureLandforms({ &level }, { &none }, measureOptions());
  EXPECT_TRUE(hasWarning(f.warnings, "no ridges or valleys"));
  EXPECT_GT(f.ridge.relief, 0.0);
  EXPECT_EQ(f.base, 500.0);
  EXPECT_THROW(measureLandforms({}, {}, measureOptions()), Error);
}

TEST(MeasureLandforms, ColoradoHasMountainSizedLandforms)
{
  const Heightfield dem = readHeightfield((test::bundledData() / "dems" / "colorado.png").string());
  const FeatureGraph g = ridgesAndValleys(dem);
  LandformMeasureOptions o;
  o.patchSize = 64;
  const LandformStatistics s = measureLandforms({ &dem }, { &g }, o);
  std::printf("Colorado: ridge level %.0f m relief %.0f m width %.0f m; valley level %.0f m "
              "relief %.0f m width %.0f m; base %.0f m; floor gradient %.4f\n",
    s.ridge.level,
    s.ridge.relief,
    s.ridge.width,
    s.valley.level,
    s.valley.relief,
    s.valley.width,
    s.base,
    s.floorGradient);
  EXPECT_TRUE(s.warnings.empty());
  for (const LandformProfile* p : { &s.ridge, &s.valley })
  {
    EXPECT_GT(p->relief, 200.0);
    EXPECT_LT(p->relief, 1500.0);
    EXPECT_GT(p->width, 1000.0);
    EXPECT_LT(p->width, 15000.0);
    EXPECT_GT(p->lineLength, 50000.0);
  }
  EXPECT_GT(s.ridge.level, s.base);
  EXPECT_LT(s.valley.level, s.base);
  EXPECT_GT(s.floorGradient, 0.001);
  EXPECT_LT(s.floorGradient, 0.2);
}

// ---------------------------------------------------------------------------
// The target field of a sketch

namespace
{

constexpr int kW = 120;
constexpr int kH2 = 160;
constexpr double kRelief = 400.0;

// Ridges 400 m above a base of 1000 m and valleys 400 m below it, with one
// cross-section shape mirrored, and floors descending 2% (limited by the depth).
LandformStatistics handStatistics()
{
  LandformStatistics s;
  s.base = kBase;
  const std::vector<double> d = { 0, 150, 300, 600, 900 };
  const std::vector<double> fall = { 0, -60, -200, -380, -400 };
  std::vector<double> rise(fall.size());
  std::transform(fall.begin(), fall.end(), rise.begin(), [](double v) { return -v; });
  s.ridge.section = MonotoneProfile::fromPoints(d, fall);
  s.ridge.level = kBase + kRelief;
  s.ridge.relief = kRelief;
  s.ridge.width = s.ridge.section.reach(0.9);
  s.valley.section = MonotoneProfile::fromPoints(d, rise);
  s.valley.level = kBase - kRelief;
  s.valley.relief = kRelief;
  s.valley.width = s.valley.section.reach(0.9);
  s.floorGradient = 0.02;
  return s;
}

LandformFieldOptions fieldOptions(std::uint64_t seed = 0)
{
  LandformFieldOptions o;
  o.patchSize = kPatch;
  o.seed = seed;
  return o;
}

FeatureGraph sketch(const std::vector<Polyline>& lines)
{
  return polylineFeatures(lines, kW, kH2, kCell, kCell);
}

LandformField fieldOf(const std::vector<Polyline>& lines, std::uint64_t seed = 0)
{
  return landformField(sketch(lines), kW, kH2, kCell, kCell, handStatistics(), fieldOptions(seed));
}

Polyline valley(std::vector<Point2> points)
{
  return { std::move(points), {}, FeatureType::Valley };
}

Polyline ridge(std::vector<Point2> points)
{
  return { std::move(points), {}, FeatureType::Ridge };
}

std::size_t cell(int i, int j)
{
  return static_cast<std::size_t>(j) * kW + static_cast<std::size_t>(i);
}

// The cells a straight segment covers, in order from a to b (as the target
// builder rasterises: half-cell steps, rounded).
std::vector<std::size_t> cellsAlong(const Point2& a, const Point2& b)
{
  std::vector<std::size_t> out;
  const int steps =
    std::max(1, static_cast<int>(std::ceil(2.0 * std::hypot(b.x - a.x, b.y - a.y))));
  for (int s = 0; s <= steps; ++s)
  {
    const double t = static_cast<double>(s) / steps;
    const std::size_t c = cell(static_cast<int>(std::lround(a.x + t * (b.x - a.x))),
      static_cast<int>(std::lround(a.y + t * (b.y - a.y))));
    if (out.empty() || out.back() != c)
    {
      out.push_back(c);
    }
  }
  return out;
}

// The floor of a valley of the hand statistics whose outlet is `longest`
// metres of flow from its farthest head, at `downstream` metres from the outlet.
double expectedFloor(double downstream, double longest)
{
  const double rise = std::min(0.02 * longest, 1.0 * kRelief);
  const double t = downstream / longest;
  return kBase - kRelief + rise * (0.3 * t + 0.7 * t * t);
}

bool sameBits(const std::vector<float>& a, const std::vector<float>& b)
{
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

} // namespace

TEST(LandformField, AValleyDrainsToItsBorderEnd)
{
  // A straight valley from (60, 150) to the bottom border.
  const LandformField f = fieldOf({ valley({ { 60, 150 }, { 60, 0 } }) });
  EXPECT_TRUE(f.warnings.empty());
  const MonotoneProfile shape = handStatistics().valley.section.normalised();
  const double longest = 150 * kCell;
  for (int j = 0; j <= 150; ++j)
  {
    const std::size_t c = cell(60, j);
    // The outlet is the border end; the flow distance grows along the line.
    // (A cell keeps the lowest value the line passes over it with, in steps of
    // half a cell or less: up to half a cell nearer the outlet than its centre.)
    const double downstream = f.downstream[c];
    ASSERT_GE(downstream, std::max(0.0, j - 0.5) * kCell - 1e-2) << j;
    ASSERT_LE(downstream, j * kCell + 1e-2) << j;
    // Floors rise from the outlet, concave (steeper towards the head).
    const double floor = f.field.z[c];
    EXPECT_NEAR(floor, expectedFloor(downstream, longest), 0.05) << j;
    if (j > 0)
    {
      EXPECT_GT(downstream, f.downstream[cell(60, j - 1)]) << j;
      EXPECT_GT(floor, f.field.z[cell(60, j - 1)]) << j;
    }
    EXPECT_EQ(f.weight[c], 1.0f) << j;
    // Beside the valley the land rises with the section from the floor to the
    // rim, which is the depth above the floor at the outlet and 60% of it at
    // the head. Floor and rim reach the land k cells away smoothed over the
    // line cells about k / 2 cells along (three sigmas: 1.5 k), so each lies
    // between the least and the most of theirs there.
    auto rimAt = [&](double flow)
    { return expectedFloor(flow, longest) + kRelief * (1.0 - 0.4 * flow / longest); };
    for (int k = 1; k <= 30; ++k)
    {
      const double first = std::max(0.0, j - 0.5 - 1.5 * k) * kCell;
      const double last = std::min(150.0, j + 0.5 + 1.5 * k) * kCell;
      const double none = std::numeric_limits<double>::infinity();
      double floorLow = none;
      double floorHigh = -none;
      double rimLow = none;
      double rimHigh = -none;
      for (double flow = first; flow <= last + 1e-9; flow += 0.25 * kCell)
      {
        floorLow = std::min(floorLow, expectedFloor(flow, longest));
        floorHigh = std::max(floorHigh, expectedFloor(flow, longest));
        rimLow = std::min(rimLow, rimAt(flow));
        rimHigh = std::max(rimHigh, rimAt(flow));
      }
      const double s = shape(k * kCell);
      const double low = floorLow * (1.0 - s) + rimLow * s - 0.05;
      const double high = floorHigh * (1.0 - s) + rimHigh * s + 0.05;
      for (int i : { 60 - k, 60 + k })
      {
        EXPECT_GE(f.field.at(i, j), low) << k << ", " << j;
        EXPECT_LE(f.field.at(i, j), high) << k << ", " << j;
      }
      EXPECT_GT(f.field.at(60 + k, j), f.field.at(60 + k - 1, j)) << k << ", " << j;
    }
  }
  // Off the line there is no flow distance.
  EXPECT_TRUE(std::isnan(f.downstream[cell(61, 80)]));
  EXPECT_TRUE(std::isnan(f.downstream[cell(60, 151)]));
  // Confidence: full out to where the section makes 75% of its relief (466.7 m
  // = 15.6 cells), none past that plus half a patch (946.7 m = 31.6 cells).
  for (int k = 0; k <= 15; ++k)
  {
    EXPECT_EQ(f.weight[cell(60 + k, 80)], 1.0f) << k;
  }
  for (int k = 16; k <= 31; ++k)
  {
    EXPECT_LT(f.weight[cell(60 + k, 80)], 1.0f) << k;
    EXPECT_GT(f.weight[cell(60 + k, 80)], 0.0f) << k;
    EXPECT_LT(f.weight[cell(60 + k, 80)], f.weight[cell(60 + k - 1, 80)]) << k;
  }
  for (int i = 0; i <= 60 - 32; ++i)
  {
    EXPECT_EQ(f.weight[cell(i, 80)], 0.0f) << i;
  }
}

TEST(LandformField, ARidgeCrestFallsWithTheSection)
{
  // Across the whole map (both ends on the border: no taper).
  const LandformField f = fieldOf({ ridge({ { 0, 80 }, { 119, 80 } }) });
  const MonotoneProfile shape = handStatistics().ridge.section.normalised();
  for (int i = 0; i < kW; ++i)
  {
    ASSERT_NEAR(f.field.at(i, 80), kBase + kRelief, 1e-3) << i;
    for (int k = 1; k < 80; ++k)
    {
      const double expected = kBase + kRelief - kRelief * shape(k * kCell);
      ASSERT_NEAR(f.field.at(i, 80 + k), expected, 0.05) << i << ", " << k;
      ASSERT_NEAR(f.field.at(i, 80 - k), expected, 0.05) << i << ", " << k;
      ASSERT_LE(f.field.at(i, 80 + k), f.field.at(i, 80 + k - 1)) << i << ", " << k;
    }
  }
  EXPECT_TRUE(
    std::all_of(f.downstream.begin(), f.downstream.end(), [](float d) { return std::isnan(d); }));
}

TEST(LandformField, ASlantedRidgeFallsWithTheDistanceToItsLineNotToItsCells)
{
  // Across the whole map at a slope of 0.4: its cells make a staircase. Off
  // the line, the field follows the section at each cell's distance to the
  // drawn line itself, so cells equally far from it are equally high. Taken
  // to the nearest line cell, the distance was up to half a cell off, and the
  // flank departed from the section by up to 15.6 m (of a 400 m relief) in a
  // ripple that followed the staircase: stripes across the flank in a
  // hillshade.
  const double slope = 0.4;
  const LandformField f = fieldOf({ ridge({ { 0, 56 }, { 119, 56 + slope * 119 } }) });
  const MonotoneProfile shape = handStatistics().ridge.section.normalised();
  double worst = 0.0;
  for (int j = 0; j < kH2; ++j)
  {
    for (int i = 10; i < kW - 10; ++i)
    {
      const double d = std::abs(j - 56 - slope * i) / std::hypot(1.0, slope);
      if (d < 1.0 || d > 20.0)
      {
        continue; // the line's own cells hold its crest; far out the section is flat
      }
      const double expected = kBase + kRelief - kRelief * shape(d * kCell);
      worst = std::max(worst, std::abs(f.field.at(i, j) - expected));
    }
  }
  std::printf("worst departure from the section at the distance to the line: %.3f m\n", worst);
  EXPECT_LT(worst, 0.3);
}

TEST(LandformField, FreeRidgeEndsTaperBorderEndsDoNot)
{
  const LandformFieldOptions o = fieldOptions();
  const double full = kBase + kRelief;
  const double end = kBase + o.endRelief * kRelief;
  // Both ends free (20 and 19 cells from the border, a patch is 32): the crest
  // keeps 40% of the relief at the ends and rises to all of it half a patch
  // (16 cells) in, along a smoothstep. (A cell holds the lowest crest the line
  // passes over it with: up to half a cell nearer the end than its centre, where
  // the crest is interpolated between points a cell apart.)
  auto taper = [&](double cells)
  {
    const double t = std::clamp(cells / (0.5 * kPatch), 0.0, 1.0);
    return kBase + kRelief * (o.endRelief + (1.0 - o.endRelief) * t * t * (3.0 - 2.0 * t));
  };
  const LandformField free = fieldOf({ ridge({ { 20, 80 }, { 100, 80 } }) });
  EXPECT_NEAR(free.field.at(20, 80), end, 1e-3);
  EXPECT_NEAR(free.field.at(100, 80), end, 1e-3);
  EXPECT_NEAR(free.field.at(60, 80), full, 1e-3);
  EXPECT_NEAR(free.field.at(40, 80), full, 1e-3);
  for (int i = 21; i <= 40; ++i)
  {
    const double fromEnd = i - 20;
    EXPECT_GE(free.field.at(i, 80), 0.5 * (taper(fromEnd - 1) + taper(fromEnd)) - 1e-3) << i;
    EXPECT_LE(free.field.at(i, 80), taper(fromEnd) + 1e-3) << i;
    EXPECT_GE(free.field.at(i, 80), free.field.at(i - 1, 80)) << i;
  }
  // Halfway along the taper: half of the missing 60%.
  EXPECT_NEAR(free.field.at(28, 80),
    kBase + kRelief * (o.endRelief + 0.5 * (1 - o.endRelief)),
    0.03 * kRelief);
  // One end on the west border: the ridge leaves the map there at full height.
  const LandformField edge = fieldOf({ ridge({ { 0, 80 }, { 60, 80 } }) });
  EXPECT_NEAR(edge.field.at(0, 80), full, 1e-3);
  EXPECT_NEAR(edge.field.at(30, 80), full, 1e-3);
  EXPECT_NEAR(edge.field.at(60, 80), end, 1e-3);
}

TEST(LandformField, AValleyTreeDrainsThroughItsTrunk)
{
  // Y: the trunk from the bottom border up to (60, 60), two branches on to heads
  // 9 cells below the top border.
  const Point2 mouth{ 60, 0 };
  const Point2 fork{ 60, 60 };
  const Point2 west{ 25, 150 };
  const Point2 east{ 95, 150 };
  const LandformField f =
    fieldOf({ valley({ mouth, fork }), valley({ fork, west }), valley({ fork, east }) });
  EXPECT_TRUE(f.warnings.empty());
  EXPECT_EQ(f.downstream[cell(60, 0)], 0.0f);
  const double branch = std::hypot(35.0, 90.0) * kCell;
  const double longest = 60 * kCell + branch;
  // Within the half cell of rasterisation (along a diagonal, half a step).
  const double half = 0.5 * std::hypot(35.0 / 90.0, 1.0) * kCell;
  EXPECT_NEAR(f.downstream[cell(60, 60)], 60 * kCell, half);
  EXPECT_NEAR(f.downstream[cell(25, 150)], longest, half);
  EXPECT_NEAR(f.downstream[cell(95, 150)], longest, half);
  const std::vector<std::size_t> westBranch = cellsAlong(fork, west);
  for (std::size_t c :
    { cell(60, 0), cell(60, 30), westBranch[westBranch.size() / 2], cell(25, 150) })
  {
    EXPECT_NEAR(f.field.z[c], expectedFloor(f.downstream[c], longest), 0.05) << c;
  }
  // From each head down its branch and the trunk to the mouth, every floor
  // cell lies lower than the one before.
  for (const Point2& head : { west, east })
  {
    std::vector<std::size_t> path = cellsAlong(head, fork);
    const std::vector<std::size_t> trunk = cellsAlong(fork, mouth);
    path.insert(path.end(), trunk.begin() + 1, trunk.end());
    for (std::size_t k = 1; k < path.size(); ++k)
    {
      ASSERT_LT(f.downstream[path[k]], f.downstream[path[k - 1]]) << k;
      ASSERT_LT(f.field.z[path[k]], f.field.z[path[k - 1]]) << k;
    }
  }
}

TEST(LandformField, ARingValleyWarnsOfItsLoopAndDrainsBothWays)
{
  // A 36-gon of radius 40 around (60, 80): nearest the border at its east point
  // (19 cells from it), where the outlet is (within the 2% of that distance
  // that make a tie, a few cells along the ring).
  std::vector<Point2> ring;
  constexpr int kSides = 36;
  constexpr double kRadius = 40.0;
  const double pi = std::acos(-1.0);
  for (int k = 0; k <= kSides; ++k)
  {
    const double a = 2.0 * pi * (k % kSides) / kSides;
    ring.push_back({ 60 + kRadius * std::cos(a), 80 + kRadius * std::sin(a) });
  }
  const LandformField f = fieldOf({ valley(ring) });
  ASSERT_EQ(f.warnings.size(), 1u);
  EXPECT_NE(f.warnings[0].find("loop"), std::string::npos);
  constexpr double kNearOutlet = 6 * kCell;
  EXPECT_LE(f.downstream[cell(100, 80)], kNearOutlet);
  // Every cell of the ring has a flow distance; the farthest is half the
  // perimeter away, opposite the outlet.
  const double half = kSides * kRadius * std::sin(pi / kSides) * kCell;
  float farthest = 0.0f;
  for (int k = 1; k <= kSides; ++k)
  {
    for (std::size_t c :
      cellsAlong(ring[static_cast<std::size_t>(k - 1)], ring[static_cast<std::size_t>(k)]))
    {
      ASSERT_TRUE(std::isfinite(f.downstream[c])) << c;
      farthest = std::max(farthest, f.downstream[c]);
    }
  }
  EXPECT_NEAR(farthest, half, 0.01 * half);
  EXPECT_NEAR(f.downstream[cell(20, 80)], half, kNearOutlet);
  // Floors rise both ways from the outlet to the divide opposite.
  EXPECT_LT(f.field.at(100, 80), f.field.at(60, 120));
  EXPECT_LT(f.field.at(100, 80), f.field.at(60, 40));
  EXPECT_LT(f.field.at(60, 120), f.field.at(20, 80));
  EXPECT_LT(f.field.at(60, 40), f.field.at(20, 80));
}

TEST(LandformField, TheSeedBreaksATieBetweenOutletsAndNothingElse)
{
  // A valley right across the map: both ends on the border, flow paths of the
  // same length. The seed picks the outlet; the same seed, the same field.
  const std::vector<Polyline> across = { valley({ { 0, 80 }, { 119, 80 } }) };
  std::set<int> outlets;
  for (std::uint64_t seed = 0; seed < 16; ++seed)
  {
    const LandformField f = fieldOf(across, seed);
    const bool west = f.downstream[cell(0, 80)] == 0.0f;
    const bool east = f.downstream[cell(119, 80)] == 0.0f;
    ASSERT_NE(west, east) << "one outlet, at one of the ends";
    outlets.insert(west ? 0 : 1);
    const LandformField again = fieldOf(across, seed);
    EXPECT_TRUE(sameBits(f.field.z, again.field.z)) << seed;
    EXPECT_TRUE(sameBits(f.weight, again.weight)) << seed;
    EXPECT_TRUE(sameBits(f.downstream, again.downstream)) << seed;
    // Floors mirror each other: lowest at the outlet.
    const double low = f.field.at(west ? 0 : 119, 80);
    const double high = f.field.at(west ? 119 : 0, 80);
    EXPECT_NEAR(low, kBase - kRelief, 1e-3);
    EXPECT_GT(high, low + 1.0);
  }
  EXPECT_EQ(outlets.size(), 2u) << "16 seeds never chose one of the two outlets";
  // Where the ends do not tie, the seed changes nothing.
  const std::vector<Polyline> oneEnd = { valley({ { 60, 150 }, { 60, 0 } }) };
  EXPECT_TRUE(sameBits(fieldOf(oneEnd, 1).field.z, fieldOf(oneEnd, 2).field.z));
}

TEST(LandformField, GivenHeightsWin)
{
  // Poly-line Elevation on a ridge: the crest is what was asked, ends and all.
  const FeatureGraph g = sketch({ ridge({ { 20, 80 }, { 100, 80 } }) });
  LineHeights heights(g.chains.size());
  for (std::size_t c = 0; c < g.chains.size(); ++c)
  {
    heights[c].assign(g.chains[c].points.size(), 1700.0f);
  }
  const LandformField f =
    landformField(g, kW, kH2, kCell, kCell, handStatistics(), fieldOptions(), nullptr, &heights);
  EXPECT_NEAR(f.field.at(20, 80), 1700.0, 1e-3);
  EXPECT_NEAR(f.field.at(60, 80), 1700.0, 1e-3);
  // A base raises the land the ridge stands on, not the crest it was given.
  Heightfield base(kW, kH2, 1200.0f);
  const LandformField b =
    landformField(g, kW, kH2, kCell, kCell, handStatistics(), fieldOptions(), &base, &heights);
  EXPECT_NEAR(b.field.at(60, 80), 1700.0, 1e-3);
  EXPECT_NEAR(b.field.at(60, 0), 1200.0, 1.0);
}

TEST(LandformField, ValleysCloserThanTheirWidthMakeADivideBetweenThem)
{
  // The hand sections make 90% of their relief by 19 cells; two valleys 20
  // cells apart leave each 10. Squeezed into that room, the land midway is
  // nearly the rim: a divide, not the broad low of two wide sections.
  const FeatureGraph g =
    sketch({ valley({ { 0, 70 }, { 119, 70 } }), valley({ { 0, 90 }, { 119, 90 } }) });
  const LandformField f = landformField(g, kW, kH2, kCell, kCell, handStatistics(), fieldOptions());
  const MonotoneProfile shape = handStatistics().valley.section.normalised();
  for (int i : { 30, 60, 90 })
  {
    const double floor = std::max(f.field.at(i, 70), f.field.at(i, 90));
    const double divide = f.field.at(i, 80);
    // The unsqueezed section would reach shape(10 cells) = 0.5 of the depth there.
    EXPECT_LT(shape(10 * kCell), 0.55);
    EXPECT_GT(divide - floor, 0.85 * kRelief * 0.6) << i; // the rim is 60-100% of the depth
    EXPECT_GT(divide, f.field.at(i, 75)) << i;
    EXPECT_GT(divide, f.field.at(i, 85)) << i;
    EXPECT_NEAR(f.halfWidth[cell(i, 80)], 10.0, 1.0) << i;
  }
  // Beyond the pair the sections have their own width.
  EXPECT_NEAR(f.halfWidth[cell(60, 130)], handStatistics().valley.width / kCell, 0.5);
}

TEST(LandformField, TheDivideBetweenTwoValleysIsShapedAsARidgeAndTakesNoRoomFromThem)
{
  // Two valleys 40 cells apart (rows 50 and 90), wide enough apart that the
  // land between them is a gentle meeting of two flanks; their implied divide
  // at row 70, shaped as a ridge, stands well above it.
  const FeatureGraph drawn =
    sketch({ valley({ { 0, 50 }, { 119, 50 } }), valley({ { 0, 90 }, { 119, 90 } }) });
  const StrokeSpacing spacing = strokeSpacing(rasteriseChains(drawn, kW, kH2), kW, kH2);
  ImpliedLineOptions io;
  io.maxDistance = kPatch;
  const FeatureGraph implied = impliedLines(drawn, spacing, io);
  ASSERT_FALSE(implied.chains.empty());
  FeatureGraph both = drawn;
  appendGraph(both, implied);
  LandformFieldOptions o = fieldOptions();
  o.impliedChainsFrom = drawn.chains.size();
  const LandformField bare =
    landformField(drawn, kW, kH2, kCell, kCell, handStatistics(), fieldOptions());
  const LandformField shaped = landformField(both, kW, kH2, kCell, kCell, handStatistics(), o);
  for (int i : { 30, 60, 90 })
  {
    // A ridge's crest (base + relief), where the bare flanks met below the base.
    EXPECT_NEAR(shaped.field.at(i, 70), kBase + kRelief, 0.05 * kRelief) << i;
    EXPECT_GT(shaped.field.at(i, 70) - bare.field.at(i, 70), 0.9 * kRelief) << i;
    EXPECT_GT(shaped.field.at(i, 70), shaped.field.at(i, 62)) << i; // a crest, not a step
    EXPECT_GT(shaped.field.at(i, 70), shaped.field.at(i, 78)) << i;
    // The valleys keep their floors and the room the drawing gives them.
    EXPECT_NEAR(shaped.field.at(i, 50), bare.field.at(i, 50), 1.0) << i;
    EXPECT_EQ(shaped.halfWidth[cell(i, 50)], bare.halfWidth[cell(i, 50)]) << i;
    EXPECT_EQ(shaped.halfWidth[cell(i, 70)], bare.halfWidth[cell(i, 70)]) << i;
  }
  EXPECT_EQ(shaped.valleyRaise, bare.valleyRaise);
  EXPECT_TRUE(shaped.warnings.empty());
}

TEST(LandformField, TheTroughBetweenTwoRidgesIsAValleyWithoutAnOutlet)
{
  // Two ridges 40 cells apart (rows 50 and 90) whose ends face a drawn valley
  // (column 105); their implied trough runs at row 70 towards the valley.
  const FeatureGraph drawn = sketch({ ridge({ { 0, 50 }, { 80, 50 } }),
    ridge({ { 0, 90 }, { 80, 90 } }),
    valley({ { 105, 0 }, { 105, 159 } }) });
  const StrokeSpacing spacing = strokeSpacing(rasteriseChains(drawn, kW, kH2), kW, kH2);
  ImpliedLineOptions io;
  io.maxDistance = kPatch;
  const FeatureGraph implied = impliedLines(drawn, spacing, io);
  ASSERT_FALSE(implied.chains.empty());
  for (const FeatureChain& c : implied.chains)
  {
    EXPECT_EQ(c.type, FeatureType::Valley);
  }
  FeatureGraph both = drawn;
  appendGraph(both, implied);
  LandformFieldOptions o = fieldOptions();
  o.impliedChainsFrom = drawn.chains.size();
  const LandformField bare =
    landformField(drawn, kW, kH2, kCell, kCell, handStatistics(), fieldOptions());
  const LandformField shaped = landformField(both, kW, kH2, kCell, kCell, handStatistics(), o);
  for (int i : { 20, 40, 60 })
  {
    // A valley's floor (base - relief) where the bare land rose to the base.
    EXPECT_NEAR(shaped.field.at(i, 70), kBase - kRelief, 0.05 * kRelief) << i;
    EXPECT_GT(bare.field.at(i, 70) - shaped.field.at(i, 70), 0.9 * kRelief) << i;
    EXPECT_LT(shaped.field.at(i, 70), shaped.field.at(i, 62)) << i;
    EXPECT_LT(shaped.field.at(i, 70), shaped.field.at(i, 78)) << i;
    // The ridges keep their crests and the room the drawing gives them; the
    // trough carries no flow (nothing drains it: it has no outlet).
    // (Within half a percent of the relief: a trough drawn into a crest would
    // take tens of percent off it.)
    EXPECT_NEAR(shaped.field.at(i, 50), bare.field.at(i, 50), 0.005 * kRelief) << i;
    EXPECT_EQ(shaped.halfWidth[cell(i, 50)], bare.halfWidth[cell(i, 50)]) << i;
    EXPECT_TRUE(std::isnan(shaped.downstream[cell(i, 70)])) << i;
  }
  // The drawn valley keeps its floor and its flow.
  EXPECT_NEAR(shaped.field.at(105, 70), bare.field.at(105, 70), 1.0);
  EXPECT_FALSE(std::isnan(shaped.downstream[cell(105, 70)]));
  EXPECT_EQ(shaped.valleyRaise, bare.valleyRaise);
  EXPECT_TRUE(shaped.warnings.empty());
}

TEST(LandformField, LandformsAreRaisedToStandOutOfRuggedLandOnlyAndKeepWithinIt)
{
  const FeatureGraph g = sketch({ ridge({ { 0, 80 }, { 119, 80 } }) });
  LandformStatistics smooth = handStatistics();
  const Heightfield gentle =
    terrain(200, 200, [](int i, int j) { return 2.0 * std::sin(i / 9.0) * std::cos(j / 7.0); });
  smooth.land = LandRelief({ &gentle });
  smooth.lowest = kBase - 5000.0;
  smooth.highest = kBase + 5000.0;
  EXPECT_EQ(landformField(g, kW, kH2, kCell, kCell, smooth, fieldOptions()).ridgeRaise, 1.0);
  // Land whose own relief rivals the sketched ridge's: raised, crest and all ...
  LandformStatistics rugged = smooth;
  const Heightfield rough =
    terrain(200, 200, [](int i, int j) { return 400.0 * std::sin(i / 9.0) * std::cos(j / 7.0); });
  rugged.land = LandRelief({ &rough });
  const LandformField raised = landformField(g, kW, kH2, kCell, kCell, rugged, fieldOptions());
  EXPECT_GT(raised.ridgeRaise, 1.5);
  EXPECT_NEAR(raised.field.at(60, 80), kBase + kRelief * raised.ridgeRaise, 1e-2);
  // ... but never past the exemplars' highest land, widened by the share of
  // their span a crest may pass it by.
  rugged.highest = kBase + 1.2 * kRelief;
  rugged.lowest = kBase - 0.8 * kRelief;
  LandformFieldOptions held = fieldOptions();
  held.crestPastHighestShare = 0.0;
  const LandformField capped = landformField(g, kW, kH2, kCell, kCell, rugged, held);
  EXPECT_NEAR(capped.ridgeRaise, 1.2, 1e-9);
  EXPECT_NEAR(capped.field.at(60, 80), kBase + 1.2 * kRelief, 1e-2);
  const LandformFieldOptions defaults = fieldOptions();
  const LandformField past = landformField(g, kW, kH2, kCell, kCell, rugged, defaults);
  // span 2 reliefs: the crest may reach 1.2 + 0.2 x 2 = 1.6 reliefs up.
  EXPECT_NEAR(past.ridgeRaise, 1.2 + defaults.crestPastHighestShare * 2.0, 1e-9);
  EXPECT_NEAR(past.field.at(60, 80), kBase + past.ridgeRaise * kRelief, 1e-2);
  // However much it is asked to stand out, a ridge's flank is never steeper
  // than ridgeFlankAllowance times the steep end of the land's slopes at its
  // width (one section in a hundred).
  LandformFieldOptions bold = fieldOptions();
  bold.standOut = 50.0;
  rugged.highest = kBase + 50.0 * kRelief;
  const double width = handStatistics().ridge.width;
  const double steepest = rugged.land.steepSlope(width / kCell) / kCell * width;
  const LandformField steep = landformField(g, kW, kH2, kCell, kCell, rugged, bold);
  EXPECT_NEAR(steep.ridgeRaise, std::max(1.0, bold.ridgeFlankAllowance * steepest / kRelief), 1e-9);
  EXPECT_LT(steep.ridgeRaise, 50.0);
  bold.ridgeFlankAllowance = 1.0;
  const LandformField steepAtOne = landformField(g, kW, kH2, kCell, kCell, rugged, bold);
  EXPECT_NEAR(steepAtOne.ridgeRaise, std::max(1.0, steepest / kRelief), 1e-9);
  EXPECT_GT(steep.ridgeRaise, 1.4 * steepAtOne.ridgeRaise);
  // A valley's flank keeps to the steep end itself, whatever ridges may do,
  // and its floor to the lowest land.
  const FeatureGraph gv = sketch({ valley({ { 0, 80 }, { 119, 80 } }) });
  bold.ridgeFlankAllowance = 3.0;
  rugged.lowest = kBase - 50.0 * kRelief;
  const double valleyWidth = handStatistics().valley.width;
  const double steepestValley = rugged.land.steepSlope(valleyWidth / kCell) / kCell * valleyWidth;
  ASSERT_GT(steepestValley / kRelief, 1.2); // the cap binds, so an allowance would show
  EXPECT_NEAR(landformField(gv, kW, kH2, kCell, kCell, rugged, bold).valleyRaise,
    std::max(1.0, steepestValley / kRelief),
    1e-9);
  rugged.lowest = kBase - 1.1 * kRelief;
  EXPECT_NEAR(landformField(gv, kW, kH2, kCell, kCell, rugged, bold).valleyRaise, 1.1, 1e-9);
  // standOut 0 turns the rule off.
  LandformFieldOptions off = fieldOptions();
  off.standOut = 0.0;
  EXPECT_EQ(landformField(g, kW, kH2, kCell, kCell, rugged, off).ridgeRaise, 1.0);
}

TEST(LandformField, TwoValleyNetworksMeetWithoutAStep)
{
  // Two valleys draining to the south border, 40 cells apart, of different
  // lengths: their floors and rims rise at different rates, so where the land
  // turns from one's flank to the other's the two disagree by tens of metres.
  // Taken from the nearest line cell alone, the field stepped there. (The
  // shorter is long enough, 120 cells, that the room its length leaves it,
  // kStrokeLengthPerHalfWidth, is the 20 cells the drawing leaves: shorter,
  // its flank is squeezed steeper than the hand section's steepest.)
  const LandformField f =
    fieldOf({ valley({ { 40, 150 }, { 40, 0 } }), valley({ { 80, 120 }, { 80, 0 } }) });
  // The steepest the land gets anywhere on a flank of one valley alone (the
  // hand section rises 140 m in 150 m at its steepest: 28 m a cell).
  const double flankStep = 140.0 / 150.0 * kCell;
  double largest = 0.0;
  int at = -1;
  for (int j = 0; j < 70; ++j)
  {
    for (int i = 41; i < 79; ++i)
    {
      const double step = std::abs(f.field.at(i + 1, j) - f.field.at(i, j));
      if (step > largest)
      {
        largest = step;
        at = i;
      }
    }
  }
  std::printf("largest step between the valleys: %.1f m (column %d)\n", largest, at);
  EXPECT_LT(largest, 1.05 * flankStep);
}
