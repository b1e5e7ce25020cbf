// Reading a sketch off a terrain at each stroke's own scale: how far apart
// strokes are (StrokeSpacing), cross-sections and the land's own relief
// (CrossSections), and the legibility measure and band-pass correlation built
// on them, on analytic surfaces with known answers.
#include "Core/Random.h"
#include "Core/Smoothing.h"
#include "Features/CrossSections.h"
#include "Features/ImpliedLines.h"
#include "Features/Sketch.h"
#include "Features/StrokeSpacing.h"
#include "Metrics/Legibility.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

using namespace tsynth;

namespace
{

constexpr double kPi = 3.14159265358979323846;

std::vector<std::uint8_t> cells(int w, int h, const std::function<bool(int, int)>& on)
{
  std::vector<std::uint8_t> c(static_cast<std::size_t>(w * h), 0);
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      c[static_cast<std::size_t>(j * w + i)] = on(i, j) ? 1 : 0;
    }
  }
  return c;
}

float at(const StrokeSpacing& s, int i, int j)
{
  return s.halfSpacing[static_cast<std::size_t>(j * s.width + i)];
}

// Straight strokes (x0, y0) -> (x1, y1) of the given types as a graph on w x h.
FeatureGraph drawnLines(int w,
  int h,
  const std::vector<std::array<double, 4>>& ends,
  const std::vector<FeatureType>& types)
{
  std::vector<Polyline> lines;
  for (std::size_t k = 0; k < ends.size(); ++k)
  {
    Polyline p;
    p.points = { { ends[k][0], ends[k][1] }, { ends[k][2], ends[k][3] } };
    p.type = types[k];
    lines.push_back(p);
  }
  return polylineFeatures(lines, w, h, 1.0, 1.0);
}

FeatureGraph implied(const FeatureGraph& drawn, const ImpliedLineOptions& o = {})
{
  const StrokeSpacing s =
    strokeSpacing(rasteriseChains(drawn, drawn.width, drawn.height), drawn.width, drawn.height);
  return impliedLines(drawn, s, o);
}

// Total length (cells) of a graph's chains of one type, and their mean row.
std::pair<double, double> lengthAndMeanRow(const FeatureGraph& g, FeatureType type)
{
  double length = 0.0, rows = 0.0, points = 0.0;
  for (const FeatureChain& c : g.chains)
  {
    if (c.type != type)
    {
      continue;
    }
    length += c.length();
    for (const Point2& p : c.points)
    {
      rows += p.y;
      points += 1.0;
    }
  }
  return { length, points > 0.0 ? rows / points : std::numeric_limits<double>::quiet_NaN() };
}

Heightfield surface(int w, int h, const std::function<double(int, int)>& f)
{
  Heightfield hf(w, h);
  hf.cellX = hf.cellY = 30.0;
  hf.cellSizeKnown = true;
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      hf.at(i, j) = static_cast<float>(f(i, j));
    }
  }
  return hf;
}

// Smooth random relief: a sum of seeded sines of wavelengths 8 to 64 cells,
// each `amplitude` metres.
Heightfield rough(int w, int h, double amplitude, std::uint64_t seed)
{
  return surface(w,
    h,
    [&](int i, int j)
    {
      double z = 0.0;
      for (int k = 0; k < 24; ++k)
      {
        const double wave = 8.0 * std::pow(2.0, 3.0 * seededUniform(seed, 1, k));
        const double a = 2.0 * kPi * seededUniform(seed, 2, k);
        const double p = 2.0 * kPi * seededUniform(seed, 3, k);
        z += amplitude * std::sin(2.0 * kPi * (i * std::cos(a) + j * std::sin(a)) / wave + p);
      }
      return z;
    });
}

