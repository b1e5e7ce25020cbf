// Tests of Kernels/Metrics/LandformMetrics.cxx.
// Landform measures on analytic terrains with known answers.
#include "Core/Error.h"
#include "Core/HeightfieldIO.h"
#include "Features/Sketch.h"
#include "Metrics/LandformMetrics.h"
#include "TestData.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>

using namespace tsynth;

namespace
{

constexpr double kCell = 30.0; // metres

Heightfield terrain(int w, int h, const std::function<double(int, int)>& f)
{
  Heightfield hf(w, h);
  hf.cellX = hf.cellY = kCell;
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      hf.at(i, j) = static_cast<float>(f(i, j));
    }
  }
  return hf;
}

FeatureGraph sketchOf(const std::vector<Polyline>& lines, const Heightfield& hf)
{
  return polylineFeatures(lines, hf.width, hf.height, hf.cellX, hf.cellY);
}

double segmentDistance(const Point2& p, const Point2& a, const Point2& b)
{
  const double dx = b.x - a.x;
  const double dy = b.y - a.y;
  const double t =
    std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / (dx * dx + dy * dy), 0.0, 1.0);
  return std::hypot(p.x - (a.x + t * dx), p.y - (a.y + t * dy));
}

double polylineDistance(const Point2& p, const std::vector<Point2>& line)
{
  double d = std::numeric_limits<double>::infinity();
  for (std::size_t k = 1; k < line.size(); ++k)
  {
    d = std::min(d, segmentDistance(p, line[k - 1], line[k]));
  }
  return d;
}

// A Gaussian ridge (sign +1) or valley (-1) of height H and width s along a
// bent polyline, on a plane tilted in both directions (which the mean of the
// two sides must cancel).
constexpr double kH = 400.0;
constexpr double kS = 8.0;
const std::vector<Point2> kBent = { { 30, 40 }, { 100, 90 }, { 170, 110 } };

Heightfield gaussianFeature(double sign)
{
  return terrain(200,
    200,
    [sign](int i, int j)
    {
      const double d = polylineDistance({ double(i), double(j) }, kBent);
      return 1000.0 + 0.5 * i + 0.3 * j + sign * kH * std::exp(-d * d / (2 * kS * kS));
    });
}

LandformOptions optionsAt(double patch, double distance = 0.0)
{
  LandformOptions o;
  o.patchSize = patch;
  o.distance = distance;
  return o;
}

// A V valley: flanks rising 5 m per cell from column 60, the floor 1 m per cell
// (towards row 0 if `southward`, else towards the north edge); 121 x 200 cells.
constexpr int kVWidth = 121;
constexpr int kVLength = 200;
constexpr int kVAxis = 60;

double vValley(int i, int j, bool southward)
{
  return 500.0 + 5.0 * std::abs(i - kVAxis) + 1.0 * (southward ? j : kVLength - 1 - j);
}

const std::vector<Polyline> kAxisValley = {
  { { { 60, 190 }, { 60, 10 } }, {}, FeatureType::Valley }
};

// A quarter turn counter-clockwise: cell (i, j) goes to (height - 1 - j, i).
Heightfield quarterTurn(const Heightfield& a)
{
  Heightfield t(a.height, a.width);
  t.cellX = a.cellY;
  t.cellY = a.cellX;
  for (int j = 0; j < a.height; ++j)
  {
    for (int i = 0; i < a.width; ++i)
    {
      t.at(a.height - 1 - j, i) = a.at(i, j);
    }
  }
  return t;
}

FeatureGraph quarterTurn(FeatureGraph g)
{
  const int h = g.height;
  std::swap(g.width, g.height);
  std::swap(g.cellX, g.cellY);
  auto turn = [h](Point2& p) { p = { h - 1 - p.y, p.x }; };
  for (FeatureNode& n : g.nodes)
  {
    turn(n.position);
  }
  for (FeatureChain& c : g.chains)
  {
    std::for_each(c.points.begin(), c.points.end(), turn);
  }
  return g;
}

} // namespace

