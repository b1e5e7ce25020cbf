// Tests of Kernels/Synthesis/SeamLines.cxx.
// Seams as poly-lines: every border between two patches is drawn once, along cell borders,
// and the lines break only where seams end or meet.
#include "Core/Error.h"
#include "Core/Random.h"
#include "Synthesis/SeamLines.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <map>
#include <set>
#include <tuple>
#include <vector>

namespace
{

using tsynth::CellCorner;
using tsynth::SeamLine;

// An edge between two neighbouring corners, smaller corner first.
using Edge = std::tuple<int, int, int, int>;

Edge edgeOf(CellCorner a, CellCorner b)
{
  if (std::tie(a.j, a.i) > std::tie(b.j, b.i))
  {
    std::swap(a, b);
  }
  return { a.i, a.j, b.i, b.j };
}

// The borders between different patches, found cell pair by cell pair.
std::set<Edge> bordersByBruteForce(const std::vector<int>& id, int w, int h)
{
  std::set<Edge> edges;
  auto at = [&](int i, int j) { return id[static_cast<std::size_t>(j * w + i)]; };
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      if (i + 1 < w && at(i, j) >= 0 && at(i + 1, j) >= 0 && at(i, j) != at(i + 1, j))
      {
        edges.insert(edgeOf({ i + 1, j }, { i + 1, j + 1 }));
      }
      if (j + 1 < h && at(i, j) >= 0 && at(i, j + 1) >= 0 && at(i, j) != at(i, j + 1))
      {
        edges.insert(edgeOf({ i, j + 1 }, { i + 1, j + 1 }));
      }
    }
  }
  return edges;
}

// The edges the lines draw; fails on a step that is not one cell border, or an edge drawn twice.
std::set<Edge> drawnEdges(const std::vector<SeamLine>& lines)
{
  std::set<Edge> edges;
  for (const SeamLine& line : lines)
  {
    EXPECT_GE(line.size(), 2U);
    for (std::size_t k = 1; k < line.size(); ++k)
    {
      EXPECT_EQ(std::abs(line[k].i - line[k - 1].i) + std::abs(line[k].j - line[k - 1].j), 1);
      EXPECT_TRUE(edges.insert(edgeOf(line[k - 1], line[k])).second) << "an edge drawn twice";
    }
  }
  return edges;
}

std::vector<int> voronoiMap(int w, int h, int sites)
{
  std::vector<double> x;
  std::vector<double> y;
  for (int s = 0; s < sites; ++s)
  {
    x.push_back(
      tsynth::seededUniform(3, tsynth::kStreamSites, static_cast<std::uint64_t>(2 * s)) * w);
    y.push_back(
      tsynth::seededUniform(3, tsynth::kStreamSites, static_cast<std::uint64_t>(2 * s + 1)) * h);
  }
  std::vector<int> id(static_cast<std::size_t>(w * h), -1);
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      double best = 1e30;
      for (int s = 0; s < sites; ++s)
      {
        const double d = (i - x[s]) * (i - x[s]) + (j - y[s]) * (j - y[s]);
        if (d < best)
        {
          best = d;
          id[static_cast<std::size_t>(j * w + i)] = s;
        }
      }
    }
  }
  for (int j = 10; j < 20; ++j) // a hole no placement wrote
  {
    for (int i = 10; i < 20; ++i)
    {
      id[static_cast<std::size_t>(j * w + i)] = -1;
    }
  }
  return id;
}

} // namespace

TEST(SeamLines, TwoHalvesMeetAlongOneStraightLine)
{
  const int w = 6;
  const int h = 4;
  std::vector<int> id(w * h);
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      id[static_cast<std::size_t>(j * w + i)] = i < 3 ? 0 : 1;
    }
  }
  const std::vector<SeamLine> lines = tsynth::seamLines(id, w, h);
  ASSERT_EQ(lines.size(), 1U);
  ASSERT_EQ(lines[0].size(), 5U);
  for (std::size_t k = 0; k < 5; ++k)
  {
    EXPECT_EQ(lines[0][k].i, 3);
    EXPECT_EQ(lines[0][k].j, static_cast<int>(k));
  }
}

