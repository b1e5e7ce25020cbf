// A graph whose nodes are grid cells and whose edges join 8-neighbours, stored
// as one 8-bit neighbour mask per cell: the working form of every feature line
// before it becomes a FeatureGraph (PPA forests, thinned strokes).
#pragma once

#include <cstddef>

#include "../Core/Grid.h"
#include <cstdint>
#include <vector>

namespace tsynth
{

class PixelGraph
{
public:
  // Neighbour k: 0 E, 1 NE, 2 N, 3 NW, 4 W, 5 SW, 6 S, 7 SE (y grows north).
  static constexpr int kDx[8] = { 1, 1, 0, -1, -1, -1, 0, 1 };
  static constexpr int kDy[8] = { 0, 1, 1, 1, 0, -1, -1, -1 };
  static constexpr int opposite(int k) { return (k + 4) & 7; }

  PixelGraph() = default;
  PixelGraph(int width, int height);

  int width() const { return width_; }
  int height() const { return height_; }
  std::size_t size() const { return links_.size(); }
  std::size_t index(int i, int j) const { return rowMajor(i, j, width_); }
  int column(std::size_t idx) const { return cellOf(idx, width_).i; }
  int row(std::size_t idx) const { return cellOf(idx, width_).j; }

  // The neighbour of cell idx in direction k, or SIZE_MAX outside the grid.
  std::size_t neighbour(std::size_t idx, int k) const;

  std::uint8_t links(std::size_t idx) const { return links_[idx]; }
  bool hasLink(std::size_t idx, int k) const { return ((links_[idx] >> k) & 1U) != 0; }
  int degree(std::size_t idx) const;
  // Links cell idx to its neighbour k (both directions). The neighbour must exist.
  void link(std::size_t idx, int k);
  void unlink(std::size_t idx, int k);
  // Removes every edge of a cell.
  void isolate(std::size_t idx);

  std::size_t edgeCount() const;
  std::size_t nodeCount() const; // cells with at least one edge

  // Removes all degree-1 cells, `times` times over: each pass shortens every
  // dangling branch by one cell (Chang's end-point reduction).
  void removeEndSegments(int times);

  // Removes dangling branches (end cell .. first cell of degree >= 3) shorter
  // than minLength cells, shortest first, never making a junction an end.
  // Repeats until nothing changes.
  void pruneShortBranches(int minLength);

  // Removes connected components with fewer than minCells cells.
  void removeSmallComponents(int minCells);

  // True if the graph has no cycle (it is a forest).
  bool isForest() const;

private:
  // Cells of the branch from end cell `start` up to (not including) the first
  // cell whose degree is not 2; `junction` receives that cell (SIZE_MAX if the
  // walk ended at another end).
  std::vector<std::size_t> traceBranch(std::size_t start, std::size_t& junction) const;

  int width_ = 0;
  int height_ = 0;
  std::vector<std::uint8_t> links_;
};

} // namespace tsynth
