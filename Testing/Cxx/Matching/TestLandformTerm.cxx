// Tests of Kernels/Matching/LandformTerm.cxx.
// Where the landform term samples a window and what it compares there: the
// exemplar through a low-pass that keeps landforms, drops detail and keeps
// nodata out.
#include "Matching/LandformTerm.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

using namespace tsynth;

TEST(LandformTerm, SamplesSpreadEvenlyAcrossThePatchAndSitOnBlockCentres)
{
  // 80-cell patches, cell by cell: a fifth of a patch apart, centred.
  std::vector<int> cells;
  for (int k = 0; k < kLandformSide; ++k)
  {
    cells.push_back(landformCell(k, 80, 1));
  }
  EXPECT_EQ(cells, std::vector<int>({ 8, 24, 40, 56, 72 }));
  // Read from 4-cell block means, the samples are the centres of the blocks that hold them.
  for (int k = 0; k < kLandformSide; ++k)
  {
    const int c = landformCell(k, 80, 4);
    EXPECT_EQ(c % 4, 2) << "sample " << k;
    EXPECT_LE(std::abs(c - cells[static_cast<std::size_t>(k)]), 2) << "sample " << k;
  }
  // Every patch size: inside the patch, in order, symmetric within a cell.
  for (int p = 16; p <= 512; p += 4)
  {
    for (int k = 0; k < kLandformSide; ++k)
    {
      const int c = landformCell(k, p, 1);
      EXPECT_GE(c, 0);
      EXPECT_LT(c, p);
      if (k > 0)
      {
        EXPECT_GT(c, landformCell(k - 1, p, 1));
      }
      EXPECT_LE(std::abs(c + landformCell(kLandformSide - 1 - k, p, 1) - (p - 1)), 1)
        << "patch " << p << ", sample " << k;
    }
  }
}

TEST(LandformTerm, TheLowPassKeepsLandformsDropsDetailAndKeepsNodataOut)
{
  const int patch = 40; // sigma 8 cells
  Heightfield ex(160, 160);
  std::mt19937 rng(5);
  std::normal_distribution<float> detail(0.0f, 10.0f);
  for (int j = 0; j < ex.height; ++j)
  {
    for (int i = 0; i < ex.width; ++i)
    {
      // A ridge a few patches wide, and cell-scale detail.
      ex.at(i, j) =
        static_cast<float>(500.0 * std::exp(-std::pow((i - 80) / 40.0, 2))) + detail(rng);
    }
  }
  for (int j = 60; j < 70; ++j)
  {
    for (int i = 20; i < 30; ++i)
    {
      ex.at(i, j) = std::numeric_limits<float>::quiet_NaN();
    }
  }
  normaliseMask(ex);
  const Heightfield low = landformImage(ex, patch);
  ASSERT_EQ(low.width, ex.width);
  // The ridge stays: crest against flank as before, within a few per cent.
  const double rise = low.at(80, 100) - low.at(20, 100);
  EXPECT_NEAR(rise, 500.0 * (1.0 - std::exp(-2.25)), 0.05 * 500.0);
  // The detail goes: what is left of it, crest row to crest row, is far below its 10 m.
  double residual = 0.0;
  int n = 0;
  for (int j = 30; j < 130; ++j)
  {
    residual += std::pow(low.at(80, j) - low.at(80, j + 1), 2);
    ++n;
  }
  EXPECT_LT(std::sqrt(residual / n), 1.0);
  // Nodata stays invalid and never becomes a height.
  EXPECT_FALSE(low.isValid(25, 65));
  EXPECT_TRUE(low.isValid(35, 65));
  EXPECT_TRUE(std::isfinite(low.at(35, 65)));
}

TEST(LandformTerm, AQueryWithoutWeightIsEmpty)
{
  LandformQuery q;
  EXPECT_TRUE(q.empty());
  q.heights.fill(100.0f); // heights alone are no opinion
  EXPECT_TRUE(q.empty());
  q.weights[12] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_TRUE(q.empty());
  q.weights[12] = 0.25f;
  EXPECT_FALSE(q.empty());
}
