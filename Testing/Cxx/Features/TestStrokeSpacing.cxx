// Tests of Kernels/Features/StrokeSpacing.cxx: how far apart the strokes of a sketch are.
#include "Core/Error.h"
#include "Features/FeatureGraph.h"
#include "Features/StrokeSpacing.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <queue>
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

namespace
{

FeatureChain straight(int from, int to, Point2 a, Point2 b)
{
  FeatureChain c;
  c.from = from;
  c.to = to;
  const int n = static_cast<int>(std::ceil(std::hypot(b.x - a.x, b.y - a.y)));
  for (int k = 0; k <= n; ++k)
  {
    const double t = static_cast<double>(k) / n;
    c.points.push_back({ a.x + t * (b.x - a.x), a.y + t * (b.y - a.y) });
  }
  return c;
}

// A T (a bar 100 cells long, a stem of 50 joined at node 1) and a dash of 30
// cells far off, on a 200 x 120 grid.
FeatureGraph aTAndADash()
{
  FeatureGraph g;
  g.width = 200;
  g.height = 120;
  g.nodes.resize(5);
  g.chains.push_back(straight(0, 1, { 10, 100 }, { 60, 100 }));
  g.chains.push_back(straight(1, 2, { 60, 100 }, { 110, 100 }));
  g.chains.push_back(straight(1, 3, { 60, 100 }, { 60, 50 }));
  g.chains.push_back(straight(4, -1, { 160, 20 }, { 190, 20 }));
  return g;
}

} // namespace

TEST(StrokeSpacing, EachCellKnowsTheLengthOfItsNearestConnectedStrokes)
{
  const FeatureGraph g = aTAndADash();
  const double cellX = 2.0, cellY = 3.0; // metres
  const std::vector<float> length = nearestStrokeLength(g, cellX, cellY);
  auto at = [&](int i, int j) { return length[static_cast<std::size_t>(j * g.width + i)]; };
  const double tMetres = 100.0 * cellX + 50.0 * cellY;
  EXPECT_NEAR(at(60, 100), tMetres, 1e-3) << "on the junction";
  EXPECT_NEAR(at(62, 60), tMetres, 1e-3) << "beside the stem: the whole T, not the stem";
  EXPECT_NEAR(at(30, 110), tMetres, 1e-3) << "above the bar";
  EXPECT_NEAR(at(170, 30), 30.0 * cellX, 1e-3) << "beside the dash";
  EXPECT_NEAR(at(140, 10), 30.0 * cellX, 1e-3) << "nearer the dash than the T";
  EXPECT_NEAR(at(100, 70), tMetres, 1e-3) << "nearer the T than the dash";
  FeatureGraph empty;
  empty.width = 8;
  empty.height = 8;
  const std::vector<float> none = nearestStrokeLength(empty, 1.0, 1.0);
  ASSERT_EQ(none.size(), 64u);
  EXPECT_TRUE(std::isinf(none[0]));
}

TEST(StrokeSpacing, AShortStrokesRoomIsAShareOfItsLength)
{
  const FeatureGraph g = aTAndADash();
  StrokeSpacing s = strokeSpacing(rasteriseChains(g, g.width, g.height), g.width, g.height);
  const float beforeT = at(s, 30, 110);
  ASSERT_GT(beforeT, 150.0 / kStrokeLengthPerHalfWidth) << "the drawing leaves the bar more";
  limitByStrokeLength(s, g, 1.0, 1.0);
  EXPECT_NEAR(at(s, 30, 110), 150.0 / kStrokeLengthPerHalfWidth, 1e-3);
  EXPECT_NEAR(at(s, 175, 5), 30.0 / kStrokeLengthPerHalfWidth, 1e-3);
  // Room the drawing already narrowed stays: two strokes 120 cells long
  // (room 20 by their length) drawn 10 cells apart have 5 each.
  FeatureGraph pair;
  pair.width = 140;
  pair.height = 40;
  pair.nodes.resize(4);
  pair.chains.push_back(straight(0, 1, { 10, 15 }, { 130, 15 }));
  pair.chains.push_back(straight(2, 3, { 10, 25 }, { 130, 25 }));
  StrokeSpacing narrow =
    strokeSpacing(rasteriseChains(pair, pair.width, pair.height), pair.width, pair.height);
  const float between = at(narrow, 70, 20);
  ASSERT_NEAR(between, 5.0, 1.0);
  limitByStrokeLength(narrow, pair, 1.0, 1.0);
  EXPECT_EQ(at(narrow, 70, 20), between);
  EXPECT_NEAR(at(narrow, 70, 35), 120.0 / kStrokeLengthPerHalfWidth, 1e-3) << "the open side";
  StrokeSpacing other = strokeSpacing(rasteriseChains(g, 100, 100), 100, 100);
  EXPECT_THROW(limitByStrokeLength(other, g, 1.0, 1.0), Error);
  EXPECT_THROW(limitByStrokeLength(other, nearestStrokeLength(g, 1.0, 1.0)), Error);
}

