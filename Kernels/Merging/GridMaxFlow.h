// Exact s-t max-flow / min-cut on an implicit 4-connected grid (Boykov and
// Kolmogorov 2004, the algorithm of their maxflow library) specialised for the
// seam graph cut: neighbours are found by index arithmetic, so there is no
// adjacency list to build, and every buffer is kept between calls.
#pragma once

#include <cstdint>
#include <vector>

namespace tsynth
{

class GridMaxFlow
{
public:
  // Edge directions from a node: +x, -x, +y, -y. The reverse of d is d ^ 1.
  enum Direction : std::uint8_t
  {
    PlusX = 0,
    MinusX = 1,
    PlusY = 2,
    MinusY = 3
  };

  // Starts a new problem on a width x height grid with every capacity zero.
  // Storage grows only when the grid does.
  void reset(int width, int height);

  // Adds capacity from the source and to the sink of node k (k = j * width + i).
  void addTerminal(int k, double toSource, double toSink);
  // Sets the capacities of the edge between k and its neighbour in direction
  // PlusX or PlusY: forward is k -> neighbour, backward is neighbour -> k.
  // Inline: SeamCut calls it for every overlap edge.
  void setEdge(int k, Direction d, double forward, double backward)
  {
    const int n = inner(k);
    cap_[4 * n + d] = forward;
    cap_[4 * neighbour(n, d) + (d ^ 1)] = backward;
  }

  // Runs the flow and returns the max-flow value (= min-cut capacity).
  double solve();

  // After solve(): true if node k is on the source side of the minimum cut.
  // Nodes that neither tree reached go to the sink side, so the source side
  // is the smallest one (exactly the nodes reachable from the source).
  bool sourceSide(int k) const
  {
    const int n = inner(k);
    return parent_[n] != None && !sink_[n];
  }

  int width() const { return width_; }
  int height() const { return height_; }

private:
  static constexpr std::int8_t None = -1;
  static constexpr std::int8_t Terminal = 4;
  static constexpr std::int8_t Orphan = 5;
  static constexpr int NotActive = -2;

  // Internally the grid has a one-node frame of zero capacity, so every node
  // has four neighbours in memory and the inner loops need no bounds tests.
  int inner(int k) const { return (k / width_ + 1) * stride_ + k % width_ + 1; }
  int neighbour(int k, int d) const { return k + offset_[d]; }
  void setActive(int k);
  int nextActive();
  void attach(int k, int d, int p, int ts, int dist);
  template<bool Sink>
  int grow(int i);
  void augment(int s, int d);
  template<bool Sink>
  void processOrphan(int i);

  int width_ = 0;
  int height_ = 0;
  int stride_ = 0;
  int offset_[4] = { 1, -1, 0, 0 };
  double flow_ = 0.0;
  std::vector<double> cap_;         // 4 residual capacities per node
  std::vector<double> tr_;          // > 0: residual from source, < 0: to sink
  std::vector<std::int8_t> parent_; // direction to the parent, Terminal, Orphan or None
  // The parent node when parent_ is a direction: walks up a tree are a chain
  // of these loads alone (the direction costs a second, dependent lookup).
  std::vector<int> up_;
  std::vector<std::uint8_t> sink_; // tree membership when parent_ != None
  std::vector<int> next_;          // active FIFO links (NotActive = not queued)
  std::vector<int> ts_;
  std::vector<int> dist_;
  std::vector<int> orphans_;
  std::vector<int> path_; // augment(): the nodes of the current path
  int queueFirst_ = -1;
  int queueLast_ = -1;
  int time_ = 0;
};

} // namespace tsynth
