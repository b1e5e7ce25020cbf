// Tests of Kernels/Features/StrokeSpacing.cxx: how far apart the strokes of a sketch are.
#include "Features/StrokeSpacing.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

using namespace tsynth;

namespace
{

std::vector<std::uint8_t> cells(int w, int h, const std::function<bool(int, int)>& on)
{
  std::vector<std::uint8_t> c(static_cast<std::size_t>(w * h), 0);
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      c[static_cast<std::size_t>(j * w + i)] = on(i, j) ? 1 : 0;
    }
  }
  return c;
}

float at(const StrokeSpacing& s, int i, int j)
{
  return s.halfSpacing[static_cast<std::size_t>(j * s.width + i)];
}

} // namespace

TEST(StrokeSpacing, ParallelStrokesMeetHalfWayAndALoneStrokeHasRoomForever)
{
  // Two horizontal strokes 40 cells apart (rows 30 and 70), a lone one far off at row 150.
  const int w = 120, h = 180;
  const StrokeSpacing s =
    strokeSpacing(cells(w, h, [](int, int j) { return j == 30 || j == 70 || j == 150; }), w, h);
  for (int j : { 35, 50, 65 })
  {
    EXPECT_NEAR(at(s, 60, j), 20.0f, 1.0f) << "between the pair, row " << j;
  }
  EXPECT_NEAR(at(s, 60, 30), 20.0f, 1.0f); // the stroke itself: its inner side
  EXPECT_NEAR(strokeHalfSpacing(s, 60, 70), 20.0f, 1.0f);
  EXPECT_EQ(s.medial[static_cast<std::size_t>(50 * w + 60)], 1);
  // Below the pair and round the lone stroke nothing faces: the medial axis
  // between row 70 and row 150 does (40 cells each way) ...
  EXPECT_NEAR(at(s, 60, 110), 40.0f, 1.0f);
  // ... but nothing lies beyond the lone stroke or beyond the first.
  EXPECT_TRUE(std::isinf(at(s, 60, 165)));
  EXPECT_TRUE(std::isinf(at(s, 60, 10)));
}

TEST(StrokeSpacing, ARingFacesItselfAcrossItsCentreButACornerDoesNot)
{
  const int w = 121, h = 121;
  const StrokeSpacing ring = strokeSpacing(
    cells(w, h, [](int i, int j) { return std::abs(std::hypot(i - 60, j - 60) - 40.0) < 0.5; }),
    w,
    h);
  EXPECT_NEAR(at(ring, 60, 80), 40.0f, 2.0f); // inside: half the diameter
  EXPECT_TRUE(std::isinf(at(ring, 60, 115))); // outside: open
  // An L: a right-angle corner of one stroke is a bend, not two strokes.
  const StrokeSpacing corner = strokeSpacing(
    cells(w, h, [](int i, int j) { return (j == 20 && i >= 20) || (i == 20 && j >= 20); }), w, h);
  EXPECT_TRUE(std::isinf(at(corner, 50, 50)));
  EXPECT_TRUE(std::isinf(at(corner, 25, 25)));
}

TEST(StrokeSpacing, NoStrokesNoSpacing)
{
  const StrokeSpacing s = strokeSpacing(std::vector<std::uint8_t>(100, 0), 10, 10);
  for (float v : s.halfSpacing)
  {
    EXPECT_TRUE(std::isinf(v));
  }
}
