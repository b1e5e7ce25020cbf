// Tests of Kernels/Optimisation/Pyramid.cxx.
// Each level halves the last after a binomial blur: sizes, the weights of one
// cell, planes kept, nodata kept out and marked.
#include "Optimisation/Pyramid.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace tsynth;
using namespace tsynth::optim;

TEST(Pyramid, LevelsHalveRoundingUp)
{
  EXPECT_EQ(levelSide(101, 0), 101);
  EXPECT_EQ(levelSide(101, 1), 51);
  EXPECT_EQ(levelSide(101, 2), 26);
  EXPECT_EQ(levelSide(101, 3), 13);
  EXPECT_EQ(levelSide(1, 4), 1);
  Heightfield hf(37, 20, 5.0f);
  hf.cellX = hf.cellY = 10.0;
  const std::vector<Heightfield> p = gaussianPyramid(hf, 3);
  ASSERT_EQ(p.size(), 4u);
  for (int k = 0; k < 4; ++k)
  {
    const Heightfield& l = p[static_cast<std::size_t>(k)];
    EXPECT_EQ(l.width, levelSide(37, k));
    EXPECT_EQ(l.height, levelSide(20, k));
    EXPECT_DOUBLE_EQ(l.cellX, 10.0 * std::pow(2.0, k));
  }
}

TEST(Pyramid, ACoarseCellIsTheBinomialAverageAroundItsFineCell)
{
  // One raised fine cell at (8, 6): coarse cell (4, 3) sees it with weight (6/16)^2.
  Heightfield fine(16, 12, 0.0f);
  fine.at(8, 6) = 256.0f;
  const Heightfield coarse = downsampleHalf(fine);
  EXPECT_FLOAT_EQ(coarse.at(4, 3), 256.0f * 36.0f / 256.0f);
  // Its neighbour (5, 3) is centred on (10, 6): two cells away, weight 1/16 * 6/16.
  EXPECT_FLOAT_EQ(coarse.at(5, 3), 256.0f * 6.0f / 256.0f);
  EXPECT_FLOAT_EQ(coarse.at(6, 3), 0.0f);
}

TEST(Pyramid, APlaneStaysAPlaneInside)
{
  Heightfield fine(21, 17);
  for (int j = 0; j < fine.height; ++j)
  {
    for (int i = 0; i < fine.width; ++i)
    {
      fine.at(i, j) = static_cast<float>(3.0 * i - 2.0 * j + 100.0);
    }
  }
  const Heightfield coarse = downsampleHalf(fine);
  // Inside, the symmetric blur keeps the plane at the fine cell under each coarse cell.
  for (int j = 1; j + 1 < coarse.height; ++j)
  {
    for (int i = 1; i + 1 < coarse.width; ++i)
    {
      EXPECT_NEAR(coarse.at(i, j), 3.0 * 2 * i - 2.0 * 2 * j + 100.0, 1e-3);
    }
  }
}

TEST(Pyramid, NodataNeverEntersAndMarksItsCoarseCells)
{
  Heightfield fine(16, 16, 50.0f);
  fine.at(5, 5) = std::numeric_limits<float>::quiet_NaN();
  normaliseMask(fine);
  const Heightfield coarse = downsampleHalf(fine);
  EXPECT_FALSE(coarse.isValid(2, 2)) << "its 2x2 block holds the nodata cell";
  EXPECT_TRUE(std::isnan(coarse.at(2, 2)));
  // (3, 3) is centred on (6, 6) and its blur reaches (5, 5): renormalised, still 50.
  EXPECT_TRUE(coarse.isValid(3, 3));
  EXPECT_FLOAT_EQ(coarse.at(3, 3), 50.0f);
}
