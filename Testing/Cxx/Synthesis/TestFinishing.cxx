// Tests of Kernels/Synthesis/Finishing.cxx.
// The last steps of a synthesis: draining the sketched valleys, the gentle
// landform correction and the exact height constraints, on terrains whose
// answer is known.
#include "Core/Error.h"
#include "Core/Smoothing.h"
#include "Features/Sketch.h"
#include "Hydrology/Flow.h"
#include "Synthesis/Finishing.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <vector>

using namespace tsynth;

namespace
{

constexpr double kCell = 30.0; // metres
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

Heightfield terrain(int w, int h, const std::function<double(int, int)>& f)
{
  Heightfield hf(w, h);
  hf.cellX = hf.cellY = kCell;
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

// |Laplacian| (m^-1) of the interior cells, its `p` quantile.
double laplacianQuantile(const Heightfield& hf, double p)
{
  std::vector<double> v;
  for (int j = 1; j + 1 < hf.height; ++j)
  {
    for (int i = 1; i + 1 < hf.width; ++i)
    {
      const double z = hf.at(i, j);
      const double l = (hf.at(i + 1, j) + hf.at(i - 1, j) - 2 * z) / (hf.cellX * hf.cellX) +
        (hf.at(i, j + 1) + hf.at(i, j - 1) - 2 * z) / (hf.cellY * hf.cellY);
      v.push_back(std::abs(l));
    }
  }
  const std::size_t k = static_cast<std::size_t>(p * static_cast<double>(v.size() - 1));
  std::nth_element(v.begin(), v.begin() + static_cast<long>(k), v.end());
  return v[k];
}

// The valley: V flanks rising 5 m per cell from column 60, the floor falling
// 1 m per cell towards the south border, bumps of 3 m along the floor and a
// 30 m dam across it at row 100. The sketched line runs up the axis from the
// border to row 150.
constexpr int kW = 121;
constexpr int kH = 170;
constexpr int kAxis = 60;
constexpr int kHead = 150;
constexpr int kDamRow = 100;
constexpr double kDam = 30.0;
constexpr double kBumps = 3.0;

Heightfield dammedValley()
{
  return terrain(kW,
    kH,
    [](int i, int j)
    {
      const double across = std::abs(i - kAxis);
      double z = 500.0 + 5.0 * across + 1.0 * j;
      // Bumps on the floor, fading over 4 cells either side.
      z += kBumps * std::sin(0.7 * j) * std::max(0.0, 1.0 - across / 4.0);
      // The dam: 30 m high on the floor, 5 rows thick, 8 cells either side.
      const double along = std::abs(j - kDamRow);
      if (along < 3.0 && across < 8.0)
      {
        z += kDam * 0.5 * (1.0 + std::cos(3.14159265358979 * along / 3.0));
      }
      return z;
    });
}

std::size_t cell(int i, int j)
{
  return static_cast<std::size_t>(j) * kW + static_cast<std::size_t>(i);
}

// Flow distance along the axis from the south border, NaN off the line.
std::vector<float> axisDownstream()
{
  std::vector<float> d(static_cast<std::size_t>(kW) * kH, kNaN);
  for (int j = 0; j <= kHead; ++j)
  {
    d[cell(kAxis, j)] = static_cast<float>(j * kCell);
  }
  return d;
}

std::vector<std::uint32_t> accumulation(const Heightfield& hf)
{
  const Heightfield filled = fillDepressions(hf);
  return flowAccumulation(flowDirections(filled), hf.width, hf.height);
}

// Line cells whose accumulation is not above the one upstream of them.
int accumulationDrops(const std::vector<std::uint32_t>& acc)
{
  int drops = 0;
  for (int j = 0; j < kHead; ++j)
  {
    drops += acc[cell(kAxis, j)] <= acc[cell(kAxis, j + 1)] ? 1 : 0;
  }
  return drops;
}

} // namespace

TEST(DrainValleys, WaterRunsDownTheSketchedValley)
{
  const Heightfield before = dammedValley();
  Heightfield out = before;
  const std::vector<float> downstream = axisDownstream();
  const DrainageOptions o;
  const DrainageReport r = drainValleys(out, downstream, o);
  std::printf("drained: %zu line cells, %zu lowered, deepest cut %.2f m, mean %.2f m\n",
    r.cells,
    r.lowered,
    r.largest,
    r.mean);
  EXPECT_EQ(r.cells, static_cast<std::size_t>(kHead + 1));
  // The dam is cut through (most of its 30 m), the bumps evened out.
  EXPECT_GT(r.largest, 0.6 * kDam);
  EXPECT_LT(r.largest, kDam + 2 * kBumps);
  EXPECT_GT(r.lowered, static_cast<std::size_t>(kHead / 3));

  // Every line cell lies below its upstream neighbour on the line by the
  // minimum gradient at least.
  const double step = o.minimumGradient * kCell;
  for (int j = 0; j < kHead; ++j)
  {
    ASSERT_LE(out.at(kAxis, j), out.at(kAxis, j + 1) - step * (1 - 1e-3)) << j;
  }
  // ... and below the cells beside it.
  for (int j = 1; j <= kHead; ++j)
  {
    ASSERT_LT(out.at(kAxis, j), out.at(kAxis - 1, j)) << j;
    ASSERT_LT(out.at(kAxis, j), out.at(kAxis + 1, j)) << j;
  }

  // No lake is left on the line: before, filling raised the floor behind the
  // dam by most of its height; after, the filled line is the drained one. (The
  // bumps past the line's head, which nobody sketched, keep their puddles.)
  auto deepestFillOnTheLine = [](const Heightfield& hf)
  {
    const Heightfield filled = fillDepressions(hf);
    double d = 0.0;
    for (int j = 0; j <= kHead; ++j)
    {
      d = std::max(d, static_cast<double>(filled.at(kAxis, j) - hf.at(kAxis, j)));
    }
    return d;
  };
  const double lakeBefore = deepestFillOnTheLine(before);
  const double lakeAfter = deepestFillOnTheLine(out);
  std::printf("deepest fill on the line: %.2f m before, %.4f m after\n", lakeBefore, lakeAfter);
  EXPECT_GT(lakeBefore, 0.5 * kDam) << "the test terrain must need draining";
  EXPECT_EQ(lakeAfter, 0.0);
  // D8 on the filled terrain follows the line: accumulation grows at every
  // step down it, and at the outlet collects nearly all of the map (all but the
  // border cells that drain off it).
  const std::vector<std::uint32_t> acc = accumulation(out);
  EXPECT_EQ(accumulationDrops(acc), 0);
  const double share = static_cast<double>(acc[cell(kAxis, 0)]) / (kW * kH);
  std::printf("outlet accumulation: %.3f of the map\n", share);
  EXPECT_GT(share, 0.9);

  // The change is confined to the reach around the line.
  for (int j = 0; j < kH; ++j)
  {
    for (int i = 0; i < kW; ++i)
    {
      const double d = j <= kHead ? std::abs(i - kAxis) : std::hypot(i - kAxis, j - kHead);
      if (d >= o.reach)
      {
        ASSERT_EQ(out.at(i, j), before.at(i, j)) << i << ", " << j;
      }
    }
  }
  // No creases: the sharpest 0.1% of the terrain (the V's axis, 0.011 1/m, and
  // its bumps) may not get more than a quarter sharper; a slot cut 1.5 m deep
  // (maximumChannelCut) beside the cells of a 30 m grid would reach 0.1 1/m.
  const double lapBefore = laplacianQuantile(before, 0.999);
  const double lapAfter = laplacianQuantile(out, 0.999);
  std::printf(
    "99.9th percentile |Laplacian|: %.5f before, %.5f after (1/m)\n", lapBefore, lapAfter);
  EXPECT_LT(lapAfter, 1.25 * lapBefore);
}

// The dammed valley with its axis slanted 0.4 cells across per row: a line
// whose cells make a staircase, as most drawn lines' do.
constexpr double kSlant = 0.4;

double slantedAxis(double j)
{
  return kAxis + kSlant * (j - 0.5 * kHead);
}

TEST(DrainValleys, ASlantedLineIsCutAsAFloorNotAsADottedSlot)
{
  const Heightfield before = terrain(kW,
    kH,
    [](int i, int j)
    {
      const double across = std::abs(i - slantedAxis(j)) / std::hypot(1.0, kSlant);
      double z = 500.0 + 5.0 * across + 1.0 * j;
      const double along = std::abs(j - kDamRow);
      if (along < 3.0 && across < 8.0)
      {
        z += kDam * 0.5 * (1.0 + std::cos(3.14159265358979 * along / 3.0));
      }
      return z;
    });
  std::vector<float> downstream(before.size(), kNaN);
  for (int j = 0; j <= kHead; ++j)
  {
    const int i = static_cast<int>(std::lround(slantedAxis(j)));
    downstream[cell(i, j)] = static_cast<float>(j * kCell * std::hypot(1.0, kSlant));
  }
  Heightfield out = before;
  const DrainageReport r = drainValleys(out, downstream);
  EXPECT_GT(r.largest, 0.6 * kDam) << "the dam must be cut through";
  // Where the dam was cut, the cells either side of the line went down with it
  // (the cut is a floor a few cells wide): over the dam's middle rows they
  // stand a small share of the cut above the line. Widened by a profile that
  // falls away from the line cells themselves, they stood 0.36 of the cut
  // above it (a slot, which a staircase of line cells showed in a hillshade
  // as a dotted line); now 0.22.
  double rise = 0.0;
  int sides = 0;
  for (int j = kDamRow - 1; j <= kDamRow + 1; ++j)
  {
    const int i = static_cast<int>(std::lround(slantedAxis(j)));
    for (int di : { -1, 1 })
    {
      if (std::isnan(downstream[cell(i + di, j)]))
      {
        rise += out.at(i + di, j) - out.at(i, j);
        ++sides;
      }
    }
  }
  rise /= sides;
  std::printf(
    "cut %.1f m; the cells beside the line over the dam %.2f m above it\n", r.largest, rise);
  EXPECT_LT(rise, 0.3 * r.largest);
  // No creases: as for the straight valley, the sharpest 0.1% of the terrain
  // may not get much sharper.
  EXPECT_LT(laplacianQuantile(out, 0.999), 1.25 * laplacianQuantile(before, 0.999));
}

TEST(DrainValleys, NoLinesNoChange)
{
  const Heightfield before = dammedValley();
  Heightfield out = before;
  const DrainageReport none = drainValleys(out, std::vector<float>(before.size(), kNaN));
  EXPECT_EQ(none.cells, 0u);
  EXPECT_EQ(none.lowered, 0u);
  EXPECT_EQ(none.largest, 0.0);
  EXPECT_EQ(out.z, before.z);
  const DrainageReport empty = drainValleys(out, {});
  EXPECT_EQ(empty.cells, 0u);
  EXPECT_EQ(out.z, before.z);
}

TEST(DrainValleys, AValleyAlreadyDrainingIsLeftNearlyAlone)
{
  // A clean V valley, descending 1 m per cell: the line already drains; only
  // the channel below the cells beside it (0.03 m for 30 m cells) is cut.
  const Heightfield before =
    terrain(kW, kH, [](int i, int j) { return 500.0 + 5.0 * std::abs(i - kAxis) + j; });
  Heightfield out = before;
  const DrainageReport r = drainValleys(out, axisDownstream());
  EXPECT_LT(r.largest, 0.1);
  double largest = 0.0;
  for (std::size_t k = 0; k < out.size(); ++k)
  {
    largest = std::max(largest, std::abs(static_cast<double>(out.z[k] - before.z[k])));
  }
  EXPECT_LT(largest, 0.1);
}

// ---------------------------------------------------------------------------

namespace
{

constexpr int kSide = 160;
constexpr double kSigma = 8.0;

// Detail at a few cells over a ramp: what the patches carry.
Heightfield detailedRamp()
{
  return terrain(kSide,
    kSide,
    [](int i, int j) { return 800.0 + 2.0 * i + 15.0 * std::sin(1.3 * i) * std::cos(0.9 * j); });
}

// The target: the same ramp with a broad 60 m hill the output lacks.
Heightfield target()
{
  return terrain(kSide,
    kSide,
    [](int i, int j)
    {
      const double r2 = (i - 80.0) * (i - 80.0) + (j - 80.0) * (j - 80.0);
      return 800.0 + 2.0 * i + 60.0 * std::exp(-r2 / (2 * 30.0 * 30.0));
    });
}

} // namespace

TEST(CorrectLandform, MovesTheLowPassWhereConfidentOnly)
{
  const Heightfield before = detailedRamp();
  const Heightfield lowTarget = smoothLarge(target(), kSigma);
  // Confident in the west half, not in the east half.
  std::vector<float> confidence(before.size());
  for (int j = 0; j < kSide; ++j)
  {
    for (int i = 0; i < kSide; ++i)
    {
      confidence[before.index(i, j)] = i < kSide / 2 ? 1.0f : 0.0f;
    }
  }
  Heightfield out = before;
  const double largest = correctLandform(out, lowTarget, confidence, kSigma);
  // The change per cell is exactly the confidence times the low-pass misfit,
  // and the largest of them is returned.
  const Heightfield lowBefore = smoothLarge(before, kSigma);
  double expectedLargest = 0.0;
  for (std::size_t k = 0; k < out.size(); ++k)
  {
    const double change = confidence[k] * (lowTarget.z[k] - lowBefore.z[k]);
    ASSERT_NEAR(out.z[k] - before.z[k], change, 1e-3) << k;
    expectedLargest = std::max(expectedLargest, std::abs(change));
  }
  EXPECT_NEAR(largest, expectedLargest, 1e-9);
  EXPECT_GT(largest, 40.0) << "the hill is missing from the output";
  // Far inside the confident half (3 sigma from the edge of the map and of the
  // confident part), the output's low-pass now matches the target's within a
  // tenth of the misfit it had; the unconfident half keeps its own.
  const Heightfield lowAfter = smoothLarge(out, kSigma);
  const int margin = static_cast<int>(3 * kSigma);
  double misfitBefore = 0.0;
  double misfitAfter = 0.0;
  for (int j = margin; j < kSide - margin; ++j)
  {
    for (int i = margin; i < kSide / 2 - margin; ++i)
    {
      misfitBefore =
        std::max(misfitBefore, std::abs(double(lowBefore.at(i, j) - lowTarget.at(i, j))));
      misfitAfter = std::max(misfitAfter, std::abs(double(lowAfter.at(i, j) - lowTarget.at(i, j))));
    }
    for (int i = kSide / 2; i < kSide; ++i)
    {
      ASSERT_EQ(out.at(i, j), before.at(i, j)) << i << ", " << j;
    }
  }
  std::printf(
    "low-pass misfit where confident: %.2f m before, %.2f m after\n", misfitBefore, misfitAfter);
  EXPECT_LT(misfitAfter, 0.1 * misfitBefore);
  // The detail finer than sigma stays: out - lowAfter is the old detail.
  double detailChange = 0.0;
  for (int j = margin; j < kSide - margin; ++j)
  {
    for (int i = margin; i < kSide / 2 - margin; ++i)
    {
      const double oldDetail = before.at(i, j) - lowBefore.at(i, j);
      const double newDetail = out.at(i, j) - lowAfter.at(i, j);
      detailChange = std::max(detailChange, std::abs(newDetail - oldDetail));
    }
  }
  EXPECT_LT(detailChange, 0.1 * misfitBefore);
  // Empty confidence means 1 everywhere; sigma 0 changes nothing.
  Heightfield all = before;
  correctLandform(all, lowTarget, {}, kSigma);
  EXPECT_NEAR(
    all.at(120, 80) - before.at(120, 80), lowTarget.at(120, 80) - lowBefore.at(120, 80), 1e-3);
  Heightfield none = before;
  EXPECT_EQ(correctLandform(none, lowTarget, {}, 0.0), 0.0);
  EXPECT_EQ(none.z, before.z);
}

TEST(MeetConstraints, ConstrainedLinesSitAtTheirHeights)
{
  // A line across a rough plane asked to stand at 1500 m at its west end and
  // 1600 m at its east end: exact on the line, fading to nothing 20 cells away.
  Heightfield out =
    terrain(120, 100, [](int i, int j) { return 1000.0 + 7.0 * std::sin(0.8 * i + 0.3 * j); });
  const Heightfield before = out;
  Polyline line{ { { 10, 50 }, { 110, 50 } }, { 1500.0f, 1600.0f }, FeatureType::Ridge };
  const FeatureGraph g = polylineFeatures({ line }, out.width, out.height, kCell, kCell);
  constexpr double kReach = 20.0;
  meetConstraints(out, g, kReach);
  for (int i = 10; i <= 110; ++i)
  {
    ASSERT_NEAR(out.at(i, 50), 1500.0 + (i - 10), 1e-2) << i;
  }
  for (int j = 0; j < out.height; ++j)
  {
    for (int i = 0; i < out.width; ++i)
    {
      const double d = i < 10 ? std::hypot(i - 10, j - 50)
        : i > 110             ? std::hypot(i - 110, j - 50)
                              : std::abs(j - 50);
      if (d >= kReach + 1)
      {
        ASSERT_EQ(out.at(i, j), before.at(i, j)) << i << ", " << j;
      }
    }
  }
  // Harmonic between: the correction falls steadily from the line.
  for (int k = 1; k < 20; ++k)
  {
    const double here = out.at(60, 50 + k) - before.at(60, 50 + k);
    const double nearer = out.at(60, 50 + k - 1) - before.at(60, 50 + k - 1);
    EXPECT_LT(here, nearer) << k;
    EXPECT_GT(here, -1e-3) << k;
  }
  // Without constraints nothing moves.
  Heightfield free = before;
  meetConstraints(free,
    polylineFeatures({ { line.points, {}, FeatureType::Ridge } }, 120, 100, kCell, kCell),
    kReach);
  EXPECT_EQ(free.z, before.z);
}

TEST(CorrectLandformAtScales, EachCellIsCorrectedAtItsOwnScale)
{
  const Heightfield before = detailedRamp();
  const Heightfield goal = target();
  // The west half asks for 4 cells, the east half for 16; the largest is 16.
  std::vector<float> sigma(before.size());
  for (int j = 0; j < kSide; ++j)
  {
    for (int i = 0; i < kSide; ++i)
    {
      sigma[before.index(i, j)] = i < kSide / 2 ? 4.0f : 16.0f;
    }
  }
  Heightfield out = before;
  const double largest = correctLandformAtScales(out, goal, {}, sigma, 16.0, 2.0);
  EXPECT_GT(largest, 40.0);
  // Where 16 was asked the change is exactly the single-scale correction at 16
  // (the scales asked are blended over the finest level, 4 cells: 3 of them
  // from the boundary they are as asked).
  Heightfield single = before;
  correctLandform(single, smoothLarge(goal, 16.0), {}, 16.0);
  const int blend = 12;
  for (int j = 0; j < kSide; j += 7)
  {
    for (int i = kSide / 2 + blend; i < kSide; i += 7)
    {
      ASSERT_NEAR(out.at(i, j), single.at(i, j), 1e-3) << i << ", " << j;
    }
  }
  // Where 4 was asked it is the correction at 4: the output's low-pass at 4
  // becomes the target's (its 15 m detail at about 1.3 cells stays).
  Heightfield fine = before;
  correctLandform(fine, smoothLarge(goal, 4.0), {}, 4.0);
  for (int j = 0; j < kSide; j += 7)
  {
    for (int i = 0; i < kSide / 2 - blend; i += 7)
    {
      ASSERT_NEAR(out.at(i, j), fine.at(i, j), 1e-3) << i << ", " << j;
    }
  }
  // Across the boundary the change moves smoothly from one to the other: no
  // step larger than the corrections' own slope.
  for (int i = kSide / 2 - blend; i < kSide / 2 + blend; ++i)
  {
    EXPECT_LT(
      std::abs((out.at(i + 1, 80) - before.at(i + 1, 80)) - (out.at(i, 80) - before.at(i, 80))),
      3.0)
      << i;
  }
  // A scale under the finest allowed is taken as the finest.
  std::vector<float> tiny(before.size(), 0.5f);
  Heightfield a = before;
  Heightfield b = before;
  correctLandformAtScales(a, goal, {}, tiny, 16.0, 4.0);
  correctLandformAtScales(b, goal, {}, std::vector<float>(before.size(), 4.0f), 16.0, 4.0);
  EXPECT_EQ(a.z, b.z);
  // A scale between the levels, everywhere: that scale exactly.
  const float between = 8.0f * std::sqrt(2.0f);
  Heightfield mid = before;
  correctLandformAtScales(mid, goal, {}, std::vector<float>(before.size(), between), 16.0, 8.0);
  Heightfield exact = before;
  correctLandform(exact, smoothLarge(goal, between), {}, between);
  EXPECT_NEAR(mid.at(80, 80), exact.at(80, 80), 1e-3);
  // Confidence scales it; no largest scale, no change.
  Heightfield none = before;
  EXPECT_EQ(correctLandformAtScales(none, goal, {}, sigma, 0.0, 2.0), 0.0);
  EXPECT_EQ(none.z, before.z);
  Heightfield zero = before;
  correctLandformAtScales(zero, goal, std::vector<float>(before.size(), 0.0f), sigma, 16.0, 2.0);
  EXPECT_EQ(zero.z, before.z);
}

TEST(CorrectLandformAtScales, ADrawnTargetKeepsItsOwnShape)
{
  // The patches' ramp with its 15 m detail, and a drawn target: the same ramp
  // with a V valley 200 m deep, 12 cells wide each side, down column 80.
  const Heightfield before = detailedRamp();
  constexpr double kDepth = 200.0;
  constexpr double kHalf = 12.0;
  const Heightfield goal = terrain(kSide,
    kSide,
    [&](int i, int)
    { return 800.0 + 2.0 * i - kDepth * std::max(0.0, 1.0 - std::abs(i - 80) / kHalf); });
  const std::vector<float> sigma(before.size(), static_cast<float>(kSigma));
  // The valley's depth in a result: its floor under the land 20 cells each side.
  auto depth = [](const Heightfield& hf)
  {
    double d = 0.0;
    for (int j = 20; j < kSide - 20; ++j)
    {
      d += 0.5 * (hf.at(60, j) + hf.at(100, j)) - hf.at(80, j);
    }
    return d / (kSide - 40);
  };
  Heightfield blurred = before;
  correctLandformAtScales(blurred, goal, {}, sigma, kSigma, kSigma);
  Heightfield drawn = before;
  constexpr double kTargetSigma = 2.0;
  correctLandformAtScales(drawn, goal, {}, sigma, kSigma, kSigma, kTargetSigma);
  std::printf(
    "valley depth: %.1f m asked, %.1f m in the target's own shape, %.1f m blurred at %g cells\n",
    kDepth,
    depth(drawn),
    depth(blurred),
    kSigma);
  // Taken at the correction's own scale the valley comes out at under half its
  // depth (0.45); in its own shape, rounded over 2 cells, at 1 - 2 sqrt(2 / pi)
  // / 12 = 0.87 of it (the V's floor averaged over the Gaussian).
  EXPECT_LT(depth(blurred), 0.55 * kDepth);
  EXPECT_NEAR(depth(drawn),
    (1.0 - kTargetSigma * std::sqrt(2.0 / 3.14159265358979) / kHalf) * kDepth,
    0.02 * kDepth);
  // Either way the detail finer than sigma stays the patches': the result
  // minus the target's shape is the patches' detail, to within what the
  // detail's own low-pass at sigma takes away.
  const Heightfield shape = smoothLarge(goal, kTargetSigma);
  double worst = 0.0;
  for (int j = 20; j < kSide - 20; ++j)
  {
    for (int i = 20; i < kSide - 20; ++i)
    {
      const double detail = before.at(i, j) - (800.0 + 2.0 * i);
      worst = std::max(worst, std::abs(drawn.at(i, j) - shape.at(i, j) - detail));
    }
  }
  std::printf("largest departure from target shape + detail: %.2f m (detail 15 m)\n", worst);
  EXPECT_LT(worst, 1.0);
}

TEST(DrainValleys, AValleyEndingInAClosedBasinIsLedOutOfIt)
{
  // A V valley falling 1 m per cell towards row 60, where its line ends in a
  // bowl 40 m deep (rows 30-90): the bowl is a closed basin whose lake, filled,
  // drowns the line's lower 25 cells. Its line is drawn from row 150 down to
  // row 60 (flow distance 0 there: the outlet lies inside the map).
  const Heightfield before = terrain(kW,
    kH,
    [](int i, int j)
    {
      const double across = std::abs(i - kAxis);
      const double r = std::hypot(i - kAxis, j - 60.0);
      return 500.0 + 5.0 * across + 1.0 * std::abs(j - 60) - 40.0 * std::max(0.0, 1.0 - r / 30.0);
    });
  std::vector<float> downstream(before.size(), kNaN);
  for (int j = 60; j <= kHead; ++j)
  {
    downstream[cell(kAxis, j)] = static_cast<float>((j - 60) * kCell);
  }
  auto deepestFillOnTheLine = [](const Heightfield& hf)
  {
    const Heightfield filled = fillDepressions(hf);
    double d = 0.0;
    for (int j = 60; j <= kHead; ++j)
    {
      d = std::max(d, static_cast<double>(filled.at(kAxis, j) - hf.at(kAxis, j)));
    }
    return d;
  };
  ASSERT_GT(deepestFillOnTheLine(before), 20.0) << "the test terrain must hold a lake";
  Heightfield out = before;
  const DrainageReport r = drainValleys(out, downstream);
  // The report counts the drawn line only, not the way out.
  EXPECT_EQ(r.cells, static_cast<std::size_t>(kHead - 60 + 1));
  // No lake is left on the line, and D8 on the filled terrain gathers the
  // flanks' water all the way down it.
  EXPECT_EQ(deepestFillOnTheLine(out), 0.0);
  const std::vector<std::uint32_t> acc = accumulation(out);
  for (int j = 60; j < kHead; ++j)
  {
    ASSERT_GT(acc[cell(kAxis, j)], acc[cell(kAxis, j + 1)]) << j;
  }
  // ... and carries it out of the map: the water at the outlet reaches the
  // border, with all of the line's catchment.
  std::size_t k = cell(kAxis, 60);
  const std::vector<std::int8_t> dir = flowDirections(fillDepressions(out));
  int steps = 0;
  while (dir[k] != kNoFlow && steps < kW * kH)
  {
    k = static_cast<std::size_t>(static_cast<std::ptrdiff_t>(k) + d8Offset(dir[k], kW));
    ++steps;
  }
  const int i = static_cast<int>(k % kW);
  const int j = static_cast<int>(k / kW);
  EXPECT_TRUE(i == 0 || j == 0 || i == kW - 1 || j == kH - 1) << i << ", " << j;
  EXPECT_GE(acc[k], acc[cell(kAxis, 60)]);
}

TEST(DrainValleys, AValleyWhoseLandFallsBackUpItIsLedOutOverTheLand)
{
  // The land along the line falls the other way, 1 m per cell towards the
  // north border, and the line's outlet end (row 60, flow distance 0) lies in
  // land that rises 1 m per cell to the south: breaching would drain the
  // outlet back up the line. Draining the line towards its outlet then made a
  // closed basin there, a lake as deep as the land the line climbed.
  const Heightfield before = terrain(kW,
    kH,
    [](int i, int j) { return 500.0 + 5.0 * std::abs(i - kAxis) + 1.0 * std::abs(j - 120); });
  std::vector<float> downstream(before.size(), kNaN);
  for (int j = 60; j <= kHead; ++j)
  {
    downstream[cell(kAxis, j)] = static_cast<float>((j - 60) * kCell);
  }
  Heightfield out = before;
  const DrainageReport r = drainValleys(out, downstream);
  EXPECT_EQ(r.cells, static_cast<std::size_t>(kHead - 60 + 1));
  const Heightfield filled = fillDepressions(out);
  double lake = 0.0;
  for (int j = 60; j <= kHead; ++j)
  {
    lake = std::max(lake, static_cast<double>(filled.at(kAxis, j) - out.at(kAxis, j)));
  }
  EXPECT_EQ(lake, 0.0);
  // The water at the outlet leaves the map without running back up the line.
  const std::vector<std::int8_t> dir = flowDirections(filled);
  std::size_t k = cell(kAxis, 60);
  int steps = 0;
  while (dir[k] != kNoFlow && steps < kW * kH)
  {
    k = static_cast<std::size_t>(static_cast<std::ptrdiff_t>(k) + d8Offset(dir[k], kW));
    ++steps;
    const int j = static_cast<int>(k / kW);
    ASSERT_FALSE(static_cast<int>(k % kW) == kAxis && j > 60 && j <= kHead) << "back up the line";
  }
  const int i = static_cast<int>(k % kW);
  const int j = static_cast<int>(k / kW);
  EXPECT_TRUE(i == 0 || j == 0 || i == kW - 1 || j == kH - 1) << i << ", " << j;
}

TEST(DrainValleys, UnconnectedValleysKeepTheirOwnFloors)
{
  // Two V valleys side by side, each falling 1 m per cell to the south border,
  // one floored 400 m above the other (a cliff between them at column 60).
  // Each already drains: draining must not move either's floor towards the
  // other's.
  constexpr int kLow = 30;
  constexpr int kHigh = 90;
  const Heightfield before = terrain(kW,
    kH,
    [](int i, int j)
    {
      const double floor =
        i < kAxis ? 500.0 + 5.0 * std::abs(i - kLow) : 900.0 + 5.0 * std::abs(i - kHigh);
      return floor + 1.0 * j;
    });
  std::vector<float> downstream(before.size(), kNaN);
  for (int j = 0; j <= kHead; ++j)
  {
    downstream[cell(kLow, j)] = static_cast<float>(j * kCell);
    downstream[cell(kHigh, j)] = static_cast<float>(j * kCell);
  }
  Heightfield out = before;
  drainValleys(out, downstream);
  double moved = 0.0;
  for (int j = 0; j <= kHead; ++j)
  {
    for (int i : { kLow, kHigh })
    {
      moved = std::max(moved, std::abs(static_cast<double>(out.at(i, j) - before.at(i, j))));
    }
  }
  std::printf("largest change of a floor: %.2f m\n", moved);
  // The channel's own cut (a tenth of a metre per 100 m cell, at most 1.5 m
  // at 30 m) and the descent's, nothing of the other valley's 400 m.
  EXPECT_LT(moved, 2.0);
}

TEST(CompressIntoRange, HeightsPastTheRangeComeBackSmoothlyAndInOrder)
{
  // A ramp from 0 to 1000 m against the range [300, 700] with 40 m of slack.
  Heightfield hf = terrain(101, 3, [](int i, int) { return 10.0 * i; });
  const Heightfield before = hf;
  const std::size_t moved = compressIntoRange(hf, 300.0, 700.0, 40.0);
  EXPECT_EQ(moved, 3u * (30 + 30)); // 0-290 m and 710-1000 m, three rows
  for (int i = 0; i <= 100; ++i)
  {
    const double z = hf.at(i, 1);
    EXPECT_GE(z, 300.0 - 40.0) << i;
    EXPECT_LE(z, 700.0 + 40.0) << i;
    if (before.at(i, 1) >= 300.0 && before.at(i, 1) <= 700.0)
    {
      EXPECT_EQ(z, before.at(i, 1)) << i; // the range itself is untouched
    }
    if (i > 0)
    {
      // Still in order (strictly within a few slacks of the range; farther,
      // tanh comes within a float step of 1): water runs where it ran.
      EXPECT_GE(z, hf.at(i - 1, 1)) << i;
      if (std::abs(before.at(i, 1) - 500.0) < 200.0 + 3 * 40.0)
      {
        EXPECT_GT(z, hf.at(i - 1, 1)) << i;
      }
    }
  }
  // Slope 1 at the edge of the range: 10 m past it is moved by under 1 m.
  EXPECT_NEAR(hf.at(29, 1), 290.0, 1.0);
  EXPECT_NEAR(hf.at(71, 1), 710.0, 1.0);
  // No slack, or an empty range: nothing moves.
  Heightfield same = before;
  EXPECT_EQ(compressIntoRange(same, 300.0, 700.0, 0.0), 0u);
  EXPECT_EQ(compressIntoRange(same, 700.0, 300.0, 40.0), 0u);
  EXPECT_EQ(same.z, before.z);
}

// The whole finishing of a synthesis (finishSynthesis), on the dammed valley
// placed 80 m too high with a tilt across it: the drift goes where the target
// is confident, the valley drains past the dam, heights past the exemplars'
// range come back into it, and a height constraint above that range still
// wins (the constraints come after the range); drainage everywhere only when
// asked.
TEST(FinishSynthesis, CorrectsDrainsKeepsTheRangeAndMeetsConstraintsLast)
{
  constexpr double kOffset = 80.0; // metres the placed land stands too high
  constexpr double kTilt = 0.5;    // ... and metres per cell it rises eastwards
  SynthesisTarget target;
  target.field =
    terrain(kW, kH, [](int i, int j) { return 500.0 + 5.0 * std::abs(i - kAxis) + j; });
  target.downstream = axisDownstream();
  constexpr double kConstraint = 1200.0; // above the range below
  const Polyline line{ { { 100, 12 }, { 115, 12 } },
    { static_cast<float>(kConstraint), static_cast<float>(kConstraint) },
    FeatureType::Ridge };
  target.graph = polylineFeatures({ line }, kW, kH, kCell, kCell);
  std::vector<float> confidence(target.field.size(), 0.0f);
  for (int j = 0; j < kH; ++j)
  {
    for (int i = 0; i < kW; ++i)
    {
      confidence[cell(i, j)] = std::abs(i - kAxis) < 20 ? 1.0f : 0.0f;
    }
  }
  const Heightfield dammed = dammedValley();
  Heightfield out =
    terrain(kW, kH, [&](int i, int j) { return dammed.at(i, j) + kOffset + kTilt * i; });
  FinishingPlan plan;
  plan.patchSize = 40; // reach of the constraint: 40 cells
  plan.lowest = 450.0;
  plan.highest = 900.0; // the valley's upper flanks (up to 970 m) lie past it
  plan.slack = 20.0;

  Heightfield finished = out;
  const FinishingReport f = finishSynthesis(finished, target, confidence, plan);

  // The drift is gone where the target is confident (away from the dam).
  double before = 0.0;
  double after = 0.0;
  int n = 0;
  for (int j = 20; j < 80; ++j)
  {
    for (int i = kAxis - 15; i <= kAxis + 15; ++i)
    {
      before += out.at(i, j) - target.field.at(i, j);
      after += finished.at(i, j) - target.field.at(i, j);
      ++n;
    }
  }
  EXPECT_GT(before / n, kOffset);
  EXPECT_LT(std::abs(after / n), 10.0);
  EXPECT_GT(f.landformCorrection, kOffset);
  // The valley drains past the dam: the floor falls all the way to the border.
  EXPECT_EQ(f.valleyCells, static_cast<std::size_t>(kHead + 1));
  EXPECT_GT(f.valleyCellsLowered, 0u);
  for (int j = 1; j <= kHead; ++j)
  {
    ASSERT_LT(finished.at(kAxis, j - 1), finished.at(kAxis, j)) << j;
  }
  // Within the range and its slack, but for the constrained line's reach.
  EXPECT_GT(f.cellsBroughtIntoRange, 0u);
  for (int j = 0; j < kH; ++j)
  {
    for (int i = 0; i < kW; ++i)
    {
      const double d = i < 100 ? std::hypot(i - 100, j - 12) : std::abs(j - 12);
      if (d > plan.patchSize + 1)
      {
        ASSERT_LE(finished.at(i, j), plan.highest + plan.slack) << i << ", " << j;
        ASSERT_GE(finished.at(i, j), plan.lowest - plan.slack) << i << ", " << j;
      }
    }
  }
  // The user's heights win over the range.
  for (int i = 100; i <= 115; ++i)
  {
    ASSERT_NEAR(finished.at(i, 12), kConstraint, 1e-2) << i;
  }
  EXPECT_FALSE(f.drained);

  // Drainage everywhere, when asked: no pit is left.
  plan.drainage = PitRemovalMethod::Fill;
  Heightfield drained = out;
  const FinishingReport g = finishSynthesis(drained, target, confidence, plan);
  EXPECT_TRUE(g.drained);
  EXPECT_EQ(g.pitsAfter, 0u);
  EXPECT_NE(drained.z, finished.z);

  // A target of another size is refused.
  SynthesisTarget smaller = target;
  smaller.field = terrain(kW - 1, kH, [](int, int) { return 0.0; });
  Heightfield again = out;
  EXPECT_THROW(finishSynthesis(again, smaller, confidence, plan), Error);
}
