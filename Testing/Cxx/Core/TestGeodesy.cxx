// Tests of Kernels/Core/Geodesy.cxx.
#include "Core/Geodesy.h"

#include <gtest/gtest.h>

#include <cmath>

using tsynth::metresPerDegree;

TEST(Geodesy, EquatorOnWgs84)
{
  // At the equator a degree of longitude is a * pi / 180; of latitude a(1-e^2) * pi / 180.
  const auto m = metresPerDegree(0.0);
  EXPECT_NEAR(m.east, 111319.49, 0.01);
  EXPECT_NEAR(m.north, 110574.27, 0.01);
}

TEST(Geodesy, SphereHasEqualDegreesAtEquatorAndCosineShrink)
{
  const double a = 6371000.0;
  const auto eq = metresPerDegree(0.0, a, 0.0);
  const auto sixty = metresPerDegree(60.0, a, 0.0);
  EXPECT_NEAR(eq.east, eq.north, 1e-6);
  EXPECT_NEAR(sixty.east, 0.5 * eq.east, 1e-6);
  EXPECT_NEAR(sixty.north, eq.north, 1e-6);
}

TEST(Geodesy, ThreeArcSecondCellsAtMountJackson)
{
  // SRTM tile N39 W107: centre latitude 39.5; 3 arc-seconds = 1/1200 degree.
  const auto m = metresPerDegree(39.5);
  EXPECT_NEAR(m.east / 1200.0, 71.68, 0.02);
  EXPECT_NEAR(m.north / 1200.0, 92.52, 0.02);
}
