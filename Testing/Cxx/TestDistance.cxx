// The kernels the landforms stand on: exact distance fields with the nearest
// seed, monotone cross-section profiles and large-scale smoothing, each against
// a brute-force or hand-computed answer (seeded randomness: TestRandom.cxx).
#include "Core/Error.h"
#include "Core/HeightfieldIO.h"
#include "Core/Smoothing.h"
#include "Distance/DistanceField.h"
#include "Distance/Profile.h"
#include "ErrorOf.h"
#include "Features/Ppa.h"
#include "TestData.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <string>

using namespace tsynth;

namespace
{

// ---------------------------------------------------------------------------
// Distance fields

struct SeedGrid
{
  int width;
  int height;
  double cellX;
  double cellY;
};

std::vector<std::uint8_t> randomSeeds(const SeedGrid& g, double density, unsigned seed)
{
  std::mt19937 rng(seed);
  std::bernoulli_distribution pick(density);
  std::vector<std::uint8_t> s(static_cast<std::size_t>(g.width) * g.height);
  for (auto& v : s)
  {
    v = pick(rng) ? 1 : 0;
  }
  return s;
}

// Squared metric distance between cells a and b (exact in double for these sizes).
double squaredMetres(const SeedGrid& g, std::size_t a, std::size_t b)
{
  const std::size_t w = static_cast<std::size_t>(g.width);
  const double dx = (static_cast<double>(a % w) - static_cast<double>(b % w)) * g.cellX;
  const double dy = (static_cast<double>(a / w) - static_cast<double>(b / w)) * g.cellY;
  return dx * dx + dy * dy;
}

// Every cell against every seed: the distance, and the seed the documented tie
// rule picks among those at that distance (lowest column, then lowest row).
struct BruteForce
{
  std::vector<double> squared;
  std::vector<std::int32_t> nearest;
};

BruteForce bruteForce(const std::vector<std::uint8_t>& seeds, const SeedGrid& g)
{
  const std::size_t n = seeds.size();
  const std::size_t w = static_cast<std::size_t>(g.width);
  BruteForce b;
  b.squared.assign(n, std::numeric_limits<double>::infinity());
  b.nearest.assign(n, -1);
  for (std::size_t c = 0; c < n; ++c)
  {
    for (std::size_t s = 0; s < n; ++s)
    {
      if (seeds[s] == 0)
      {
        continue;
      }
      const double d2 = squaredMetres(g, c, s);
      const std::size_t best = static_cast<std::size_t>(b.nearest[c]);
      const bool tieWins = b.nearest[c] >= 0 && d2 == b.squared[c] &&
        (s % w < best % w || (s % w == best % w && s / w < best / w));
      if (d2 < b.squared[c] || tieWins)
      {
        b.squared[c] = d2;
        b.nearest[c] = static_cast<std::int32_t>(s);
      }
    }
  }
  return b;
}

void expectMatchesBruteForce(const SeedGrid& g, double density, unsigned seed)
{
  const std::vector<std::uint8_t> seeds = randomSeeds(g, density, seed);
  const NearestSeeds fast = nearestSeeds(seeds, g.width, g.height, g.cellX, g.cellY);
  const BruteForce slow = bruteForce(seeds, g);
  ASSERT_EQ(fast.distance.size(), seeds.size());
  ASSERT_EQ(fast.nearest.size(), seeds.size());
  const bool any = std::count(seeds.begin(), seeds.end(), 1) > 0;
  EXPECT_EQ(fast.empty(), !any);
  for (std::size_t c = 0; c < seeds.size(); ++c)
  {
    const std::string where = std::to_string(g.width) + " x " + std::to_string(g.height) +
      ", cells " + std::to_string(g.cellX) + " x " + std::to_string(g.cellY) + ", density " +
      std::to_string(density) + ", cell " + std::to_string(c);
    if (!any)
    {
      ASSERT_TRUE(std::isinf(fast.distance[c])) << where;
      ASSERT_EQ(fast.nearest[c], -1) << where;
      continue;
    }
    ASSERT_EQ(fast.distance[c], static_cast<float>(std::sqrt(slow.squared[c]))) << where;
    const std::int32_t k = fast.nearest[c];
    ASSERT_GE(k, 0) << where;
    ASSERT_EQ(seeds[static_cast<std::size_t>(k)], 1) << where;
    ASSERT_EQ(squaredMetres(g, c, static_cast<std::size_t>(k)), slow.squared[c]) << where;
    ASSERT_EQ(k, slow.nearest[c]) << where << ": the tie rule";
  }
}

} // namespace