TEST(LandformMetrics, GaussianRidgeProminenceIsHTimesOneMinusTheGaussianAtD)
{
  const Heightfield ridge = gaussianFeature(+1);
  const Heightfield valley = gaussianFeature(-1);
  const FeatureGraph ridgeLine = sketchOf({ { kBent, {}, FeatureType::Ridge } }, ridge);
  const FeatureGraph valleyLine = sketchOf({ { kBent, {}, FeatureType::Valley } }, valley);
  // Bilinear sampling of the crest loses at most H / (8 s^2) = 0.8 m.
  constexpr double kTolerance = 1.2;
  for (const double d : { 10.0, 20.0 })
  {
    const double expected = kH * (1.0 - std::exp(-d * d / (2 * kS * kS))); // 216.9, 382.4 m
    const LandformMeasures r = evaluateLandforms(ridge, ridgeLine, {}, {}, optionsAt(80, d));
    EXPECT_NEAR(r.ridgeProminence, expected, kTolerance) << "D " << d;
    EXPECT_EQ(r.ridgeSamples, 159u); // every cell of the 158.8-cell line, all sides inside
    EXPECT_NEAR(
      typicalProminence(ridge, ridgeLine, FeatureType::Ridge, d), r.ridgeProminence, 1e-9);
    const LandformMeasures v = evaluateLandforms(valley, valleyLine, {}, {}, optionsAt(80, d));
    EXPECT_NEAR(v.valleyDepth, expected, kTolerance) << "D " << d;
  }
  // The default D is the patch size.
  EXPECT_NEAR(evaluateLandforms(ridge, ridgeLine, {}, {}, optionsAt(20)).ridgeProminence,
    kH * (1.0 - std::exp(-400.0 / (2 * kS * kS))),
    kTolerance);
}

TEST(LandformMetrics, RatiosCompareWithTheExemplarsOwnLines)
{
  const Heightfield ridge = gaussianFeature(+1);
  const FeatureGraph line = sketchOf({ { kBent, {}, FeatureType::Ridge } }, ridge);
  // The exemplar: the same ridge at half the height.
  Heightfield half = ridge;
  const Heightfield base =
    terrain(200, 200, [](int i, int j) { return 1000.0 + 0.5 * i + 0.3 * j; });
  for (std::size_t k = 0; k < half.size(); ++k)
  {
    half.z[k] = base.z[k] + 0.5f * (ridge.z[k] - base.z[k]);
  }
  const LandformMeasures m = evaluateLandforms(ridge, line, { &half }, { &line }, optionsAt(20));
  EXPECT_NEAR(m.ridgeProminenceRatio, 2.0, 0.01);
  EXPECT_NEAR(m.referenceRidgeProminence, 0.5 * m.ridgeProminence, 0.5);

  // A transposed copy with transposed lines is the same landform: ratio exactly 1.
  Heightfield transposed = ridge;
  std::vector<Point2> flipped;
  for (int j = 0; j < ridge.height; ++j)
  {
    for (int i = 0; i < ridge.width; ++i)
    {
      transposed.at(j, i) = ridge.at(i, j);
    }
  }
  for (const Point2& p : kBent)
  {
    flipped.push_back({ p.y, p.x });
  }
  const FeatureGraph flippedLine = sketchOf({ { flipped, {}, FeatureType::Ridge } }, transposed);
  const LandformMeasures t =
    evaluateLandforms(transposed, flippedLine, { &ridge }, { &line }, optionsAt(20));
  EXPECT_NEAR(t.ridgeProminenceRatio, 1.0, 1e-6); // float rounding of the bilinear sums

  // Pooled exemplars: the median of all samples, so two equal exemplars change nothing.
  EXPECT_DOUBLE_EQ(typicalProminence({ &half, &half }, { &line, &line }, FeatureType::Ridge, 20),
    typicalProminence(half, line, FeatureType::Ridge, 20));
}

