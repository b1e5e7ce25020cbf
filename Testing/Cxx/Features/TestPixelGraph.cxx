// Tests of Kernels/Features/PixelGraph.cxx.
// The cell graph every feature line passes through: links both ways, never off
// the grid, and the three prunings (end reduction, short branches, small
// components) on shapes whose answers are known.
#include "Features/PixelGraph.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>

using namespace tsynth;

namespace
{

// Links the cells from (i0, j) east to (i1, j).
void eastRun(PixelGraph& g, int i0, int i1, int j)
{
  for (int i = i0; i < i1; ++i)
  {
    g.link(g.index(i, j), 0);
  }
}

// Links the cells from (i, j0) north to (i, j1).
void northRun(PixelGraph& g, int i, int j0, int j1)
{
  for (int j = j0; j < j1; ++j)
  {
    g.link(g.index(i, j), 2);
  }
}

// A T: a bar from (2, 10) to (22, 10) and a stem from (12, 10) down to (12, 0 + stemFrom).
PixelGraph tee(int stemFrom)
{
  PixelGraph g(30, 20);
  eastRun(g, 2, 22, 10);
  northRun(g, 12, stemFrom, 10);
  return g;
}

} // namespace

TEST(PixelGraph, LinksGoBothWaysAndNeverOffTheGrid)
{
  PixelGraph g(5, 4);
  const std::size_t c = g.index(2, 1);
  g.link(c, 1); // north-east
  EXPECT_TRUE(g.hasLink(c, 1));
  EXPECT_TRUE(g.hasLink(g.index(3, 2), PixelGraph::opposite(1)));
  EXPECT_EQ(g.degree(c), 1);
  EXPECT_EQ(g.edgeCount(), 1u);
  EXPECT_EQ(g.nodeCount(), 2u);
  EXPECT_EQ(g.neighbour(g.index(4, 0), 0), std::numeric_limits<std::size_t>::max());
  EXPECT_EQ(g.neighbour(g.index(0, 3), 3), std::numeric_limits<std::size_t>::max());
  EXPECT_EQ(g.column(g.index(3, 2)), 3);
  EXPECT_EQ(g.row(g.index(3, 2)), 2);
  g.unlink(g.index(3, 2), PixelGraph::opposite(1));
  EXPECT_EQ(g.edgeCount(), 0u);
  EXPECT_EQ(g.links(c), 0);
}

TEST(PixelGraph, EndReductionShortensEveryDanglingBranchByOneCellAPass)
{
  PixelGraph g = tee(4); // arms of 10, 10 and 6 cells from the junction
  EXPECT_EQ(g.nodeCount(), 27u);
  g.removeEndSegments(3);
  EXPECT_EQ(g.nodeCount(), 27u - 9u);
  EXPECT_TRUE(g.isForest());
}

TEST(PixelGraph, ShortBranchesGoShortestFirstAndTheJunctionStays)
{
  PixelGraph g = tee(6); // stem 4 cells below the junction
  g.pruneShortBranches(5);
  EXPECT_EQ(g.degree(g.index(12, 6)), 0) << "the stem was shorter than 5";
  EXPECT_EQ(g.degree(g.index(12, 10)), 2) << "the junction is now a bar cell";
  EXPECT_EQ(g.nodeCount(), 21u);
  // A bar alone: both of its arms are long; pruning leaves it whole.
  g.pruneShortBranches(5);
  EXPECT_EQ(g.nodeCount(), 21u);
}

TEST(PixelGraph, SmallComponentsGoAndCyclesAreSeen)
{
  PixelGraph g(30, 20);
  eastRun(g, 0, 4, 2);    // 5 cells
  eastRun(g, 10, 25, 15); // 16 cells
  g.removeSmallComponents(6);
  EXPECT_EQ(g.nodeCount(), 16u);
  EXPECT_TRUE(g.isForest());
  // A square loop.
  eastRun(g, 2, 6, 5);
  eastRun(g, 2, 6, 9);
  northRun(g, 2, 5, 9);
  northRun(g, 6, 5, 9);
  EXPECT_FALSE(g.isForest());
  g.isolate(g.index(2, 5));
  EXPECT_TRUE(g.isForest());
}