// A graph of straight chains on a grid (points every cell).
FeatureGraph lines(int w,
  int h,
  const std::vector<std::pair<Point2, Point2>>& segments,
  FeatureType type)
{
  FeatureGraph g;
  g.width = w;
  g.height = h;
  for (const auto& [a, b] : segments)
  {
    FeatureChain c;
    c.type = type;
    const int n = static_cast<int>(std::ceil(std::hypot(b.x - a.x, b.y - a.y)));
    for (int k = 0; k <= n; ++k)
    {
      const double t = static_cast<double>(k) / n;
      c.points.push_back({ a.x + t * (b.x - a.x), a.y + t * (b.y - a.y) });
    }
    c.from = static_cast<int>(g.nodes.size());
    c.to = c.from + 1;
    g.nodes.push_back(FeatureNode{});
    g.nodes.push_back(FeatureNode{});
    g.chains.push_back(c);
  }
  return g;
}

} // namespace

TEST(StrokeSpacing, ParallelStrokesMeetHalfWayAndALoneStrokeHasRoomForever)
{
  // Two horizontal strokes 40 cells apart (rows 30 and 70), a lone one far off at row 150.
  const int w = 120, h = 180;
  const StrokeSpacing s =
    strokeSpacing(cells(w, h, [](int, int j) { return j == 30 || j == 70 || j == 150; }), w, h);
  for (int j : { 35, 50, 65 })
  {
    EXPECT_NEAR(at(s, 60, j), 20.0f, 1.0f) << "between the pair, row " << j;
  }
  EXPECT_NEAR(at(s, 60, 30), 20.0f, 1.0f); // the stroke itself: its inner side
  EXPECT_NEAR(strokeHalfSpacing(s, 60, 70), 20.0f, 1.0f);
  EXPECT_EQ(s.medial[static_cast<std::size_t>(50 * w + 60)], 1);
  // Below the pair and round the lone stroke nothing faces: the medial axis
  // between row 70 and row 150 does (40 cells each way) ...
  EXPECT_NEAR(at(s, 60, 110), 40.0f, 1.0f);
  // ... but nothing lies beyond the lone stroke or beyond the first.
  EXPECT_TRUE(std::isinf(at(s, 60, 165)));
  EXPECT_TRUE(std::isinf(at(s, 60, 10)));
}

TEST(StrokeSpacing, ARingFacesItselfAcrossItsCentreButACornerDoesNot)
{
  const int w = 121, h = 121;
  const StrokeSpacing ring = strokeSpacing(
    cells(w, h, [](int i, int j) { return std::abs(std::hypot(i - 60, j - 60) - 40.0) < 0.5; }),
    w,
    h);
  EXPECT_NEAR(at(ring, 60, 80), 40.0f, 2.0f); // inside: half the diameter
  EXPECT_TRUE(std::isinf(at(ring, 60, 115))); // outside: open
  // An L: a right-angle corner of one stroke is a bend, not two strokes.
  const StrokeSpacing corner = strokeSpacing(
    cells(w, h, [](int i, int j) { return (j == 20 && i >= 20) || (i == 20 && j >= 20); }), w, h);
  EXPECT_TRUE(std::isinf(at(corner, 50, 50)));
  EXPECT_TRUE(std::isinf(at(corner, 25, 25)));
}

TEST(ImpliedLines, TwoValleysArePartedByARidgeAndTwoRidgesByAValley)
{
  const int w = 160, h = 100;
  for (FeatureType drawnType : { FeatureType::Valley, FeatureType::Ridge })
  {
    // Two strokes 40 cells apart, 120 long: the line between them runs
    // halfway, at row 50, of the other type, their whole length and a little
    // beyond their ends (where the two ends still face each other: about 18
    // cells at kFacingRatio 1.5), not more.
    const FeatureGraph g =
      drawnLines(w, h, { { 20, 30, 140, 30 }, { 20, 70, 140, 70 } }, { drawnType, drawnType });
    const FeatureGraph i = implied(g);
    const FeatureType other =
      drawnType == FeatureType::Valley ? FeatureType::Ridge : FeatureType::Valley;
    const auto [length, row] = lengthAndMeanRow(i, other);
    EXPECT_GT(length, 120.0);
    EXPECT_LT(length, 160.0);
    EXPECT_NEAR(row, 50.0, 1.5);
    EXPECT_EQ(lengthAndMeanRow(i, drawnType).first, 0.0);
    EXPECT_FALSE(i.bfsOrder.empty());
  }
}