TEST(LandformMetrics, FlatReferenceGivesNaNRatiosWithAReason)
{
  const Heightfield ridge = gaussianFeature(+1);
  const FeatureGraph line = sketchOf({ { kBent, {}, FeatureType::Ridge },
                                       { { { 20, 160 }, { 180, 150 } }, {}, FeatureType::Valley } },
    ridge);
  const Heightfield flat = terrain(200, 200, [](int, int) { return 700.0; });
  const LandformMeasures m = evaluateLandforms(ridge, line, { &flat }, { &line }, optionsAt(20));
  EXPECT_TRUE(std::isfinite(m.ridgeProminence));
  EXPECT_EQ(m.referenceRidgeProminence, 0.0);
  EXPECT_TRUE(std::isnan(m.ridgeProminenceRatio));
  EXPECT_TRUE(std::isnan(m.valleyDepthRatio));
  EXPECT_EQ(m.notes.count("ridgeProminenceRatio"), 1u);
  EXPECT_TRUE(std::isfinite(m.valleyDepth)); // about 0 on the plane, but measured
  EXPECT_NE(m.notes.at("valleyDepthRatio").find("no relief"), std::string::npos);
  // No exemplar at all: NaN too, with its own reason.
  const LandformMeasures none = evaluateLandforms(ridge, line, {}, {}, optionsAt(20));
  EXPECT_TRUE(std::isnan(none.ridgeProminenceRatio));
  EXPECT_EQ(none.notes.at("ridgeProminenceRatio"), "no exemplar given");
}

TEST(LandformMetrics, TiltedVValleyDrainsAndDescends)
{
  for (const bool southward : { true, false })
  {
    SCOPED_TRACE(southward ? "draining south" : "draining north");
    const Heightfield v =
      terrain(kVWidth, kVLength, [&](int i, int j) { return vValley(i, j, southward); });
    const FeatureGraph sketch = sketchOf(kAxisValley, v);
    const LandformMeasures m = evaluateLandforms(v, sketch, {}, {}, optionsAt(40));
    EXPECT_EQ(m.drainageSamples, 181u);
    EXPECT_EQ(m.valleyDrainage, 1.0);
    EXPECT_EQ(m.descentPairs, 18u); // 180 cells in steps of 10
    EXPECT_EQ(m.valleyDescent, 1.0);
    EXPECT_NEAR(m.valleyDepth, 5.0 * 40.0, 1e-3); // flanks 5 m per cell at D = 40 cells
    EXPECT_TRUE(std::isnan(m.ridgeProminence));
    // Drawn the other way round: the same figures (the outlet comes from the terrain).
    const std::vector<Polyline> reversed = {
      { { { 60, 10 }, { 60, 190 } }, {}, FeatureType::Valley }
    };
    const LandformMeasures r = evaluateLandforms(v, sketchOf(reversed, v), {}, {}, optionsAt(40));
    EXPECT_EQ(r.valleyDrainage, m.valleyDrainage);
    EXPECT_EQ(r.valleyDescent, m.valleyDescent);
  }
}

TEST(LandformMetrics, ValleyTiltedTheWrongWayBehindADamDoesNotDrain)
{
  // The floor falls north, but a dam near the north end (rows 164-186, 250 m
  // above the floor at row 175) is higher than the south end: the valley becomes
  // a lake that spills south over the border, its flow spread in parallel lines
  // over the flat surface.
  const Heightfield v = terrain(kVWidth,
    kVLength,
    [](int i, int j)
    { return vValley(i, j, false) + 250.0 * std::max(0.0, 1.0 - std::abs(j - 175) / 12.0); });
  const LandformMeasures m = evaluateLandforms(v, sketchOf(kAxisValley, v), {}, {}, optionsAt(40));
  EXPECT_LT(m.valleyDrainage, 0.3);
  // Of the 18 floor pairs only row 160 -> 170 climbs (537 m -> 635 m, the lowest
  // within 2 cells); 170 -> 180 is already on the way down the dam.
  EXPECT_EQ(m.descentPairs, 18u);
  EXPECT_DOUBLE_EQ(m.valleyDescent, 17.0 / 18.0);
}