TEST(DistanceField, EqualsBruteForceOnRandomSeeds)
{
  const std::vector<SeedGrid> grids = { { 37, 23, 1.0, 1.0 },
    { 41, 29, 30.0, 90.0 },
    { 29, 41, 90.0, 30.0 },
    { 64, 1, 30.0, 90.0 },
    { 1, 57, 30.0, 90.0 },
    { 1, 1, 1.0, 1.0 } };
  // From a lone seed to a seed in every third cell.
  const std::array<double, 4> densities = { 0.002, 0.02, 0.1, 0.35 };
  unsigned seed = 1;
  for (const SeedGrid& g : grids)
  {
    for (double density : densities)
    {
      expectMatchesBruteForce(g, density, seed++);
      if (HasFatalFailure())
      {
        return;
      }
    }
  }
}

TEST(DistanceField, TiesAndSingleSeeds)
{
  // One seed: its own cell at 0, the far corner at the metric diagonal.
  std::vector<std::uint8_t> one(10 * 6, 0);
  one[2 * 10 + 3] = 1; // (3, 2)
  const NearestSeeds a = nearestSeeds(one, 10, 6, 30.0, 90.0);
  EXPECT_EQ(a.distance[2 * 10 + 3], 0.0f);
  EXPECT_FLOAT_EQ(a.distance[5 * 10 + 9], static_cast<float>(std::hypot(6 * 30.0, 3 * 90.0)));
  for (std::int32_t k : a.nearest)
  {
    EXPECT_EQ(k, 2 * 10 + 3);
  }
  // Seeds (1, 0) and (0, 1) are both one cell from (1, 1) and (0, 0): the one
  // in the lower column wins, though its index is the higher.
  std::vector<std::uint8_t> two(3 * 3, 0);
  two[1] = two[3] = 1;
  const NearestSeeds b = nearestSeeds(two, 3, 3);
  EXPECT_EQ(b.nearest[4], 3);
  EXPECT_EQ(b.nearest[0], 3);
  EXPECT_EQ(b.distance[4], 1.0f);
}

TEST(DistanceField, NoSeedsAndBadInput)
{
  const NearestSeeds none = nearestSeeds(std::vector<std::uint8_t>(12, 0), 4, 3, 30.0, 30.0);
  EXPECT_TRUE(none.empty());
  for (std::size_t c = 0; c < 12; ++c)
  {
    EXPECT_EQ(none.distance[c], std::numeric_limits<float>::infinity());
    EXPECT_EQ(none.nearest[c], -1);
  }
  EXPECT_THROW(nearestSeeds(std::vector<std::uint8_t>(11, 1), 4, 3), Error);
  EXPECT_THROW(nearestSeeds(std::vector<std::uint8_t>(13, 1), 4, 3), Error);
  EXPECT_THROW(distanceTransform(std::vector<std::uint8_t>(5, 1), 2, 2), Error);

  // distanceTransform is the unit-cell distance of nearestSeeds.
  const SeedGrid g{ 19, 13, 1.0, 1.0 };
  const std::vector<std::uint8_t> seeds = randomSeeds(g, 0.05, 99);
  EXPECT_EQ(
    distanceTransform(seeds, g.width, g.height), nearestSeeds(seeds, g.width, g.height).distance);
}

// ---------------------------------------------------------------------------
// Monotone profiles

namespace
{

using tsynth::test::errorOf;

bool contains(const std::string& text, const std::string& part)
{
  return text.find(part) != std::string::npos;
}

} // namespace