TEST(ImpliedLines, TwoRidgesGetATroughUnlessTurnedOff)
{
  const FeatureGraph g = drawnLines(160,
    100,
    { { 20, 30, 140, 30 }, { 20, 70, 140, 70 } },
    { FeatureType::Ridge, FeatureType::Ridge });
  EXPECT_GT(lengthAndMeanRow(implied(g), FeatureType::Valley).first, 120.0);
  ImpliedLineOptions divides;
  divides.troughs = false;
  EXPECT_TRUE(implied(g, divides).chains.empty());
}

TEST(ImpliedLines, NoneBetweenARidgeAndAValleyFarApartOrAtABend)
{
  const int w = 160, h = 240;
  // A valley facing a ridge: one slope joins them.
  EXPECT_TRUE(implied(drawnLines(w,
                        h,
                        { { 20, 30, 140, 30 }, { 20, 70, 140, 70 } },
                        { FeatureType::Valley, FeatureType::Ridge }))
                .chains.empty());
  // Two valleys 200 cells apart, farther than maxDistance (80) from the line
  // between them: free land.
  EXPECT_TRUE(implied(drawnLines(w,
                        h,
                        { { 20, 20, 140, 20 }, { 20, 220, 140, 220 } },
                        { FeatureType::Valley, FeatureType::Valley }))
                .chains.empty());
  // ... but with room enough they are parted.
  ImpliedLineOptions farther;
  farther.maxDistance = 120.0;
  EXPECT_FALSE(implied(drawnLines(w,
                         h,
                         { { 20, 20, 140, 20 }, { 20, 220, 140, 220 } },
                         { FeatureType::Valley, FeatureType::Valley }),
    farther)
                 .chains.empty());
  // A right-angle bend of one valley (an L) is one stroke, not two facing ones.
  EXPECT_TRUE(implied(drawnLines(w,
                        h,
                        { { 20, 20, 140, 20 }, { 20, 20, 20, 200 } },
                        { FeatureType::Valley, FeatureType::Valley }))
                .chains.empty());
}

TEST(StrokeSpacing, NoStrokesNoSpacing)
{
  const StrokeSpacing s = strokeSpacing(std::vector<std::uint8_t>(100, 0), 10, 10);
  for (float v : s.halfSpacing)
  {
    EXPECT_TRUE(std::isinf(v));
  }
}

TEST(CrossSections, AVShapedValleyStandsOutByHalfItsDepthAndAPlaneNotAtAll)
{
  // A V 300 m deep over 30 cells each side: smoothed at a third of the half
  // width its floor rises by about a quarter of the depth, its outer halves
  // average three quarters of the rim less what the smoothing at the section's
  // ends takes: a little over a third of the depth.
  std::vector<double> v(61), plane(61);
  for (int s = -30; s <= 30; ++s)
  {
    v[static_cast<std::size_t>(s + 30)] = 300.0 * std::abs(s) / 30.0;
    plane[static_cast<std::size_t>(s + 30)] = 5.0 * s;
  }
  const double valley = sectionProminence(v, -1.0);
  EXPECT_GT(valley, 0.3 * 300.0);
  EXPECT_LT(valley, 0.45 * 300.0);
  EXPECT_LT(sectionProminence(v, 1.0), 0.0); // no crest there
  EXPECT_NEAR(sectionRelief(plane), 0.0, 1e-9);
  // A tilted plane has one side higher than its middle: no ridge, no valley.
  EXPECT_LT(sectionProminence(plane, 1.0), 0.0);
  EXPECT_LT(sectionProminence(plane, -1.0), 0.0);
}