TEST(LandformMetrics, ValleyTreeDrainsToItsLowestEnd)
{
  // Three V valleys meeting at (100, 100), the floor falling 1 m per cell
  // towards (100, 0) on the south edge: the terrain is the lowest of the three.
  const std::vector<std::vector<Point2>> arms = {
    { { 40, 180 }, { 100, 100 } }, { { 160, 180 }, { 100, 100 } }, { { 100, 100 }, { 100, 0 } }
  };
  const double armLength = std::hypot(60.0, 80.0); // 100 cells
  auto floorAlong = [&](std::size_t a, const Point2& p, double& d)
  {
    const Point2& s = arms[a][0];
    const Point2& e = arms[a][1];
    const double len = std::hypot(e.x - s.x, e.y - s.y);
    const double t =
      std::clamp(((p.x - s.x) * (e.x - s.x) + (p.y - s.y) * (e.y - s.y)) / (len * len), 0.0, 1.0);
    d = std::hypot(p.x - (s.x + t * (e.x - s.x)), p.y - (s.y + t * (e.y - s.y)));
    const double fromTop = a < 2 ? t * len : armLength + t * len;
    return 600.0 - fromTop;
  };
  const Heightfield v = terrain(200,
    200,
    [&](int i, int j)
    {
      double z = std::numeric_limits<double>::infinity();
      for (std::size_t a = 0; a < arms.size(); ++a)
      {
        double d = 0.0;
        const double f = floorAlong(a, { double(i), double(j) }, d);
        z = std::min(z, f + 5.0 * d);
      }
      return z;
    });
  std::vector<Polyline> lines;
  for (const auto& a : arms)
  {
    lines.push_back({ a, {}, FeatureType::Valley });
  }
  const LandformMeasures m = evaluateLandforms(v, sketchOf(lines, v), {}, {}, optionsAt(40));
  EXPECT_EQ(m.valleyDescent, 1.0);
  EXPECT_GE(m.valleyDrainage, 0.97);
  // Pairs every 10 cells: 11 on each arm (the last walks on into the trunk
  // through the junction) and 10 on the 100-cell trunk.
  EXPECT_EQ(m.descentPairs, 11u + 11u + 10u);
}

TEST(LandformMetrics, DrainageBarGrowsWithTheLongestPathFromAHead)
{
  // A bar of 140 cells per cell of path (3.5 x 40) against a channel that
  // collects 121 cells per row: the sample at row j (path 190 - j from the head)
  // sees the channel cell 2 rows downstream (the tolerance), and passes iff
  // 121 (202 - j) >= 140 (190 - j), i.e. j >= 114: 77 of 181.
  const Heightfield v =
    terrain(kVWidth, kVLength, [](int i, int j) { return vValley(i, j, true); });
  LandformOptions o = optionsAt(40);
  o.drainageStripFraction = 3.5;
  const LandformMeasures single = evaluateLandforms(v, sketchOf(kAxisValley, v), {}, {}, o);
  EXPECT_DOUBLE_EQ(single.valleyDrainage, 77.0 / 181.0);
  // The same line cut at row 100 by a 3-cell side branch: below the branch the
  // path still counts from the top head (90 + 100 - j), so rows 10-100 fail as
  // before; the branch's 4 samples pass (the channel is within 2 cells).
  const std::vector<Polyline> cut = { { { { 60, 190 }, { 60, 100 } }, {}, FeatureType::Valley },
    { { { 60, 100 }, { 60, 10 } }, {}, FeatureType::Valley },
    { { { 63, 100 }, { 60, 100 } }, {}, FeatureType::Valley } };
  const LandformMeasures m = evaluateLandforms(v, sketchOf(cut, v), {}, {}, o);
  EXPECT_EQ(m.drainageSamples, 91u + 91u + 4u);
  EXPECT_DOUBLE_EQ(m.valleyDrainage, (77.0 + 4.0) / 186.0);
}