TEST(MonotoneProfile, FromPointsNamesTheOffendingPoint)
{
  std::string m = errorOf([] { MonotoneProfile::fromPoints({ 0.0, -5.0, 10.0 }, { 0, 1, 2 }); });
  EXPECT_TRUE(contains(m, "point 2 (-5, 1)")) << m;
  m = errorOf([] { MonotoneProfile::fromPoints({ -1.0, 5.0 }, { 0, 1 }); });
  EXPECT_TRUE(contains(m, "point 1")) << m;
  m = errorOf([] { MonotoneProfile::fromPoints({ 0.0, 10.0, 10.0 }, { 0, 1, 2 }); });
  EXPECT_TRUE(contains(m, "point 3 (10, 2)")) << m;
  EXPECT_TRUE(contains(m, "increase")) << m;
  m = errorOf([] { MonotoneProfile::fromPoints({ 0.0, 10.0, 5.0 }, { 0, 1, 2 }); });
  EXPECT_TRUE(contains(m, "point 3")) << m;
  // Up, level, then down: the fall at point 4 is the offence.
  m = errorOf([] { MonotoneProfile::fromPoints({ 0, 10, 20, 30 }, { 0, 5, 5, 3 }); });
  EXPECT_TRUE(contains(m, "point 4 (30, 3)")) << m;
  EXPECT_TRUE(contains(m, "turns down after going up")) << m;
  m = errorOf([] { MonotoneProfile::fromPoints({ 0, 10, 20 }, { 0, -5, 1 }); });
  EXPECT_TRUE(contains(m, "point 3")) << m;
  EXPECT_TRUE(contains(m, "turns up after going down")) << m;
  m = errorOf([] { MonotoneProfile::fromPoints({ 0, 10 }, { 0, std::nan("") }); });
  EXPECT_TRUE(contains(m, "point 2")) << m;
  EXPECT_FALSE(errorOf([] { MonotoneProfile::fromPoints({ 0, 1 }, { 0 }); }).empty());
  EXPECT_FALSE(errorOf([] { MonotoneProfile::fromPoints({}, {}); }).empty());
  // Level stretches are monotone either way.
  EXPECT_NO_THROW(MonotoneProfile::fromPoints({ 0, 10, 20, 30 }, { 4, 4, 1, 1 }));
  EXPECT_NO_THROW(MonotoneProfile::fromPoints({ 2.5 }, { 7 }));
}

TEST(MonotoneProfile, FitIsThePoolAdjacentViolatorsSolution)
{
  std::string m;
  // Rising fit of 5, 1, 2, 0, 6 with weights 1, 2, 1, 1, 1: 5 pools with 1
  // (7/3), then with 2 (9/4), then with 0 (9/5); 6 stays.
  const std::vector<double> d = { 0, 10, 20, 30, 40 };
  const std::vector<double> w = { 1, 2, 1, 1, 1 };
  const MonotoneProfile up =
    MonotoneProfile::fit(d, { 5, 1, 2, 0, 6 }, w, Monotonicity::NonDecreasing);
  const std::vector<double> expected = { 1.8, 1.8, 1.8, 1.8, 6.0 };
  ASSERT_EQ(up.values().size(), expected.size());
  for (std::size_t k = 0; k < expected.size(); ++k)
  {
    EXPECT_NEAR(up.values()[k], expected[k], 1e-12) << k;
  }
  EXPECT_EQ(up.distances(), d);
  // The falling fit of the negated data is the negated solution.
  const MonotoneProfile down =
    MonotoneProfile::fit(d, { -5, -1, -2, 0, -6 }, w, Monotonicity::NonIncreasing);
  for (std::size_t k = 0; k < expected.size(); ++k)
  {
    EXPECT_NEAR(down.values()[k], -expected[k], 1e-12) << k;
  }
  // 1, 3, 2, 4, 3.5, 5 unweighted: two separate pools (2.5 and 3.75).
  const MonotoneProfile two = MonotoneProfile::fit({ 0, 1, 2, 3, 4, 5 },
    { 1, 3, 2, 4, 3.5, 5 },
    { 1, 1, 1, 1, 1, 1 },
    Monotonicity::NonDecreasing);
  const std::vector<double> twoExpected = { 1, 2.5, 2.5, 3.75, 3.75, 5 };
  for (std::size_t k = 0; k < twoExpected.size(); ++k)
  {
    EXPECT_NEAR(two.values()[k], twoExpected[k], 1e-12) << k;
  }
  // Zero weights and NaN values drop out, distances and all.
  const MonotoneProfile dropped = MonotoneProfile::fit({ 0, 1, 2, 3, 4 },
    { 3, 1000, 1, std::nan(""), 2 },
    { 1, 0, 1, 1, 2 },
    Monotonicity::NonDecreasing);
  EXPECT_EQ(dropped.distances(), (std::vector<double>{ 0, 2, 4 }));
  // 3 and 1 pool to 2, then 2 (weight 2) with it: 2 everywhere.
  for (double v : dropped.values())
  {
    EXPECT_NEAR(v, 2.0, 1e-12);
  }
  // Bad input is an error, not a read past the end.
  EXPECT_THROW(
    MonotoneProfile::fit({ 0, 1, 2 }, { 1, 2, 3 }, { 1, 1 }, Monotonicity::NonDecreasing), Error);
  EXPECT_THROW(
    MonotoneProfile::fit({ 0, 1, 2 }, { 1, 2 }, { 1, 1, 1 }, Monotonicity::NonDecreasing), Error);
  m = errorOf(
    [] {
      MonotoneProfile::fit({ 0, 2, 1 }, { 1, 2, 3 }, { 1, 1, 1 }, Monotonicity::NonDecreasing);
    });
  EXPECT_TRUE(contains(m, "sample 3")) << m;
  // Monotone data come back unchanged.
  const MonotoneProfile same =
    MonotoneProfile::fit({ 0, 5, 9 }, { 10, 7, -2 }, { 3, 1, 1 }, Monotonicity::NonIncreasing);
  EXPECT_EQ(same.values(), (std::vector<double>{ 10, 7, -2 }));
}

