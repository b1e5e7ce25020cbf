// Tests of Kernels/Features/FeatureGraph.cxx.
// The graph operations on a hand-made graph whose answers are known: a Y of
// three ridges meeting at a branch, and a short valley apart.
#include "Core/Constants.h"
#include "Features/FeatureGraph.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <utility>
#include <vector>

using namespace tsynth;

namespace
{

// A chain of straight points from `from` to `to`, one per cell along it.
FeatureChain straightChain(int fromNode, int toNode, Point2 a, Point2 b, FeatureType type)
{
  FeatureChain c;
  c.from = fromNode;
  c.to = toNode;
  c.type = type;
  const int steps = static_cast<int>(std::ceil(std::hypot(b.x - a.x, b.y - a.y)));
  for (int k = 0; k <= steps; ++k)
  {
    const double t = static_cast<double>(k) / steps;
    c.points.push_back({ a.x + t * (b.x - a.x), a.y + t * (b.y - a.y) });
    c.elevation.push_back(100.0f);
  }
  return c;
}

// Nodes 0 (branch at (20, 20)), 1 (20, 40), 2 (4, 8), 3 (36, 8): the Y's three arms of
// lengths 20, 20 and 20; nodes 4 and 5: a valley from (50, 40) to (56, 40), apart.
FeatureGraph yAndAValley()
{
  FeatureGraph g;
  g.width = 64;
  g.height = 48;
  const Point2 at[] = { { 20, 20 }, { 20, 40 }, { 4, 8 }, { 36, 8 }, { 50, 40 }, { 56, 40 } };
  for (const Point2& p : at)
  {
    FeatureNode n;
    n.position = p;
    g.nodes.push_back(n);
  }
  g.chains.push_back(straightChain(0, 1, at[0], at[1], FeatureType::Ridge));
  g.chains.push_back(straightChain(0, 2, at[0], at[2], FeatureType::Ridge));
  g.chains.push_back(straightChain(3, 0, at[3], at[0], FeatureType::Ridge));
  g.chains.push_back(straightChain(4, 5, at[4], at[5], FeatureType::Valley));
  for (std::size_t c = 0; c < g.chains.size(); ++c)
  {
    for (int v : { g.chains[c].from, g.chains[c].to })
    {
      FeatureNode& n = byId(g.nodes, v);
      n.chains.push_back(static_cast<int>(c));
      n.degree = static_cast<int>(n.chains.size());
      n.type = g.chains[c].type;
    }
  }
  g.nodes[0].kind = NodeKind::Branch;
  return g;
}

} // namespace

TEST(FeatureGraph, ChainLengthIsTheSumOfItsSegments)
{
  FeatureChain c;
  c.points = { { 0, 0 }, { 3, 4 }, { 3, 10 } };
  EXPECT_DOUBLE_EQ(c.length(), 11.0);
}

TEST(FeatureGraph, TheLongestComponentComesFirstFromItsBranch)
{
  FeatureGraph g = yAndAValley();
  computeBreadthFirstOrder(g);
  EXPECT_EQ(g.componentCount, 2);
  ASSERT_EQ(g.bfsOrder.size(), 6u);
  EXPECT_EQ(g.bfsOrder.front(), 0) << "the Y (60 cells) walked from its branch";
  EXPECT_EQ(
    std::set<int>(g.bfsOrder.begin(), g.bfsOrder.begin() + 4), std::set<int>({ 0, 1, 2, 3 }));
  EXPECT_EQ(std::set<int>(g.bfsOrder.begin() + 4, g.bfsOrder.end()), std::set<int>({ 4, 5 }));
  EXPECT_EQ(g.nodes[3].component, g.nodes[0].component);
  EXPECT_NE(g.nodes[4].component, g.nodes[0].component);
}

TEST(FeatureGraph, ControlPointsLieWhereEachChainCrossesTheCircle)
{
  FeatureGraph g = yAndAValley();
  computeControlPoints(g, 5.0);
  const FeatureNode& branch = g.nodes[0];
  ASSERT_EQ(branch.controls.size(), 3u);
  for (const ControlPoint& cp : branch.controls)
  {
    EXPECT_TRUE(cp.reached);
    EXPECT_NEAR(std::hypot(cp.position.x - 20.0, cp.position.y - 20.0), 5.0, 1e-9);
  }
  EXPECT_NEAR(branch.controls[0].angle, 0.5 * kPi, 1e-9) << "north, up the stem";
  EXPECT_NEAR(branch.controls[1].angle, std::atan2(-12.0, -16.0), 1e-9);
  EXPECT_NEAR(branch.controls[2].angle, std::atan2(-12.0, 16.0), 1e-9) << "chain 2 ends here";
  // The valley is 6 cells long: from its ends a radius of 8 is never reached.
  computeControlPoints(g, 8.0);
  const ControlPoint& short4 = g.nodes[4].controls.at(0);
  EXPECT_FALSE(short4.reached);
  EXPECT_DOUBLE_EQ(short4.position.x, 56.0) << "the chain's far end";
}