TEST(CrossSections, LandReliefGrowsWithRoughnessAndIsZeroOnAPlane)
{
  const Heightfield plane = surface(200, 200, [](int i, int j) { return 3.0 * i - 2.0 * j; });
  const Heightfield gentle = rough(200, 200, 10.0, 7);
  const Heightfield rugged = rough(200, 200, 40.0, 7);
  const LandRelief flat({ &plane });
  const LandRelief soft({ &gentle });
  const LandRelief hard({ &rugged });
  for (double h : { 4.0, 10.0, 30.0 })
  {
    EXPECT_NEAR(flat.at(h), 0.0, 1e-3) << h; // float rounding of the bilinear reads
    EXPECT_GT(soft.at(h), 0.0) << h;
    // Relief scales with the heights: four times the amplitude, four times the relief.
    EXPECT_NEAR(hard.at(h) / soft.at(h), 4.0, 1e-3) << h;
  }
  EXPECT_GT(soft.at(30.0), soft.at(4.0)); // wider sections see more of the relief
  // A plane's steepest sections run down its gradient: 3.6 m per cell.
  EXPECT_NEAR(flat.steepSlope(10.0), std::hypot(3.0, 2.0), 0.02);
  EXPECT_NEAR(hard.steepSlope(10.0) / soft.steepSlope(10.0), 4.0, 1e-3);
  EXPECT_EQ(LandRelief({ &gentle }).at(16.0), soft.at(16.0)); // a fixed seed
  EXPECT_EQ(LandRelief().at(16.0), 0.0);
}

TEST(Legibility, AGaussianRidgeOnTheStrokeIsLegibleAndTheLandBesideItIsNot)
{
  const int w = 200, h = 160;
  const Heightfield land = rough(w, h, 15.0, 3);
  const LandRelief relief({ &land });
  // A ridge 600 m high, 10 cells wide (sigma), along row 80.
  const Heightfield ridged = surface(w,
    h,
    [&](int i, int j)
    { return land.at(i, j) + 600.0 * std::exp(-0.5 * std::pow((j - 80) / 10.0, 2)); });
  const FeatureGraph onIt = lines(w, h, { { { 20, 80 }, { 180, 80 } } }, FeatureType::Ridge);
  const FeatureGraph beside = lines(w, h, { { { 20, 120 }, { 180, 120 } } }, FeatureType::Ridge);
  const FeatureGraph asValley = lines(w, h, { { { 20, 80 }, { 180, 80 } } }, FeatureType::Valley);
  const Legibility good = evaluateLegibility(ridged, onIt, relief);
  EXPECT_GT(good.ridge.share, 0.95);
  EXPECT_GT(good.ridge.prominence, 200.0);
  EXPECT_TRUE(std::isnan(good.valley.share));
  EXPECT_EQ(good.share, good.ridge.share);
  EXPECT_NEAR(good.ridge.halfWidth, 40.0, 0.5); // a lone stroke: loneHalfWidth
  EXPECT_LT(evaluateLegibility(ridged, beside, relief).ridge.share, 0.35);
  EXPECT_LT(evaluateLegibility(ridged, asValley, relief).valley.share, 0.05);
  // The bare land reads about as often as chance would have it.
  EXPECT_LT(evaluateLegibility(land, onIt, relief).ridge.share, 0.35);
  // One meter measures terrain after terrain as one evaluation each would.
  const LegibilityMeter meter(onIt, relief);
  EXPECT_EQ(meter.measure(land).ridge.share, evaluateLegibility(land, onIt, relief).ridge.share);
  EXPECT_EQ(meter.measure(ridged).ridge.share, good.ridge.share);
  EXPECT_EQ(meter.measure(ridged).ridge.prominence, good.ridge.prominence);
}

