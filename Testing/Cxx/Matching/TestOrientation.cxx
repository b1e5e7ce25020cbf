// Tests of Kernels/Matching/Orientation.cxx: the exemplar's turned and mirrored copies and the
// feature angles of each variant.
#include "Core/Constants.h"
#include "Matching/Orientation.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace tsynth;

TEST(Orientation, QuarterTurnsAndMirrorsAreExactCopies)
{
  Heightfield ex(5, 3);
  for (int j = 0; j < 3; ++j)
  {
    for (int i = 0; i < 5; ++i)
    {
      ex.at(i, j) = static_cast<float>(10 * j + i);
    }
  }
  for (int k : { 0, 2, 4, 6, 8, 9 })
  {
    double cu = 0.0;
    double cv = 0.0;
    const Heightfield out = orientExemplar(ex, variant(k), &cu, &cv);
    EXPECT_FALSE(out.hasMask()) << "variant " << k;
    // Exemplar offset (a, b) from its centre appears rotated by k * 45 degrees
    // (or mirrored) around the centre of the placed image.
    for (int j = 0; j < 3; ++j)
    {
      for (int i = 0; i < 5; ++i)
      {
        const double a = i - 2.0;
        const double b = j - 1.0;
        double pu = a;
        double pv = b;
        if (k < 8)
        {
          const double t = k * kPi / 4;
          pu = std::round(std::cos(t) * a - std::sin(t) * b);
          pv = std::round(std::sin(t) * a + std::cos(t) * b);
        }
        else if (k == 8)
        {
          pu = -a;
        }
        else
        {
          pv = -b;
        }
        ASSERT_EQ(out.at(static_cast<int>(cu + pu), static_cast<int>(cv + pv)), ex.at(i, j))
          << "variant " << k << " cell " << i << "," << j;
      }
    }
  }
  EXPECT_EQ(orientExemplar(ex, variant(2)).width, 3);
  EXPECT_EQ(orientExemplar(ex, variant(2)).height, 5);
  const Heightfield diagonal = orientExemplar(ex, variant(1));
  EXPECT_TRUE(diagonal.hasMask()); // corners outside the rotated exemplar
}

TEST(Orientation, FeatureAnglesFollowTheVariant)
{
  EXPECT_NEAR(variant(2).placedAngle(0.0), kPi / 2, 1e-12);
  EXPECT_NEAR(variant(1).placedAngle(0.0), kPi / 4, 1e-12);
  EXPECT_NEAR(std::abs(variant(8).placedAngle(0.0)), kPi, 1e-12);
  EXPECT_NEAR(variant(9).placedAngle(kPi / 2), -kPi / 2, 1e-12);
}
