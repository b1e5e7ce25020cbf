// Tests of Kernels/Merging/PoissonEditing.cxx: seamless cloning and the integration of slopes.
#include "Core/Error.h"
#include "Merging/PoissonEditing.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace tsynth;

TEST(PoissonEditing, CloningAHillKeepsItsReliefAndMeetsTheBorder)
{
  // A 50 m Gaussian hill (sigma 4 cells) on a source at 0 m, cloned into a flat
  // 100 m destination inside a centred square: the hill stands 50 m over the
  // destination (its flanks are ~0 at the square's border), the border and
  // the outside keep the destination's heights.
  constexpr int kSide = 40;
  tsynth::Heightfield dst(kSide, kSide, 100.0f);
  tsynth::Heightfield src(kSide, kSide, 0.0f);
  dst.cellX = dst.cellY = src.cellX = src.cellY = 10.0;
  std::vector<std::uint8_t> mask(dst.size(), 0);
  for (int j = 0; j < kSide; ++j)
  {
    for (int i = 0; i < kSide; ++i)
    {
      const double r2 = (i - 20.0) * (i - 20.0) + (j - 20.0) * (j - 20.0);
      src.at(i, j) = static_cast<float>(50.0 * std::exp(-r2 / (2.0 * 16.0)));
      mask[dst.index(i, j)] = i >= 8 && i < 33 && j >= 8 && j < 33 ? 1 : 0;
    }
  }
  const tsynth::PoissonEditResult r = tsynth::seamlessClone(dst, src, &mask, 1e-10);
  EXPECT_EQ(r.solvedCells, 625u);
  EXPECT_EQ(r.terrain.at(5, 5), 100.0f);
  EXPECT_NEAR(r.terrain.at(20, 20), 150.0, 0.5);
  EXPECT_NEAR(r.terrain.at(9, 20), 100.0 + src.at(9, 20), 0.5); // its flank, 1.1 m up
  EXPECT_THROW(
    tsynth::seamlessClone(dst, tsynth::Heightfield(kSide, kSide + 1), &mask, 1e-10), tsynth::Error);
  const std::vector<std::uint8_t> shortMask(10, 1);
  EXPECT_THROW(tsynth::seamlessClone(dst, src, &shortMask, 1e-10), tsynth::Error);
}

TEST(PoissonEditing, IntegratingAConstantSlopeGivesAPlane)
{
  // Slope 0.05 east on 10 m cells: 0.5 m per cell, across the whole interior.
  constexpr int kSide = 32;
  tsynth::Heightfield dst(kSide, kSide);
  dst.cellX = dst.cellY = 10.0;
  std::vector<std::uint8_t> mask(dst.size(), 0);
  for (int j = 0; j < kSide; ++j)
  {
    for (int i = 0; i < kSide; ++i)
    {
      dst.at(i, j) = static_cast<float>(0.5 * i);
      const bool inside = i > 0 && j > 0 && i + 1 < kSide && j + 1 < kSide;
      mask[dst.index(i, j)] = inside ? 1 : 0;
      if (inside)
      {
        dst.at(i, j) = 0.0f; // forgotten inside: the slopes must bring it back
      }
    }
  }
  const std::vector<double> sx(dst.size(), 0.05);
  const std::vector<double> sy(dst.size(), 0.0);
  const tsynth::PoissonEditResult r = tsynth::integrateSlopes(dst, sx, sy, mask, 1e-12);
  double worst = 0.0;
  for (int j = 0; j < kSide; ++j)
  {
    for (int i = 0; i < kSide; ++i)
    {
      worst = std::max(worst, std::abs(r.terrain.at(i, j) - 0.5 * i));
    }
  }
  EXPECT_LT(worst, 1e-3);
  EXPECT_THROW(
    tsynth::integrateSlopes(dst, std::vector<double>(3), sy, mask, 1e-10), tsynth::Error);
}
