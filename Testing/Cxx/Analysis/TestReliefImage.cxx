// Tests of Kernels/Analysis/ReliefImage.cxx.
#include "Analysis/Hillshade.h"
#include "Analysis/ReliefImage.h"

#include <gtest/gtest.h>

#include <limits>

TEST(ReliefImage, TopRowIsNorthAndNodataIsGrey)
{
  tsynth::Heightfield hf(2, 2);
  hf.at(0, 0) = 0.0f; // south-west: lowest
  hf.at(1, 0) = 0.0f;
  hf.at(0, 1) = 100.0f; // north-west: highest
  hf.at(1, 1) = std::numeric_limits<float>::quiet_NaN();
  tsynth::normaliseMask(hf);
  tsynth::HillshadeOptions o;
  const auto rgb = tsynth::renderRelief(hf, tsynth::computeHillshade(hf, o));
  ASSERT_EQ(rgb.size(), 12u);
  // Pixel (row 0, col 0) is grid (0, 1), the highest: near-white snow tint, brighter than the low
  // pixel.
  EXPECT_GT(rgb[0] + rgb[1] + rgb[2], rgb[6] + rgb[7] + rgb[8]);
  // Pixel (row 0, col 1) is the nodata cell.
  EXPECT_EQ(rgb[3], 140);
  EXPECT_EQ(rgb[4], 153);
  EXPECT_EQ(rgb[5], 173);
}
