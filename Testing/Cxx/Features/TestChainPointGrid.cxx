// Tests of Kernels/Features/ChainPointGrid.cxx.
// The chain-point grid (Features/ChainPointGrid): the points it visits near a
// spot are exactly those a walk over the whole graph finds there.
#include "Core/Random.h"
#include "Features/ChainPointGrid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

using namespace tsynth;

namespace
{

using Found = std::vector<std::pair<double, double>>;

// Chains of random points, ridges and valleys alternating, over a 300 x 200
// grid whose origin is not at 0.
FeatureGraph randomGraph(std::uint64_t seed)
{
  FeatureGraph g;
  for (std::uint64_t c = 0; c < 12; ++c)
  {
    FeatureChain chain;
    chain.type = c % 2 == 0 ? FeatureType::Ridge : FeatureType::Valley;
    for (std::uint64_t k = 0; k < 60; ++k)
    {
      const std::uint64_t i = c * 1000 + k;
      chain.points.push_back(
        { 40.0 + 300.0 * seededUniform(seed, 1, i), -25.0 + 200.0 * seededUniform(seed, 2, i) });
    }
    g.chains.push_back(std::move(chain));
  }
  return g;
}

Found walked(const FeatureGraph& g, FeatureType type, double x, double y, double reach)
{
  Found found;
  for (const FeatureChain& chain : g.chains)
  {
    for (const Point2& q : chain.points)
    {
      if (chain.type == type && std::abs(q.x - x) <= reach && std::abs(q.y - y) <= reach)
      {
        found.emplace_back(q.x, q.y);
      }
    }
  }
  std::sort(found.begin(), found.end());
  return found;
}

Found visited(const ChainPointGrid& grid, FeatureType type, double x, double y, double reach)
{
  Found found;
  grid.forEachNear(type, x, y, reach, [&](const Point2& q) { found.emplace_back(q.x, q.y); });
  std::sort(found.begin(), found.end());
  return found;
}

} // namespace

TEST(ChainPointGrid, VisitsExactlyThePointsOfTheKindWithinReach)
{
  const FeatureGraph g = randomGraph(3);
  const double side = 20.0;
  const ChainPointGrid grid(g, side);
  std::size_t total = 0;
  for (std::uint64_t s = 0; s < 200; ++s)
  {
    // Spots inside the points' extent, on its edges and beyond it.
    const double x = -20.0 + 420.0 * seededUniform(5, 1, s);
    const double y = -80.0 + 320.0 * seededUniform(5, 2, s);
    const double reach = s % 3 == 0 ? side : 0.5 * side;
    for (FeatureType type : { FeatureType::Ridge, FeatureType::Valley })
    {
      const Found expected = walked(g, type, x, y, reach);
      EXPECT_EQ(visited(grid, type, x, y, reach), expected) << x << ", " << y;
      total += expected.size();
    }
  }
  EXPECT_GT(total, 200u); // the spots do find points
}

TEST(ChainPointGrid, AnEmptyGraphVisitsNothing)
{
  const ChainPointGrid grid(FeatureGraph{}, 20.0);
  EXPECT_TRUE(visited(grid, FeatureType::Ridge, 10.0, 10.0, 20.0).empty());
}