TEST(Legibility, FlanksAgreeWithTheLineUnlessSpursAndGulliesCrossIt)
{
  // The 600 m ridge along row 80: its flanks fall away from the line
  // everywhere (agreement near 1); read as a valley they rise towards it (near
  // -1); the bare land agrees no more than chance. (The land is calm: its
  // slopes, unlike its relief, rival the ridge's at 15 m a wave.)
  const int w = 200, h = 160;
  const Heightfield land = rough(w, h, 2.0, 3);
  const LandRelief relief({ &land });
  const auto ridgeWith = [&](double corrugation)
  {
    return surface(w,
      h,
      [&](int i, int j)
      {
        const double across = std::exp(-0.5 * std::pow((j - 80) / 10.0, 2));
        return land.at(i, j) + (600.0 + corrugation * std::sin(2.0 * kPi * i / 16.0)) * across;
      });
  };
  const FeatureGraph asRidge = lines(w, h, { { { 20, 80 }, { 180, 80 } } }, FeatureType::Ridge);
  const FeatureGraph asValley = lines(w, h, { { { 20, 80 }, { 180, 80 } } }, FeatureType::Valley);
  const Legibility clean = evaluateLegibility(ridgeWith(0.0), asRidge, relief);
  EXPECT_GT(clean.ridge.flankAgreement, 0.95);
  EXPECT_EQ(clean.flankAgreement, clean.ridge.flankAgreement);
  EXPECT_LT(evaluateLegibility(ridgeWith(0.0), asValley, relief).valley.flankAgreement, -0.95);
  // Along one line the land's waves may lean one way by chance (-0.21 to
  // -0.01 over these four; 0.77 and 1.00 with the ridge).
  double bareMean = 0.0;
  for (std::uint64_t seed : { 3, 4, 5, 6 })
  {
    const double bare =
      evaluateLegibility(rough(w, h, 2.0, seed), asRidge, relief).ridge.flankAgreement;
    EXPECT_LT(std::abs(bare), 0.3) << seed;
    bareMean += bare / 4.0;
  }
  EXPECT_LT(std::abs(bareMean), 0.15);
  // Spurs and gullies 16 cells apart across it, 300 m: every cross-section
  // still stands out (the line is legible at its own scale), but its flanks
  // slope along the line as much as away from it, as over Mont Blanc a drawn
  // ring's did where patches' spurs crossed it.
  const Legibility crossed = evaluateLegibility(ridgeWith(300.0), asRidge, relief);
  std::printf("flank agreement: clean %.2f, crossed by spurs %.2f (legible %.2f)\n",
    clean.ridge.flankAgreement,
    crossed.ridge.flankAgreement,
    crossed.ridge.share);
  EXPECT_GT(crossed.ridge.share, 0.9);
  EXPECT_LT(crossed.ridge.flankAgreement, 0.7);
}

TEST(Legibility, BothKindsFlankAgreementIsTheMeanOverEverySampleWithFlanksToRead)
{
  // A clean ridge on its stroke (agreement 1 all along), and a valley stroke
  // drawn along a bump for its western half (-1 there) that runs on over dead
  // flat land (no shading: no flanks to read). The total is the mean of the
  // samples that had flanks, about (160 - 80) / 240 = 0.33, not the kinds'
  // means weighed by all their samples (about 0).
  const int w = 200, h = 160;
  const auto bump = [](int j, int row) { return std::max(0.0, 1.0 - std::abs(j - row) / 20.0); };
  const Heightfield terrain = surface(w,
    h,
    [&](int i, int j) { return 600.0 * bump(j, 40) + (i < 100 ? 400.0 * bump(j, 120) : 0.0); });
  const Heightfield flat = surface(w, h, [](int, int) { return 0.0; });
  const LandRelief relief({ &flat });
  FeatureGraph sketch =
    lines(w, h, { { { 20, 40 }, { 180, 40 } }, { { 20, 120 }, { 180, 120 } } }, FeatureType::Ridge);
  sketch.chains[1].type = FeatureType::Valley;
  const Legibility l = evaluateLegibility(terrain, sketch, relief);
  EXPECT_GT(l.ridge.flankAgreement, 0.95);
  EXPECT_LT(l.valley.flankAgreement, -0.95);
  EXPECT_EQ(l.ridge.flankSamples, l.ridge.samples);
  EXPECT_NEAR(static_cast<double>(l.valley.flankSamples),
    0.5 * static_cast<double>(l.valley.samples),
    0.1 * static_cast<double>(l.valley.samples));
  EXPECT_NEAR(l.flankAgreement, 1.0 / 3.0, 0.08);
}