TEST(LandformMetrics, RidgeOverValleyIsTheProbabilityOfBeingHigher)
{
  // A ridge along row 150 and a valley along row 50 of a surface rising north.
  const Heightfield north = terrain(200, 200, [](int, int j) { return 100.0 + 2.0 * j; });
  const std::vector<Polyline> lines = { { { { 20, 150 }, { 180, 150 } }, {}, FeatureType::Ridge },
    { { { 20, 50 }, { 180, 50 } }, {}, FeatureType::Valley } };
  EXPECT_EQ(
    evaluateLandforms(north, sketchOf(lines, north), {}, {}, optionsAt(40)).ridgeOverValley, 1.0);
  const Heightfield flat = terrain(200, 200, [](int, int) { return 300.0; });
  EXPECT_EQ(
    evaluateLandforms(flat, sketchOf(lines, flat), {}, {}, optionsAt(40)).ridgeOverValley, 0.5);
  const Heightfield south = terrain(200, 200, [](int, int j) { return 800.0 - 2.0 * j; });
  EXPECT_EQ(
    evaluateLandforms(south, sketchOf(lines, south), {}, {}, optionsAt(40)).ridgeOverValley, 0.0);
  // Half the ridge above, half below the valley: a half.
  const Heightfield mixed =
    terrain(200, 200, [](int i, int j) { return j > 100 ? (i < 100 ? 900.0 : 100.0) : 500.0; });
  EXPECT_NEAR(
    evaluateLandforms(mixed, sketchOf(lines, mixed), {}, {}, optionsAt(40)).ridgeOverValley,
    0.5,
    0.01);
}

TEST(LandformMetrics, RidgesShedWaterAndValleysDoNot)
{
  const Heightfield ridge = gaussianFeature(+1);
  const LandformMeasures r = evaluateLandforms(
    ridge, sketchOf({ { kBent, {}, FeatureType::Ridge } }, ridge), {}, {}, optionsAt(40));
  EXPECT_EQ(r.ridgeShedding, 1.0);
  EXPECT_EQ(r.sheddingSamples,
    static_cast<std::size_t>(std::floor(std::hypot(70, 50) + std::hypot(70, 20))) + 1u);
  // A "ridge" drawn along the channel of a V valley collects the valley's water.
  const Heightfield v =
    terrain(kVWidth, kVLength, [](int i, int j) { return vValley(i, j, true); });
  const std::vector<Polyline> onChannel = {
    { { { 60, 190 }, { 60, 10 } }, {}, FeatureType::Ridge }
  };
  const LandformMeasures c = evaluateLandforms(v, sketchOf(onChannel, v), {}, {}, optionsAt(40));
  // Even the top sample has 10 rows x 121 cells upstream, over 80 (two patch widths).
  EXPECT_EQ(c.ridgeShedding, 0.0);
  EXPECT_NEAR(c.ridgeProminence, -200.0, 1e-3); // and it lies below its surroundings
}

TEST(LandformMetrics, FieldsWithoutLinesAreNaNWithAReason)
{
  const Heightfield v =
    terrain(kVWidth, kVLength, [](int i, int j) { return vValley(i, j, true); });
  const LandformMeasures m = evaluateLandforms(v, sketchOf(kAxisValley, v), {}, {}, optionsAt(40));
  for (const double x :
    { m.ridgeProminence, m.ridgeProminenceRatio, m.ridgeOverValley, m.ridgeShedding })
  {
    EXPECT_TRUE(std::isnan(x));
  }
  for (const char* f :
    { "ridgeProminence", "ridgeProminenceRatio", "ridgeOverValley", "ridgeShedding" })
  {
    EXPECT_EQ(m.notes.at(f), "the sketch has no ridge line") << f;
  }
  EXPECT_TRUE(std::isfinite(m.valleyDepth));
  EXPECT_EQ(m.notes.count("valleyDepth"), 0u);

  const FeatureGraph empty;
  const LandformMeasures e = evaluateLandforms(v, empty, {}, {}, optionsAt(40));
  EXPECT_TRUE(std::isnan(e.valleyDrainage));
  EXPECT_TRUE(std::isnan(e.valleyDescent));
  EXPECT_EQ(e.notes.at("valleyDrainage"), "the sketch has no valley line");

  // Lines too close to the edge for D on both sides: no prominence sample.
  const LandformMeasures edge =
    evaluateLandforms(v, sketchOf(kAxisValley, v), {}, {}, optionsAt(40, 70));
  EXPECT_TRUE(std::isnan(edge.valleyDepth));
  EXPECT_EQ(edge.valleySamples, 0u);
  EXPECT_EQ(edge.notes.count("valleyDepth"), 1u);
  EXPECT_EQ(edge.valleyDrainage, 1.0); // the rest does not need the sides
}