TEST(FeatureGraph, ChainCellsAreEveryCellUnderTheLineAndNoneOffTheGrid)
{
  FeatureChain c = straightChain(0, 1, { 2, 3 }, { 8, 3 }, FeatureType::Ridge);
  std::set<std::pair<int, int>> cells;
  forEachChainCell(c, 64, 48, [&](int i, int j, std::size_t, double) { cells.insert({ i, j }); });
  std::set<std::pair<int, int>> row;
  for (int i = 2; i <= 8; ++i)
  {
    row.insert({ i, 3 });
  }
  EXPECT_EQ(cells, row);
  // Half of it off the grid's west edge.
  FeatureChain off = straightChain(0, 1, { -5, 3 }, { 2, 3 }, FeatureType::Ridge);
  cells.clear();
  forEachChainCell(off, 64, 48, [&](int i, int j, std::size_t, double) { cells.insert({ i, j }); });
  const std::set<std::pair<int, int>> onGrid = { { 0, 3 }, { 1, 3 }, { 2, 3 } };
  EXPECT_EQ(cells, onGrid);
  const std::vector<std::uint8_t> raster = rasteriseChains(yAndAValley(), 64, 48);
  EXPECT_EQ(raster[3 * 64 + 2], 0);
  EXPECT_EQ(raster[30 * 64 + 20], 1) << "on the stem";
  EXPECT_EQ(raster[40 * 64 + 53], 1) << "on the valley";
}

TEST(FeatureGraph, SmoothingMovesInteriorPointsOnlyTowardsTheirNeighbours)
{
  FeatureGraph g;
  FeatureChain zig;
  zig.points = { { 0, 0 }, { 1, 2 }, { 2, 0 }, { 3, 2 } };
  g.chains.push_back(zig);
  smoothChains(g, 1);
  const std::vector<Point2>& p = g.chains[0].points;
  EXPECT_DOUBLE_EQ(p[0].y, 0.0);
  EXPECT_DOUBLE_EQ(p[3].y, 2.0);
  EXPECT_DOUBLE_EQ(p[1].y, 0.25 * 0 + 0.5 * 2 + 0.25 * 0);
  EXPECT_DOUBLE_EQ(p[2].y, 0.25 * 2 + 0.5 * 0 + 0.25 * 2);
}

TEST(FeatureGraph, AppendingRenumbersTheSecondGraph)
{
  FeatureGraph a = yAndAValley();
  const FeatureGraph b = yAndAValley();
  appendGraph(a, b);
  ASSERT_EQ(a.nodes.size(), 12u);
  ASSERT_EQ(a.chains.size(), 8u);
  EXPECT_EQ(a.chains[4].from, 6);
  EXPECT_EQ(a.chains[4].to, 7);
  EXPECT_EQ(a.nodes[6].chains, std::vector<int>({ 4, 5, 6 }));
  EXPECT_EQ(a.componentCount, 4);
  EXPECT_EQ(a.countKind(NodeKind::Branch), 2);
  EXPECT_EQ(a.countKind(NodeKind::End, FeatureType::Valley), 4);
}

TEST(FeatureGraph, ConnectedChainSetsJoinChainsAtTheirNodes)
{
  FeatureGraph g = yAndAValley();
  // A chain whose end node is missing stands alone.
  FeatureChain loose = straightChain(0, 99, { 20, 20 }, { 30, 30 }, FeatureType::Ridge);
  loose.from = -1;
  g.chains.push_back(loose);
  std::size_t count = 0;
  const std::vector<std::size_t> sets = connectedChainSets(g, &count);
  EXPECT_EQ(count, 3u);
  EXPECT_EQ(sets, (std::vector<std::size_t>{ 0, 0, 0, 1, 2 }))
    << "the Y, the valley, the loose chain";
  EXPECT_EQ(connectedChainSets(FeatureGraph{}).size(), 0u);
}
