// Tests of Kernels/Core/Resample.cxx.
#include "Core/Error.h"
#include "Core/Resample.h"

#include <gtest/gtest.h>

using tsynth::Heightfield;

TEST(Resample, PlanesStayPlanesOnTheNewGrid)
{
  Heightfield hf(101, 51);
  hf.cellX = 30.0;
  hf.cellY = 30.0;
  for (int j = 0; j < hf.height; ++j)
  {
    for (int i = 0; i < hf.width; ++i)
    {
      hf.at(i, j) = static_cast<float>(2.0 * i * 30.0 + 0.5 * j * 30.0); // z = 2x + 0.5y (metres)
    }
  }
  const Heightfield r = tsynth::resampleToCellSize(hf, 90.0, 45.0);
  EXPECT_EQ(r.width, 34);  // 3000 m / 90 m + 1
  EXPECT_EQ(r.height, 34); // 1500 m / 45 m + 1
  EXPECT_DOUBLE_EQ(r.cellX, 90.0);
  for (int j = 0; j < r.height; ++j)
  {
    for (int i = 0; i < r.width; ++i)
    {
      ASSERT_NEAR(r.at(i, j), 2.0 * i * 90.0 + 0.5 * j * 45.0, 1e-2);
    }
  }
  EXPECT_THROW(tsynth::resampleToCellSize(hf, 0.0, 1.0), tsynth::Error);
}
