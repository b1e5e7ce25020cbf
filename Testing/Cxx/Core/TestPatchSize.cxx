// Tests of Kernels/Core/PatchSize.cxx.
#include "Core/PatchSize.h"

#include <gtest/gtest.h>

TEST(PatchExtraction, TheWindowCornerIsTheRoundedCentreLessHalfAPatch)
{
  EXPECT_EQ(tsynth::windowCorner(50.0, 20), 40);
  EXPECT_EQ(tsynth::windowCorner(50.5, 20), 41); // halves round away from zero
  EXPECT_EQ(tsynth::windowCorner(50.49, 21), 40);
}
