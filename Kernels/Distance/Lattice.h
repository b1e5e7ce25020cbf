// The 8-connected lattice of distance-based synthesis (Rusnell 2009, §3.1):
// one node per height sample, edges with random positive weights
// w = mu_w + r v, v uniform in [-1, 1] (eq. 3.3), or weights from an image.
#pragma once

#include <array>

#include "../Core/Grid.h"
#include <cstddef>
#include <cstdint>
#include <vector>

namespace tsynth
{

// The eight neighbour directions, in the order the searches relax them.
enum class Direction : int
{
  East,
  West,
  North,
  South,
  NorthEast,
  SouthWest,
  NorthWest,
  SouthEast
};
constexpr int kDirectionCount = 8;
// Column and row steps of the directions (rows grow northwards).
constexpr std::array<int, kDirectionCount> kDirectionDx = { 1, -1, 0, 0, 1, -1, -1, 1 };
constexpr std::array<int, kDirectionCount> kDirectionDy = { 0, 0, 1, -1, 1, -1, 1, -1 };

struct LatticeOptions
{
  double meanWeight = 1.0;    // mu_w > 0: steepness
  double roughness = 0.75;    // r, 0 <= r < mu_w: roughness
  bool sqrt2Diagonals = true; // diagonal edges weigh sqrt(2) times more
  std::uint64_t seed = 1;
};

// Edge weights of a width x height lattice (row 0 south, as Heightfield).
// Random lattices give both directions of an edge one weight; image lattices
// give one weight per node to all its outgoing edges (thesis §4.4: the graph
// is then directed).
class Lattice
{
public:
  // Random weights, seeded: the weight of an edge depends only on (seed, edge).
  // Throws tsynth::Error unless mu_w > 0 and 0 <= r < mu_w.
  static Lattice random(int width, int height, const LatticeOptions& options);
  // One weight per node (row 0 south), each finite and > 0; sqrt2Diagonals as above.
  static Lattice fromNodeWeights(int width,
    int height,
    std::vector<float> weights,
    bool sqrt2Diagonals);

  int width() const { return width_; }
  int height() const { return height_; }
  std::size_t size() const { return cellCount(width_, height_); }
  double meanWeight() const { return meanWeight_; } // divides profile slopes (eq. 3.5)
  double minWeight() const { return minWeight_; }   // smallest edge weight (axis edge)
  // The least and the greatest stored edge weight (diagonal factor applied), as
  // the searches read them; +inf and 0 on a 1 x 1 lattice, which has no edges.
  float leastEdgeWeight() const { return leastEdge_; }
  float greatestEdgeWeight() const { return greatestEdge_; }

  // Weight of the edge from `node` in direction `d`; the neighbour must exist.
  float weight(std::size_t node, Direction d) const
  {
    return weights_[rowMajor(d, node, kDirectionCount)];
  }
  // The eight weights of a node's outgoing edges, in Direction order.
  const float* weights(std::size_t node) const { return weights_.data() + kDirectionCount * node; }

private:
  int width_ = 0;
  int height_ = 0;
  double meanWeight_ = 1.0;
  double minWeight_ = 1.0;
  float leastEdge_ = 0.0f;
  float greatestEdge_ = 0.0f;
  // Eight outgoing weights per node, diagonal factor applied: a search reads one
  // node's edges from one cache line (an undirected edge is stored twice).
  std::vector<float> weights_;

  void findEdgeRange(); // leastEdge_ and greatestEdge_ over the edges that exist
};

// Grey values (0.3 R + 0.59 G + 0.11 B, eq. 4.4) of an image's pixels, rows
// flipped to row 0 south, normalised over the image and mapped linearly onto
// [low, high]; a constant image gives `low` everywhere. Throws tsynth::Error
// unless 0 < low <= high.
std::vector<float> greyToWeights(const std::uint8_t* pixels,
  int width,
  int height,
  int channels,
  double low,
  double high);

} // namespace tsynth