TEST(StrokeSpacing, LengthsReadOnceLimitAsTheLinesDo)
{
  const FeatureGraph g = aTAndADash();
  const double cellX = 2.0, cellY = 3.0;
  StrokeSpacing fromLines =
    strokeSpacing(rasteriseChains(g, g.width, g.height), g.width, g.height, cellX, cellY);
  StrokeSpacing fromLengths = fromLines;
  limitByStrokeLength(fromLines, g, cellX, cellY);
  limitByStrokeLength(fromLengths, nearestStrokeLength(g, cellX, cellY));
  EXPECT_EQ(fromLengths.halfSpacing, fromLines.halfSpacing);
  EXPECT_NEAR(at(fromLengths, 170, 30), 30.0 * cellX / kStrokeLengthPerHalfWidth, 1e-3);
}

namespace
{

// Metres to the nearest medial cell over the same graph as strokeSpacing's
// (8-connected, stroke cells reached but passing nothing on, no diagonal
// between two stroke cells touching at a corner; each step's sum rounded to
// float), by Dijkstra's search: the least of those sums over every path,
// whatever order a method relaxes the cells in.
std::vector<float> dijkstraToMedial(const std::vector<std::uint8_t>& strokes,
  const std::vector<std::uint8_t>& medial,
  int w,
  int h,
  double cx,
  double cy)
{
  const float inf = std::numeric_limits<float>::infinity();
  std::vector<float> d(strokes.size(), inf);
  using Entry = std::pair<float, std::size_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
  for (std::size_t k = 0; k < d.size(); ++k)
  {
    if (medial[k] != 0 && strokes[k] == 0)
    {
      d[k] = 0.0f;
      open.emplace(0.0f, k);
    }
  }
  const auto index = [w](int i, int j) { return static_cast<std::size_t>(j * w + i); };
  while (!open.empty())
  {
    const auto [dm, m] = open.top();
    open.pop();
    if (dm > d[m] || strokes[m] != 0)
    {
      continue; // stale, or a wall
    }
    const int x = static_cast<int>(m) % w;
    const int y = static_cast<int>(m) / w;
    for (int dj = -1; dj <= 1; ++dj)
    {
      for (int di = -1; di <= 1; ++di)
      {
        const int i = x + di;
        const int j = y + dj;
        if ((di == 0 && dj == 0) || i < 0 || j < 0 || i >= w || j >= h)
        {
          continue;
        }
        const bool diagonal = di != 0 && dj != 0;
        if (diagonal && strokes[index(x, j)] != 0 && strokes[index(i, y)] != 0)
        {
          continue;
        }
        const double step = std::hypot(di * cx, dj * cy);
        const float next = static_cast<float>(d[m] + step);
        if (next < d[index(i, j)])
        {
          d[index(i, j)] = next;
          open.emplace(next, index(i, j));
        }
      }
    }
  }
  return d;
}

} // namespace

// The medial distance is found by raster sweeps until nothing changes: on a
// spiral (a path round it turns many times), crossing strokes and strokes
// touching at corners, on cells longer than they are wide, every cell's half
// spacing is the one Dijkstra's search over the same graph gives, to the bit.
TEST(StrokeSpacing, SweepsFindTheShortestPathsToTheMedialAxisToTheBit)
{
  const int w = 150, h = 130;
  const double cx = 30.0, cy = 45.0;
  const std::vector<std::uint8_t> strokes = cells(w,
    h,
    [](int i, int j)
    {
      const double dx = i - 60.0, dy = j - 60.0;
      const double r = std::hypot(dx, dy);
      const double turn = std::atan2(dy, dx) / (2.0 * M_PI);
      const bool spiral =
        r > 4.0 && r < 58.0 && std::abs(std::fmod(r / 9.0 - turn + 10.0, 1.0) - 0.5) < 0.06;
      const bool diagonal = i - j == 80 && i > 100; // cells touching at corners only
      const bool cross = (i == 130 && j > 20) || (j == 110 && i > 90);
      return spiral || diagonal || cross;
    });
  const StrokeSpacing s = strokeSpacing(strokes, w, h, cx, cy);
  const std::vector<float> toMedial = dijkstraToMedial(strokes, s.medial, w, h, cx, cy);
  std::size_t finite = 0;
  for (std::size_t k = 0; k < strokes.size(); ++k)
  {
    const float want = strokes[k] != 0 ? toMedial[k] : s.toStroke[k] + toMedial[k];
    ASSERT_EQ(s.halfSpacing[k], want) << "cell " << k;
    finite += std::isfinite(want) ? 1 : 0;
  }
  EXPECT_GT(finite, strokes.size() / 2); // the medial axis reaches most of the map
}
