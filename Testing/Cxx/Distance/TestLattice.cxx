// Tests of Kernels/Distance/Lattice.cxx: the lattice's edge weights, random and from an image.
#include "Distance/DistanceSynthesis.h"
#include "Distance/Lattice.h"
#include "DistanceTestData.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

using namespace tsynth;

namespace
{

using tsynth::test::distance::cellOf;
using tsynth::test::distance::plainOptions;
using tsynth::test::distance::point;

// Every edge that exists, read from both ends: the same weight both ways on
// random lattices; the least and greatest of them are the lattice's edge range.
void expectEdgeRange(const Lattice& l, bool symmetric)
{
  float least = std::numeric_limits<float>::infinity();
  float greatest = 0.0f;
  const int w = l.width();
  for (int row = 0; row < l.height(); ++row)
  {
    for (int col = 0; col < w; ++col)
    {
      for (int d = 0; d < kDirectionCount; ++d)
      {
        const int c = col + kDirectionDx[static_cast<std::size_t>(d)];
        const int r = row + kDirectionDy[static_cast<std::size_t>(d)];
        if (c < 0 || r < 0 || c >= w || r >= l.height())
        {
          continue;
        }
        const float weight = l.weight(static_cast<std::size_t>(cellOf(col, row, w)), Direction(d));
        least = std::min(least, weight);
        greatest = std::max(greatest, weight);
        if (symmetric) // the opposite direction is d ^ 1 (E/W, N/S, NE/SW, NW/SE)
        {
          ASSERT_EQ(weight, l.weight(static_cast<std::size_t>(cellOf(c, r, w)), Direction(d ^ 1)));
        }
      }
    }
  }
  EXPECT_EQ(l.leastEdgeWeight(), least);
  EXPECT_EQ(l.greatestEdgeWeight(), greatest);
}

TEST(DistanceLattice, EdgeWeightsBothWaysAndTheirRange)
{
  LatticeOptions o;
  o.meanWeight = 2.0;
  o.roughness = 1.5;
  o.seed = 9;
  const Lattice l = Lattice::random(37, 23, o);
  expectEdgeRange(l, true);
  EXPECT_GE(l.leastEdgeWeight(), 0.5f);                      // mu_w - r
  EXPECT_LT(l.leastEdgeWeight(), 0.55f);                     // 3,300 draws reach near it
  EXPECT_LE(l.greatestEdgeWeight(), 3.5f * std::sqrt(2.0f)); // (mu_w + r) sqrt 2
  EXPECT_GT(l.greatestEdgeWeight(), 3.4f * std::sqrt(2.0f)); // on a diagonal
  o.sqrt2Diagonals = false;
  expectEdgeRange(Lattice::random(1, 6, o), true); // one column: N and S only
  EXPECT_LE(Lattice::random(1, 6, o).greatestEdgeWeight(), 3.5f);
  const Lattice single = Lattice::random(1, 1, o); // no edges
  EXPECT_EQ(single.leastEdgeWeight(), std::numeric_limits<float>::infinity());
  EXPECT_EQ(single.greatestEdgeWeight(), 0.0f);
  // Image weights: a node's weight on all its outgoing edges (directed).
  std::vector<float> nodes(5 * 4, 1.0f);
  nodes[7] = 0.25f;
  nodes[19] = 3.0f; // a corner: its diagonal edge SW exists
  const Lattice image = Lattice::fromNodeWeights(5, 4, nodes, true);
  expectEdgeRange(image, false);
  EXPECT_EQ(image.leastEdgeWeight(), 0.25f);
  EXPECT_EQ(image.greatestEdgeWeight(), 3.0f * static_cast<float>(std::sqrt(2.0)));
}

TEST(DistanceSynthesis, EdgeWeightsFromAnImage)
{
  // Grey 0 -> 0.25 and 255 -> 2.5 (eq. 4.4 normalised), used on a node's outgoing edges.
  const std::vector<std::uint8_t> grey = { 0, 255, 255, 0 }; // 2 x 2, first row at the top
  const std::vector<float> w = greyToWeights(grey.data(), 2, 2, 1, 0.25, 2.5);
  EXPECT_FLOAT_EQ(w[0], 2.5f); // bottom-left = top row of the flipped image... (row 1 of the file)
  EXPECT_FLOAT_EQ(w[1], 0.25f);
  DistanceInputs in;
  in.width = 40;
  in.height = 3;
  in.features = { point(0, 1, 40, 0.0f) };
  in.nodeWeights.assign(120, 0.5f);
  DistanceOptions o = plainOptions();
  o.seaLevelScale = 1.0;
  o.fbm.scale = 0.0;
  in.features.push_back(point(39, 1, 40, 15.0f)); // sets c_max = 15
  const DistanceTerrain t = synthesiseByDistance(in, o);
  EXPECT_NEAR(t.heights.at(10, 1), 15.0f - 10 * 0.5f, 1e-4f);
}

} // namespace
