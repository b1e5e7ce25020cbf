// Tests of Kernels/Analysis/Hillshade.cxx.
#include "Analysis/Hillshade.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace
{

constexpr double kDeg = 3.14159265358979323846 / 180.0;

// z = a x + b y on a grid with different cell sizes in x and y.
tsynth::Heightfield plane(double a,
  double b,
  int w = 9,
  int h = 7,
  double cx = 30.0,
  double cy = 90.0)
{
  tsynth::Heightfield hf(w, h);
  hf.cellX = cx;
  hf.cellY = cy;
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      hf.at(i, j) = static_cast<float>(1000.0 + a * i * cx + b * j * cy);
    }
  }
  return hf;
}

double expectedShade(double p, double q, double azimuthDeg, double altitudeDeg)
{
  const double az = azimuthDeg * kDeg;
  const double alt = altitudeDeg * kDeg;
  const double l[3] = { std::sin(az) * std::cos(alt), std::cos(az) * std::cos(alt), std::sin(alt) };
  return std::max(0.0, (-p * l[0] - q * l[1] + l[2]) / std::sqrt(1.0 + p * p + q * q));
}

} // namespace

TEST(Hillshade, PlaneSlopeIsExactEverywhereIncludingEdges)
{
  const double a = 0.3;
  const double b = -0.4;
  const auto hf = plane(a, b);
  const auto r = tsynth::computeHillshade(hf);
  const double expected = std::atan(std::hypot(a, b)) / kDeg; // 26.565 degrees
  for (float s : r.slopeDeg)
  {
    EXPECT_NEAR(s, expected, 2e-3);
  }
}

TEST(Hillshade, SingleLightMatchesTheAnalyticNormal)
{
  const double a = 0.5;
  const double b = 0.2;
  const auto hf = plane(a, b);
  tsynth::HillshadeOptions o;
  o.multidirectional = false;
  for (double az : { 0.0, 90.0, 200.0, 315.0 })
  {
    o.azimuthDeg = az;
    o.altitudeDeg = 30.0;
    const auto r = tsynth::computeHillshade(hf, o);
    for (float s : r.shade)
    {
      EXPECT_NEAR(s, expectedShade(a, b, az, 30.0), 1e-4) << "azimuth " << az;
    }
  }
}

TEST(Hillshade, ZFactorScalesGradients)
{
  const auto hf = plane(0.1, 0.0);
  tsynth::HillshadeOptions o;
  o.zFactor = 3.0;
  const auto r = tsynth::computeHillshade(hf, o);
  EXPECT_NEAR(r.slopeDeg[0], std::atan(0.3) / kDeg, 2e-3);
}

TEST(Hillshade, MultidirectionalIsAWeightedMeanOfItsLights)
{
  // Flat ground is lit as sin(altitude) by every light.
  const auto flat = plane(0.0, 0.0);
  const auto r = tsynth::computeHillshade(flat);
  EXPECT_NEAR(r.shade[10], std::sin(45.0 * kDeg), 1e-6);
  // A slope facing east (downhill to +x): aspect 90 deg. Weights sin^2(90 - az):
  // 225 -> 0.5, 270 -> 0, 315 -> 0.5, 360 -> 1; their sum is 2.
  const auto east = plane(-0.6, 0.0);
  const auto m = tsynth::computeHillshade(east);
  const double blend =
    (0.5 * expectedShade(-0.6, 0, 225, 45) + 0.5 * expectedShade(-0.6, 0, 315, 45) +
      1.0 * expectedShade(-0.6, 0, 360, 45)) /
    2.0;
  EXPECT_NEAR(m.shade[20], blend, 1e-5);
}

TEST(Hillshade, NodataStaysOutOfNeighbours)
{
  auto hf = plane(0.2, 0.1);
  hf.valid.assign(hf.size(), 1);
  hf.valid[hf.index(4, 3)] = 0;
  hf.at(4, 3) = std::numeric_limits<float>::quiet_NaN();
  const auto r = tsynth::computeHillshade(hf);
  EXPECT_TRUE(std::isnan(r.slopeDeg[hf.index(4, 3)]));
  EXPECT_TRUE(std::isnan(r.shade[hf.index(4, 3)]));
  // The hole's neighbours still see the exact plane.
  const double expected = std::atan(std::hypot(0.2, 0.1)) / kDeg;
  EXPECT_NEAR(r.slopeDeg[hf.index(3, 3)], expected, 2e-3);
  EXPECT_NEAR(r.slopeDeg[hf.index(5, 4)], expected, 2e-3);
}