TEST(MonotoneProfile, EvaluationReachAndNormalised)
{
  // A ridge falling 100 m over 600 m, steepest between 100 and 300 m.
  const MonotoneProfile p =
    MonotoneProfile::fromPoints({ 0, 100, 300, 600 }, { 0, -20, -80, -100 });
  EXPECT_DOUBLE_EQ(p(-50), 0.0);
  EXPECT_DOUBLE_EQ(p(50), -10.0);
  EXPECT_DOUBLE_EQ(p(200), -50.0);
  EXPECT_DOUBLE_EQ(p(450), -90.0);
  EXPECT_DOUBLE_EQ(p(1e6), -100.0);
  EXPECT_DOUBLE_EQ(p.length(), 600.0);
  EXPECT_DOUBLE_EQ(p.reach(0.0), 0.0);
  EXPECT_DOUBLE_EQ(p.reach(0.2), 100.0);
  EXPECT_DOUBLE_EQ(p.reach(0.5), 200.0);
  EXPECT_DOUBLE_EQ(p.reach(0.9), 450.0);
  EXPECT_DOUBLE_EQ(p.reach(1.0), 600.0);
  const MonotoneProfile n = p.normalised();
  EXPECT_EQ(n.distances(), p.distances());
  const std::vector<double> shape = { 0.0, 0.2, 0.8, 1.0 };
  for (std::size_t k = 0; k < shape.size(); ++k)
  {
    EXPECT_NEAR(n.values()[k], shape[k], 1e-15) << k;
  }
  // A valley (rising) with a level start: the reach counts from the start of
  // the change, its smallest distance.
  const MonotoneProfile v = MonotoneProfile::fromPoints({ 0, 50, 150, 250 }, { 5, 5, 35, 45 });
  EXPECT_DOUBLE_EQ(v.reach(0.0), 0.0);
  EXPECT_DOUBLE_EQ(v.reach(0.5), 50.0 + 100.0 * 20.0 / 30.0);
  EXPECT_DOUBLE_EQ(v.reach(0.75), 150.0);
  EXPECT_NEAR(v.normalised()(100.0), 0.375, 1e-15);
  // Constant and empty profiles.
  const MonotoneProfile flat = MonotoneProfile::fromPoints({ 0, 10 }, { 3, 3 });
  EXPECT_DOUBLE_EQ(flat.reach(0.9), 0.0);
  const MonotoneProfile flatShape = flat.normalised();
  for (double x : flatShape.values())
  {
    EXPECT_EQ(x, 0.0);
  }
  const MonotoneProfile none;
  EXPECT_TRUE(none.empty());
  EXPECT_DOUBLE_EQ(none(12.0), 0.0);
  EXPECT_DOUBLE_EQ(none.reach(0.5), 0.0);
}

// ---------------------------------------------------------------------------
// Large-scale smoothing

