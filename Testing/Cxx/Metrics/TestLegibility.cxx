// Tests of Kernels/Metrics/Legibility.cxx: the legibility measure and the band-pass correlation,
// on analytic surfaces with known answers.
#include "Core/Constants.h"
#include "Core/Error.h"
#include "Core/Smoothing.h"
#include "Features/CrossSections.h"
#include "Features/FeatureGraph.h"
#include "Features/FeaturesTestData.h"
#include "Metrics/Legibility.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <utility>
#include <vector>

using namespace tsynth;
using tsynth::test::features::rough;
using tsynth::test::features::surface;

namespace
{

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

// Rough land of 200 x 160 cells with a ridge 600 m high, 10 cells wide
// (sigma), along row 80.
struct RidgedLand
{
  static constexpr int kW = 200;
  static constexpr int kH = 160;
  Heightfield land = rough(kW, kH, 15.0, 3);
  Heightfield ridged = surface(kW,
    kH,
    [this](int i, int j)
    { return land.at(i, j) + 600.0 * std::exp(-0.5 * std::pow((j - 80) / 10.0, 2)); });
};

} // namespace

TEST(Legibility, AGaussianRidgeOnTheStrokeIsLegibleAndTheLandBesideItIsNot)
{
  const RidgedLand r;
  const int w = r.kW, h = r.kH;
  const Heightfield& land = r.land;
  const LandRelief relief({ &land });
  const Heightfield& ridged = r.ridged;
  const FeatureGraph onIt = lines(w, h, { { { 20, 80 }, { 180, 80 } } }, FeatureType::Ridge);
  const FeatureGraph beside = lines(w, h, { { { 20, 120 }, { 180, 120 } } }, FeatureType::Ridge);
  const FeatureGraph asValley = lines(w, h, { { { 20, 80 }, { 180, 80 } } }, FeatureType::Valley);
  const Legibility good = evaluateLegibility(ridged, onIt, relief);
  EXPECT_GT(good.ridge.share, 0.95);
  EXPECT_GT(good.ridge.prominence, 200.0);
  EXPECT_TRUE(std::isnan(good.valley.share));
  EXPECT_EQ(good.share, good.ridge.share);
  // A lone stroke 160 cells long: a sixth of its length, under loneHalfWidth.
  EXPECT_NEAR(good.ridge.halfWidth, std::floor(160.0 / kStrokeLengthPerHalfWidth), 0.5);
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

TEST(Legibility, EachStrokeIsReadOnItsOwnAndTheWeakestIsNamed)
{
  const RidgedLand r;
  const int w = r.kW, h = r.kH;
  const LandRelief relief({ &r.land });
  const Heightfield& ridged = r.ridged;
  // The ridge drawn on it, a stroke beside it, and one too short to count.
  const FeatureGraph drawn = lines(w,
    h,
    { { { 20, 80 }, { 180, 80 } }, { { 20, 130 }, { 180, 130 } }, { { 20, 20 }, { 30, 20 } } },
    FeatureType::Ridge);
  const Legibility l = evaluateLegibility(ridged, drawn, relief);
  ASSERT_EQ(l.strokes.size(), 3u);
  EXPECT_GT(l.strokes[0].share, 0.95);
  EXPECT_LT(l.strokes[1].share, 0.35);
  EXPECT_NEAR(l.strokes[0].length, 160.0, 1e-9);
  EXPECT_NEAR(l.strokes[0].centre.x, 100.0, 1e-9);
  EXPECT_NEAR(l.strokes[1].centre.y, 130.0, 1e-9);
  EXPECT_LT(l.strokes[2].samples, kMinWeakestStrokeSamples);
  EXPECT_EQ(l.weakest, 1u);
  EXPECT_EQ(l.weakestShare(), l.strokes[1].share);
  // The share of all the length lies between the strokes'.
  EXPECT_GT(l.share, l.strokes[1].share);
  EXPECT_LT(l.share, l.strokes[0].share);
  // Nothing to read: no weakest.
  const Legibility none = evaluateLegibility(ridged, lines(w, h, {}, FeatureType::Ridge), relief);
  EXPECT_TRUE(none.strokes.empty());
  EXPECT_TRUE(std::isnan(none.weakestShare()));
}