TEST(LandformMetrics, BadInputIsRefused)
{
  const Heightfield v =
    terrain(kVWidth, kVLength, [](int i, int j) { return vValley(i, j, true); });
  const FeatureGraph sketch = sketchOf(kAxisValley, v);
  const Heightfield other = terrain(50, 50, [](int, int) { return 0.0; });
  EXPECT_THROW(evaluateLandforms(other, sketch, {}, {}), Error);
  EXPECT_THROW(evaluateLandforms(v, sketch, { &v }, {}), Error);
  EXPECT_THROW(evaluateLandforms(v, sketch, { &other }, { &sketch }), Error);
  LandformOptions bad;
  bad.patchSize = 0.0;
  EXPECT_THROW(evaluateLandforms(v, sketch, {}, {}, bad), Error);
  bad = {};
  bad.tolerance = -1.0;
  EXPECT_THROW(evaluateLandforms(v, sketch, {}, {}, bad), Error);
}

TEST(LandformMetrics, RealDemsOwnLandformLinesDrainShedAndDescend)
{
  // Each bundled DEM against its own landform-scale lines (PPA after smoothing
  // at 2 cells) with the default options (patch 80): the thresholds must pass
  // real valleys and ridges. Measured: drainage 0.79-0.84, shedding >= 0.997,
  // descent 0.92-0.94, ridge over valley 0.74-0.79.
  PpaOptions landform;
  landform.presmoothSigma = 2.0;
  for (const char* name : { "alps-montblanc.png", "colorado.png", "mount_jackson_crop601.tif" })
  {
    SCOPED_TRACE(name);
    const Heightfield dem = readHeightfield(test::bundledData() / "dems" / name);
    const FeatureGraph lines = ownFeatureLines(dem, landform);
    const LandformMeasures m = evaluateLandforms(dem, lines, { &dem }, { &lines });
    std::printf("%-26s ridge %6.1f m, valley %6.1f m, ridge over valley %.3f, drainage %.3f, "
                "shedding %.3f, descent %.3f\n",
      name,
      m.ridgeProminence,
      m.valleyDepth,
      m.ridgeOverValley,
      m.valleyDrainage,
      m.ridgeShedding,
      m.valleyDescent);
    EXPECT_GT(m.ridgeProminence, 150.0);
    EXPECT_GT(m.valleyDepth, 100.0);
    EXPECT_DOUBLE_EQ(m.ridgeProminenceRatio, 1.0); // its own lines are the reference
    EXPECT_DOUBLE_EQ(m.valleyDepthRatio, 1.0);
    EXPECT_GE(m.valleyDrainage, 0.75);
    EXPECT_GE(m.ridgeShedding, 0.99);
    EXPECT_GE(m.valleyDescent, 0.9);
    EXPECT_GE(m.ridgeOverValley, 0.7);
    EXPECT_TRUE(m.notes.empty());

    // A quarter turn of the DEM and its lines is the same landscape: the
    // exemplar's own figure is met exactly, and drainage moves only by D8's
    // tie-breaking order.
    const Heightfield turned = quarterTurn(dem);
    const LandformMeasures t = evaluateLandforms(turned, quarterTurn(lines), { &dem }, { &lines });
    EXPECT_NEAR(t.ridgeProminenceRatio, 1.0, 1e-6);
    EXPECT_NEAR(t.valleyDepthRatio, 1.0, 1e-6);
    EXPECT_NEAR(t.valleyDrainage, m.valleyDrainage, 0.005);
    EXPECT_NEAR(t.ridgeShedding, m.ridgeShedding, 0.005);
    EXPECT_NEAR(t.valleyDescent, m.valleyDescent, 0.005);
  }
}