namespace
{

// Moments of a non-negative field about its mean, per axis.
struct Moments
{
  double sum = 0.0;
  double meanX = 0.0, meanY = 0.0;
  double varX = 0.0, varY = 0.0, covXY = 0.0;
};

Moments moments(const Heightfield& hf)
{
  Moments m;
  for (int j = 0; j < hf.height; ++j)
  {
    for (int i = 0; i < hf.width; ++i)
    {
      const double v = hf.at(i, j);
      m.sum += v;
      m.meanX += v * i;
      m.meanY += v * j;
    }
  }
  m.meanX /= m.sum;
  m.meanY /= m.sum;
  for (int j = 0; j < hf.height; ++j)
  {
    for (int i = 0; i < hf.width; ++i)
    {
      const double v = hf.at(i, j) / m.sum;
      m.varX += v * (i - m.meanX) * (i - m.meanX);
      m.varY += v * (j - m.meanY) * (j - m.meanY);
      m.covXY += v * (i - m.meanX) * (j - m.meanY);
    }
  }
  return m;
}

double rms(const Heightfield& a, const Heightfield& b, int margin)
{
  double s = 0.0;
  double n = 0.0;
  for (int j = margin; j < a.height - margin; ++j)
  {
    for (int i = margin; i < a.width - margin; ++i)
    {
      const double d = a.at(i, j) - b.at(i, j);
      s += d * d;
      n += 1.0;
    }
  }
  return std::sqrt(s / n);
}

// The impulse response of smoothLarge at sigma, on a grid wide enough that no
// cell the kernel reaches has its weights renormalised by an edge.
Heightfield impulseResponse(double sigma)
{
  // Three boxes of odd widths near 2 sigma reach at most 3 sigma + 3 cells; a
  // cell that far out must itself be that far from the edge.
  const int side = 2 * (2 * static_cast<int>(std::ceil(3.0 * sigma + 3.0))) + 1;
  Heightfield delta(side, side, 0.0f);
  delta.at(side / 2, side / 2) = 1.0f;
  return smoothLarge(delta, sigma);
}

} // namespace

TEST(SmoothLarge, ADeltaSpreadsWithTheGaussianVariance)
{
  // Odd box widths cannot add up to every variance: three boxes of widths w
  // have variance sum (w^2 - 1) / 12, and the best choice of widths lower and
  // lower + 2 misses sigma^2 by up to (lower + 1) / 6, lower <= 2 sigma: a
  // relative error up to 1 / (3 sigma) + 1 / (6 sigma^2) (8.3% at sigma 4, as
  // the widths 7, 7, 9 give; 3.3% at 10; 0.8% at 40).
  for (double sigma : { 4.0, 10.0, 40.0 })
  {
    const Heightfield r = impulseResponse(sigma);
    const Moments m = moments(r);
    const double centre = r.width / 2;
    EXPECT_NEAR(m.sum, 1.0, 1e-5) << sigma;
    EXPECT_NEAR(m.meanX, centre, 1e-6) << sigma;
    EXPECT_NEAR(m.meanY, centre, 1e-6) << sigma;
    EXPECT_NEAR(m.covXY, 0.0, 1e-6 * sigma * sigma) << sigma;
    const double bound = 1.0 / (3.0 * sigma) + 1.0 / (6.0 * sigma * sigma);
    EXPECT_NEAR(m.varX / (sigma * sigma), 1.0, bound) << sigma;
    EXPECT_NEAR(m.varY / (sigma * sigma), 1.0, bound) << sigma;
    EXPECT_NEAR(m.varX, m.varY, 1e-6 * sigma * sigma) << sigma;
    std::printf("sigma %.0f: variance %.3f of %.0f (%.2f%%)\n",
      sigma,
      m.varX,
      sigma * sigma,
      100.0 * (m.varX / (sigma * sigma) - 1.0));
  }
  // Exact values: sigma 4 -> widths 7, 7, 9; sigma 10 -> 19, 19, 21; sigma 40 -> 79, 79, 81.
  EXPECT_NEAR(moments(impulseResponse(4.0)).varX, (48.0 + 48.0 + 80.0) / 12.0, 1e-5);
  EXPECT_NEAR(moments(impulseResponse(10.0)).varX, (360.0 + 360.0 + 440.0) / 12.0, 1e-4);
  EXPECT_NEAR(moments(impulseResponse(40.0)).varX, (6240.0 + 6240.0 + 6560.0) / 12.0, 1e-3);
  // A bell, not a box: the impulse response falls monotonically from the centre
  // and vanishes past the three radii (3 + 3 + 4 cells at sigma 4).
  const Heightfield r = impulseResponse(4.0);
  const int c = r.width / 2;
  for (int i = c; i + 1 < r.width; ++i)
  {
    EXPECT_LE(r.at(i + 1, c), r.at(i, c)) << i;
  }
  EXPECT_GT(r.at(c + 10, c), 0.0f);
  EXPECT_EQ(r.at(c + 11, c), 0.0f);
}