TEST(Legibility, AStrokeMustStandOutOfTheTerrainsOwnLandToo)
{
  // The same ridge, once over land like the exemplars' and once over land
  // twelve times as rough: measured against the exemplars' land alone, both
  // would read; among knobs taller than itself, the second does not.
  const int w = 200, h = 200;
  const Heightfield exemplarLand = rough(w, h, 15.0, 3);
  const LandRelief relief({ &exemplarLand });
  const auto ridgeOver = [&](const Heightfield& land)
  {
    return surface(w,
      h,
      [&](int i, int j)
      { return land.at(i, j) + 600.0 * std::exp(-0.5 * std::pow((j - 100) / 10.0, 2)); });
  };
  const Heightfield roughLand = rough(w, h, 180.0, 7);
  const FeatureGraph g = lines(w, h, { { { 20, 100 }, { 180, 100 } } }, FeatureType::Ridge);
  const Legibility calm = evaluateLegibility(ridgeOver(rough(w, h, 15.0, 7)), g, relief);
  const Legibility busy = evaluateLegibility(ridgeOver(roughLand), g, relief);
  EXPECT_GT(calm.ridge.share, 0.95);
  EXPECT_LT(busy.ridge.share, 0.5);
  // Its threshold is the rougher land's, about twelve times the exemplars'.
  EXPECT_GT(busy.ridge.threshold, 8.0 * calm.ridge.threshold);
  EXPECT_NEAR(busy.ridge.threshold,
    LandRelief({ &roughLand }).at(busy.ridge.halfWidth),
    0.2 * busy.ridge.threshold);
}

TEST(Legibility, KnobsInARowAreNotALine)
{
  // Knobs 600 m high and about 8 cells long every 30 cells along the stroke:
  // each stands out over its sides, but the eye sees knobs, not a ridge. The
  // same knobs 6 cells apart merge into one.
  const int w = 200, h = 160;
  const Heightfield land = rough(w, h, 15.0, 3);
  const LandRelief relief({ &land });
  const auto knobs = [&](double spacing)
  {
    return surface(w,
      h,
      [&](int i, int j)
      {
        const double along = std::remainder(i - 20.0, spacing);
        return land.at(i, j) +
          600.0 * std::exp(-0.5 * (std::pow((j - 80) / 10.0, 2) + std::pow(along / 3.0, 2)));
      });
  };
  const FeatureGraph g = lines(w, h, { { { 20, 80 }, { 180, 80 } } }, FeatureType::Ridge);
  EXPECT_LT(evaluateLegibility(knobs(30.0), g, relief).ridge.share, 0.05);
  EXPECT_GT(evaluateLegibility(knobs(6.0), g, relief).ridge.share, 0.9);
}

TEST(Legibility, NeighbouringStrokesAreReadAtHalfTheirSpacing)
{
  // Valleys every 40 cells, 300 m deep: each is read 20 cells each side.
  const int w = 200, h = 200;
  const Heightfield land = rough(w, h, 10.0, 5);
  const Heightfield valleys = surface(w,
    h,
    [&](int i, int j)
    { return land.at(i, j) + 150.0 * (1.0 - std::cos(2.0 * kPi * (j - 20) / 40.0)); });
  const FeatureGraph g = lines(w,
    h,
    { { { 10, 60 }, { 190, 60 } }, { { 10, 100 }, { 190, 100 } }, { { 10, 140 }, { 190, 140 } } },
    FeatureType::Valley);
  const Legibility l = evaluateLegibility(valleys, g, LandRelief({ &land }));
  EXPECT_NEAR(l.valley.halfWidth, 20.0, 0.5);
  EXPECT_GT(l.valley.share, 0.95);
  // Drawn on the divides instead, they are not valleys at all.
  const FeatureGraph divides = lines(
    w, h, { { { 10, 80 }, { 190, 80 } }, { { 10, 120 }, { 190, 120 } } }, FeatureType::Valley);
  EXPECT_LT(evaluateLegibility(valleys, divides, LandRelief({ &land })).valley.share, 0.05);
}

TEST(Legibility, RefusesAGraphOfAnotherGrid)
{
  const Heightfield land = rough(64, 64, 10.0, 1);
  FeatureGraph g = lines(64, 64, { { { 5, 30 }, { 60, 30 } } }, FeatureType::Ridge);
  g.width = 65;
  EXPECT_THROW(evaluateLegibility(land, g, LandRelief({ &land })), std::exception);
}

