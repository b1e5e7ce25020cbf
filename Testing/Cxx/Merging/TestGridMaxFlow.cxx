// Tests of Kernels/Merging/GridMaxFlow.cxx: the max flow of small grids equals
// their minimum cut found by trying every partition of the nodes, and the
// source side returned is a cut of that capacity.
#include "Merging/GridMaxFlow.h"

#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

using namespace tsynth;

namespace
{

// A graph-cut problem on a width x height grid with whole-number capacities
// (sums are exact in double).
struct GridProblem
{
  int width = 0;
  int height = 0;
  std::vector<double> toSource, toSink; // per node
  std::vector<double> right, left;      // edge to the +x neighbour: forward, backward
  std::vector<double> up, down;         // edge to the +y neighbour: forward, backward

  int nodes() const { return width * height; }
  std::size_t at(int i, int j) const { return static_cast<std::size_t>(j * width + i); }

  // The capacity of the cut whose source side is `source` (bit k: node k).
  double cut(std::uint32_t source) const
  {
    auto onSource = [&](int i, int j) { return ((source >> (j * width + i)) & 1u) != 0; };
    double c = 0.0;
    for (int j = 0; j < height; ++j)
    {
      for (int i = 0; i < width; ++i)
      {
        const std::size_t k = at(i, j);
        c += onSource(i, j) ? toSink[k] : toSource[k];
        if (i + 1 < width && onSource(i, j) != onSource(i + 1, j))
        {
          c += onSource(i, j) ? right[k] : left[k];
        }
        if (j + 1 < height && onSource(i, j) != onSource(i, j + 1))
        {
          c += onSource(i, j) ? up[k] : down[k];
        }
      }
    }
    return c;
  }

  double minimumCut() const
  {
    double best = std::numeric_limits<double>::infinity();
    for (std::uint32_t s = 0; s < (1u << nodes()); ++s)
    {
      best = std::min(best, cut(s));
    }
    return best;
  }

  // Solves it with `flow` (reset to this grid first); returns the flow and
  // the source side as bits.
  double solve(GridMaxFlow& flow, std::uint32_t& source) const
  {
    flow.reset(width, height);
    for (int j = 0; j < height; ++j)
    {
      for (int i = 0; i < width; ++i)
      {
        const std::size_t k = at(i, j);
        const int n = static_cast<int>(k);
        flow.addTerminal(n, toSource[k], toSink[k]);
        if (i + 1 < width)
        {
          flow.setEdge(n, GridMaxFlow::PlusX, right[k], left[k]);
        }
        if (j + 1 < height)
        {
          flow.setEdge(n, GridMaxFlow::PlusY, up[k], down[k]);
        }
      }
    }
    const double value = flow.solve();
    source = 0;
    for (int k = 0; k < nodes(); ++k)
    {
      source |= flow.sourceSide(k) ? (1u << k) : 0u;
    }
    return value;
  }
};

GridProblem randomProblem(int width, int height, std::mt19937& rng)
{
  std::uniform_int_distribution<int> capacity(0, 9);
  auto values = [&]
  {
    std::vector<double> v(static_cast<std::size_t>(width * height));
    for (double& x : v)
    {
      x = capacity(rng);
    }
    return v;
  };
  GridProblem p;
  p.width = width;
  p.height = height;
  p.toSource = values();
  p.toSink = values();
  p.right = values();
  p.left = values();
  p.up = values();
  p.down = values();
  return p;
}

} // namespace

TEST(GridMaxFlow, TheFlowIsTheMinimumCutOfEveryPartition)
{
  std::mt19937 rng(2004); // Boykov and Kolmogorov's year
  GridMaxFlow flow;       // one solver for every problem: its buffers are reused
  const int sizes[][2] = { { 3, 3 }, { 4, 2 }, { 2, 5 }, { 1, 6 }, { 4, 4 } };
  int problems = 0;
  for (const auto& size : sizes)
  {
    for (int trial = 0; trial < 12; ++trial)
    {
      const GridProblem p = randomProblem(size[0], size[1], rng);
      std::uint32_t source = 0;
      const double value = p.solve(flow, source);
      EXPECT_EQ(value, p.minimumCut()) << size[0] << " x " << size[1] << ", trial " << trial;
      // The source side it gives is a minimum cut.
      EXPECT_EQ(p.cut(source), value) << size[0] << " x " << size[1] << ", trial " << trial;
      ++problems;
    }
  }
  EXPECT_EQ(problems, 60);
}

TEST(GridMaxFlow, AChainIsCutAtItsWeakestLink)
{
  // Source -> node 0 -> ... -> node 4 -> sink along a row, links 7, 3, 5, 2, 6
  // forward (nothing back): the flow is the weakest, 2, between nodes 3 and 4.
  GridProblem p;
  p.width = 5;
  p.height = 1;
  p.toSource = { 100, 0, 0, 0, 0 };
  p.toSink = { 0, 0, 0, 0, 100 };
  p.right = { 7, 3, 5, 2, 0 };
  p.left.assign(5, 0.0);
  p.up.assign(5, 0.0);
  p.down.assign(5, 0.0);
  GridMaxFlow flow;
  std::uint32_t source = 0;
  EXPECT_EQ(p.solve(flow, source), 2.0);
  // The source side is what the source still reaches: nodes 0 to 3.
  EXPECT_EQ(source, 0b01111u);
  EXPECT_EQ(flow.width(), 5);
  EXPECT_EQ(flow.height(), 1);
}
