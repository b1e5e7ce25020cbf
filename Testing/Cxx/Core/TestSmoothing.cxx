// Tests of Kernels/Core/Smoothing.cxx: large-scale smoothing against the Gaussian.
#include "Core/HeightfieldIO.h"
#include "Core/Smoothing.h"
#include "Features/Ppa.h"
#include "TestData.h"

#include <gtest/gtest.h>
#include <omp.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

using namespace tsynth;

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

TEST(SmoothLarge, BoxWidthsAreOddAndTheirVariancesAddUpToSigmaSquared)
{
  // The widths the delta above spreads with, read directly.
  EXPECT_EQ(boxWidths(4.0), (std::array<int, kBoxPasses>{ 7, 7, 9 }));
  EXPECT_EQ(boxWidths(10.0), (std::array<int, kBoxPasses>{ 19, 19, 21 }));
  EXPECT_EQ(boxWidths(40.0), (std::array<int, kBoxPasses>{ 79, 79, 81 }));
  for (double sigma = 1.0; sigma <= 400.0; sigma *= 1.07)
  {
    const std::array<int, kBoxPasses> widths = boxWidths(sigma);
    double variance = 0.0;
    for (int w : widths)
    {
      EXPECT_EQ(w % 2, 1) << sigma;
      variance += (w * w - 1.0) / 12.0;
    }
    EXPECT_LE(widths.back() - widths.front(), 2) << sigma;
    const double bound = 1.0 / (3.0 * sigma) + 1.0 / (6.0 * sigma * sigma);
    EXPECT_NEAR(variance / (sigma * sigma), 1.0, bound) << sigma;
  }
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

// The column passes run in stripes of 512 columns on all threads: a field
// three stripes wide (the last one partial), with nodata across a stripe's
// edge, smooths as its transpose does (whose columns are one stripe; the
// transpose's rows take the other pass's arithmetic, so the two agree to
// rounding, not to the bit), and to the bit on one thread and on four.
TEST(SmoothLarge, StripesOfColumnsAgreeWithTheTransposeOnAnyThreadCount)
{
  constexpr int kW = 1300;
  constexpr int kH = 61;
  Heightfield wide(kW, kH);
  wide.valid.assign(wide.size(), 1);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.0f, 800.0f);
  for (int j = 0; j < kH; ++j)
  {
    for (int i = 0; i < kW; ++i)
    {
      wide.at(i, j) = u(rng) + 0.5f * static_cast<float>(i);
      if (std::abs(i - 512) < 9 && j > 20 && j < 35)
      {
        wide.valid[wide.index(i, j)] = 0;
        wide.at(i, j) = std::numeric_limits<float>::quiet_NaN();
      }
    }
  }
  Heightfield tall(kH, kW);
  tall.valid.assign(tall.size(), 1);
  for (int j = 0; j < kH; ++j)
  {
    for (int i = 0; i < kW; ++i)
    {
      tall.at(j, i) = wide.at(i, j);
      tall.valid[tall.index(j, i)] = wide.valid[wide.index(i, j)];
    }
  }
  const int threads = omp_get_max_threads();
  for (double sigma : { 5.0, 40.0 })
  {
    const Heightfield a = smoothLarge(wide, sigma);
    const Heightfield t = smoothLarge(tall, sigma);
    double worst = 0.0;
    for (int j = 0; j < kH; ++j)
    {
      for (int i = 0; i < kW; ++i)
      {
        ASSERT_EQ(a.isValid(i, j), t.isValid(j, i));
        if (a.isValid(i, j))
        {
          worst = std::max(worst, std::abs(static_cast<double>(a.at(i, j)) - t.at(j, i)));
        }
      }
    }
    EXPECT_LT(worst, 1e-3) << "sigma " << sigma; // heights of 0 to 1450 m in float
    omp_set_num_threads(1);
    const Heightfield one = smoothLarge(wide, sigma);
    omp_set_num_threads(4);
    const Heightfield four = smoothLarge(wide, sigma);
    omp_set_num_threads(threads);
    for (std::size_t k = 0; k < a.size(); ++k)
    {
      if (a.isValid(k))
      {
        ASSERT_EQ(a.z[k], one.z[k]) << k;
        ASSERT_EQ(a.z[k], four.z[k]) << k;
      }
    }
  }
}

// Where every cell counts, the weights are not summed in a plane but taken as
// the product of a row's and a column's counts: the same numbers, to the bit,
// as the plane the general path sums (a valid mask of all ones takes it).
TEST(SmoothLarge, WeightsOfAFieldWithoutNodataAreThePlanesToTheBit)
{
  Heightfield hf(700, 333);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-200.0f, 3000.0f);
  for (float& z : hf.z)
  {
    z = u(rng);
  }
  Heightfield masked = hf;
  masked.valid.assign(masked.size(), 1);
  for (double sigma : { 1.0, 7.5, 40.0, 400.0 })
  {
    const Heightfield a = smoothLarge(hf, sigma);
    const Heightfield b = smoothLarge(masked, sigma);
    ASSERT_EQ(a.z, b.z) << "sigma " << sigma;
  }
}