TEST(BandPassCorrelation, OneForTheSameRelief_MinusOneForItsNegativeAndNearZeroForOther)
{
  const Heightfield a = rough(160, 160, 20.0, 11);
  const Heightfield b = rough(160, 160, 20.0, 12);
  Heightfield negative = a;
  Heightfield shifted = a;
  for (std::size_t k = 0; k < a.size(); ++k)
  {
    negative.z[k] = 1000.0f - a.z[k];
    shifted.z[k] = a.z[k] * 3.0f + 500.0f;
  }
  for (const BandCorrelation& c : bandPassCorrelation(a, shifted, defaultCorrelationScales()))
  {
    EXPECT_NEAR(c.correlation, 1.0, 1e-4) << c.sigma;
  }
  for (const BandCorrelation& c : bandPassCorrelation(a, negative, { 2.0, 8.0 }))
  {
    EXPECT_NEAR(c.correlation, -1.0, 1e-4) << c.sigma;
  }
  for (const BandCorrelation& c : bandPassCorrelation(a, b, { 2.0, 4.0 }))
  {
    EXPECT_LT(std::abs(c.correlation), 0.2) << c.sigma;
  }
  EXPECT_THROW(bandPassCorrelation(a, rough(150, 160, 1.0, 1), { 2.0 }), std::exception);
}

// BandPassTarget smooths each field once per distinct sigma and the target
// once for several terrains; its numbers are those of the band-passes taken
// one by one, G(sigma) - G(2 sigma) of each field, correlated by Pearson.
TEST(BandPassCorrelation, SharedGaussiansGiveTheBandsTakenOneByOne)
{
  Heightfield terrain = rough(120, 100, 20.0, 21);
  const Heightfield target = rough(120, 100, 20.0, 22);
  terrain.valid.assign(terrain.size(), 1);
  terrain.valid[5 * 120 + 7] = 0; // an invalid cell stays out of every band
  terrain.z[5 * 120 + 7] = std::numeric_limits<float>::quiet_NaN();
  auto band = [](const Heightfield& hf, double sigma)
  {
    const Heightfield fine = smoothLarge(hf, sigma);
    const Heightfield coarse = smoothLarge(hf, 2.0 * sigma);
    std::vector<double> out(hf.size(), std::numeric_limits<double>::quiet_NaN());
    for (std::size_t k = 0; k < hf.size(); ++k)
    {
      if (hf.isValid(k) && fine.isValid(k) && coarse.isValid(k))
      {
        out[k] = fine.z[k] - coarse.z[k];
      }
    }
    return out;
  };
  const BandPassTarget shared(target, defaultCorrelationScales());
  const std::vector<BandCorrelation> got = shared.correlate(terrain);
  ASSERT_EQ(got.size(), defaultCorrelationScales().size());
  for (const BandCorrelation& c : got)
  {
    const std::vector<double> a = band(terrain, c.sigma);
    const std::vector<double> b = band(target, c.sigma);
    double sa = 0.0, sb = 0.0, n = 0.0;
    for (std::size_t k = 0; k < a.size(); ++k)
    {
      if (std::isfinite(a[k]) && std::isfinite(b[k]))
      {
        sa += a[k];
        sb += b[k];
        n += 1.0;
      }
    }
    double ab = 0.0, aa = 0.0, bb = 0.0;
    for (std::size_t k = 0; k < a.size(); ++k)
    {
      if (std::isfinite(a[k]) && std::isfinite(b[k]))
      {
        ab += (a[k] - sa / n) * (b[k] - sb / n);
        aa += (a[k] - sa / n) * (a[k] - sa / n);
        bb += (b[k] - sb / n) * (b[k] - sb / n);
      }
    }
    EXPECT_NEAR(c.correlation, ab / std::sqrt(aa * bb), 1e-9) << c.sigma;
  }
  // A second terrain against the same target gives its own numbers.
  const std::vector<BandCorrelation> self = shared.correlate(target);
  EXPECT_NEAR(self.front().correlation, 1.0, 1e-12);
  EXPECT_THROW(shared.correlate(rough(100, 120, 1.0, 1)), std::exception);
}