TEST(SmoothLarge, ConstantStaysConstantAndNodataNeverLeaks)
{
  constexpr int kW = 90;
  constexpr int kH = 70;
  constexpr float kLevel = 1234.5f;
  // Nodata: a block touching the west edge, a hole in the middle, scattered cells.
  auto withNodata = [](Heightfield hf, float fill)
  {
    hf.valid.assign(hf.size(), 1);
    for (int j = 0; j < hf.height; ++j)
    {
      for (int i = 0; i < hf.width; ++i)
      {
        const bool block = i < 12 && j > 40;
        const bool hole = std::abs(i - 50) < 6 && std::abs(j - 30) < 4;
        const bool scattered = (i * 7 + j * 13) % 29 == 0;
        if (block || hole || scattered)
        {
          hf.valid[hf.index(i, j)] = 0;
          hf.at(i, j) = fill;
        }
      }
    }
    return hf;
  };
  const float kNaN = std::numeric_limits<float>::quiet_NaN();
  for (double sigma : { 3.0, 15.0, 60.0 })
  {
    const Heightfield flat = smoothLarge(withNodata(Heightfield(kW, kH, kLevel), kNaN), sigma);
    for (std::size_t k = 0; k < flat.size(); ++k)
    {
      if (flat.isValid(k))
      {
        ASSERT_NEAR(flat.z[k], kLevel, 1e-3) << "sigma " << sigma << ", cell " << k;
      }
      else
      {
        ASSERT_TRUE(std::isnan(flat.z[k])) << "invalid cells stay as they were";
      }
    }
  }
  // A rough field: what the invalid cells hold never changes a valid cell.
  Heightfield rough(kW, kH);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 500.0f);
  for (float& z : rough.z)
  {
    z = u(rng);
  }
  const Heightfield a = smoothLarge(withNodata(rough, kNaN), 8.0);
  const Heightfield b = smoothLarge(withNodata(rough, 1e30f), 8.0);
  const Heightfield c = smoothLarge(withNodata(rough, -7.0f), 8.0);
  ASSERT_EQ(a.valid, withNodata(rough, 0.0f).valid);
  for (std::size_t k = 0; k < a.size(); ++k)
  {
    if (a.isValid(k))
    {
      ASSERT_EQ(a.z[k], b.z[k]) << k;
      ASSERT_EQ(a.z[k], c.z[k]) << k;
    }
    else
    {
      EXPECT_TRUE(std::isnan(a.z[k]));
      EXPECT_EQ(b.z[k], 1e30f);
      EXPECT_EQ(c.z[k], -7.0f);
    }
  }
  // sigma 0: the input.
  EXPECT_EQ(smoothLarge(rough, 0.0).z, rough.z);
}

TEST(SmoothLarge, CloseToTheGaussianOnARealDem)
{
  const Heightfield dem = readHeightfield((test::bundledData() / "dems" / "colorado.png").string());
  Heightfield crop(240, 200);
  for (int j = 0; j < crop.height; ++j)
  {
    for (int i = 0; i < crop.width; ++i)
    {
      crop.at(i, j) = dem.at(200 + i, 150 + j);
    }
  }
  // The yardstick: how far the Gaussian moves when its sigma grows by 5%.
  // smoothLarge's variance is within 8.3% of sigma^2 (sigma within 4.2%) and
  // its bell is not quite Gaussian, so inside (3 sigma from the edges) it must
  // be nearer the Gaussian than that, by a margin: measured 0.48 (sigma 4) and
  // 0.53 (sigma 16) of the yardstick, bound 0.75. At the edges both renormalise
  // what is left of the kernel, but the halves of two bells differ in their
  // centroid, which on this DEM's slopes costs up to 7.5% of what the
  // smoothing changes (bound 10%).
  for (double sigma : { 4.0, 16.0 })
  {
    const Heightfield fast = smoothLarge(crop, sigma);
    const Heightfield exact = gaussianSmooth(crop, sigma);
    const Heightfield wider = gaussianSmooth(crop, 1.05 * sigma);
    const int margin = static_cast<int>(std::ceil(3 * sigma));
    const double change = rms(exact, crop, margin);
    const double yardstick = rms(wider, exact, margin);
    const double off = rms(fast, exact, margin);
    const double edges = rms(fast, exact, 0);
    std::printf("sigma %.0f: smoothing changes %.2f m rms, 5%% more sigma %.2f m; the boxes "
                "differ from the Gaussian by %.2f m inside, %.2f m with the edges\n",
      sigma,
      change,
      yardstick,
      off,
      edges);
    EXPECT_LT(off, 0.75 * yardstick) << sigma;
    EXPECT_LT(edges, 0.1 * rms(exact, crop, 0)) << sigma;
  }
}