TEST(SeamLines, AnIslandPatchIsOneClosedLine)
{
  const int w = 8;
  const int h = 7;
  std::vector<int> id(w * h, 4);
  for (int j = 2; j < 5; ++j)
  {
    for (int i = 3; i < 7; ++i)
    {
      id[static_cast<std::size_t>(j * w + i)] = 9;
    }
  }
  const std::vector<SeamLine> lines = tsynth::seamLines(id, w, h);
  ASSERT_EQ(lines.size(), 1U);
  const SeamLine& loop = lines[0];
  ASSERT_EQ(loop.size(), 2U * (4 + 3) + 1); // the perimeter, and back to the start
  EXPECT_EQ(loop.front().i, loop.back().i);
  EXPECT_EQ(loop.front().j, loop.back().j);
  EXPECT_EQ(drawnEdges(lines), bordersByBruteForce(id, w, h));
}

TEST(SeamLines, ThreePatchesMeetingGiveThreeLinesEndingAtTheMeetingCorner)
{
  const int w = 6;
  const int h = 6;
  std::vector<int> id(w * h);
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      id[static_cast<std::size_t>(j * w + i)] = j >= 3 ? 2 : i < 2 ? 0 : 1;
    }
  }
  const std::vector<SeamLine> lines = tsynth::seamLines(id, w, h);
  ASSERT_EQ(lines.size(), 3U);
  for (const SeamLine& line : lines)
  {
    const bool fromMeeting = line.front().i == 2 && line.front().j == 3;
    const bool toMeeting = line.back().i == 2 && line.back().j == 3;
    EXPECT_TRUE(fromMeeting != toMeeting) << "each line has the meeting corner at one end";
  }
  EXPECT_EQ(drawnEdges(lines), bordersByBruteForce(id, w, h));
}

TEST(SeamLines, EveryBorderOfAPatchMapIsDrawnExactlyOnce)
{
  const int w = 97;
  const int h = 83;
  const std::vector<int> id = voronoiMap(w, h, 40);
  const std::vector<SeamLine> lines = tsynth::seamLines(id, w, h);
  const std::set<Edge> expected = bordersByBruteForce(id, w, h);
  EXPECT_GT(expected.size(), 500U);
  EXPECT_EQ(drawnEdges(lines), expected);
  // Lines break only where seams end or meet: an inner corner of a line has two borders.
  std::map<std::pair<int, int>, int> degree;
  for (const Edge& e : expected)
  {
    ++degree[{ std::get<0>(e), std::get<1>(e) }];
    ++degree[{ std::get<2>(e), std::get<3>(e) }];
  }
  for (const SeamLine& line : lines)
  {
    for (std::size_t k = 1; k + 1 < line.size(); ++k)
    {
      EXPECT_EQ((degree[{ line[k].i, line[k].j }]), 2);
    }
    const bool closed = line.front().i == line.back().i && line.front().j == line.back().j;
    if (!closed)
    {
      EXPECT_NE((degree[{ line.front().i, line.front().j }]), 2);
      EXPECT_NE((degree[{ line.back().i, line.back().j }]), 2);
    }
  }
  EXPECT_EQ(tsynth::seamLines(id, w, h).size(), lines.size()); // deterministic
}

TEST(SeamLines, UnwrittenCellsBorderNothingAndAWrongSizeIsRefused)
{
  EXPECT_TRUE(tsynth::seamLines(std::vector<int>(12, -1), 4, 3).empty());
  EXPECT_TRUE(tsynth::seamLines(std::vector<int>(12, 5), 4, 3).empty());
  EXPECT_THROW(tsynth::seamLines(std::vector<int>(11, 0), 4, 3), tsynth::Error);
}
