#include "SeamLines.h"

#include "../Core/Error.h"
#include "../Core/Grid.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

namespace tsynth
{
namespace
{

// The borders of a width x height grid as edges between corners: up(i, j) joins corner (i, j)
// to (i, j + 1) (the border left of cell (i, j)), right(i, j) joins (i, j) to (i + 1, j) (the
// border below cell (i, j)). Each is set when the cells on its two sides are different patches.
class SeamEdges
{
public:
  SeamEdges(const std::vector<int>& id, int width, int height)
    : w_(static_cast<std::size_t>(width))
    , h_(static_cast<std::size_t>(height))
    , up_((w_ + 1) * (h_ + 1), 0)
    , right_((w_ + 1) * (h_ + 1), 0)
  {
    auto cell = [&](std::size_t i, std::size_t j) { return id[j * w_ + i]; };
    auto differ = [](int a, int b) { return a >= 0 && b >= 0 && a != b; };
    for (std::size_t j = 0; j < h_; ++j)
    {
      for (std::size_t i = 1; i < w_; ++i)
      {
        up_[corner(i, j)] = differ(cell(i - 1, j), cell(i, j)) ? 1 : 0;
      }
    }
    for (std::size_t j = 1; j < h_; ++j)
    {
      for (std::size_t i = 0; i < w_; ++i)
      {
        right_[corner(i, j)] = differ(cell(i, j - 1), cell(i, j)) ? 1 : 0;
      }
    }
  }

  std::size_t cornersX() const { return w_ + 1; }
  std::size_t cornersY() const { return h_ + 1; }

  // The corners joined to (i, j) by an edge not yet taken: up, right, down, left.
  int degree(std::size_t i, std::size_t j) const
  {
    int d = 0;
    for (int k = 0; k < 4; ++k)
    {
      d += open(i, j, k) ? 1 : 0;
    }
    return d;
  }

  // Takes the first open edge from (i, j) and moves there; false when none is open.
  bool step(std::size_t& i, std::size_t& j)
  {
    for (int k = 0; k < 4; ++k)
    {
      if (open(i, j, k))
      {
        edge(i, j, k) = 0;
        i = k == 1 ? i + 1 : k == 3 ? i - 1 : i;
        j = k == 0 ? j + 1 : k == 2 ? j - 1 : j;
        return true;
      }
    }
    return false;
  }

private:
  static constexpr int kUp = 0;
  static constexpr int kRight = 1;
  static constexpr int kDown = 2;
  static constexpr int kLeft = 3;

  std::size_t corner(std::size_t i, std::size_t j) const { return j * (w_ + 1) + i; }

  bool open(std::size_t i, std::size_t j, int k) const
  {
    if ((k == kDown && j == 0) || (k == kLeft && i == 0) || (k == kUp && j == h_) ||
      (k == kRight && i == w_))
    {
      return false;
    }
    return const_cast<SeamEdges*>(this)->edge(i, j, k) != 0;
  }

  std::uint8_t& edge(std::size_t i, std::size_t j, int k)
  {
    switch (k)
    {
      case kUp:
        return up_[corner(i, j)];
      case kRight:
        return right_[corner(i, j)];
      case kDown:
        return up_[corner(i, j - 1)];
      default:
        return right_[corner(i - 1, j)];
    }
  }

  std::size_t w_;
  std::size_t h_;
  std::vector<std::uint8_t> up_;
  std::vector<std::uint8_t> right_;
};

// Walks from (i, j) along open edges until a corner where seams meet, end, or the walk closes.
// `ends` marks the corners where seams end or meet (not two edges before any walk).
SeamLine walk(SeamEdges& edges, const std::vector<std::uint8_t>& ends, std::size_t i, std::size_t j)
{
  SeamLine line{ { static_cast<int>(i), static_cast<int>(j) } };
  while (edges.step(i, j))
  {
    line.push_back({ static_cast<int>(i), static_cast<int>(j) });
    if (ends[j * edges.cornersX() + i] != 0)
    {
      break;
    }
  }
  return line;
}

} // namespace

std::vector<SeamLine> seamLines(const std::vector<int>& patchId, int width, int height)
{
  if (width < 0 || height < 0 || patchId.size() != cellCount(width, height))
  {
    throw Error("seamLines: " + std::to_string(patchId.size()) + " patch ids for a " +
      std::to_string(width) + " x " + std::to_string(height) + " grid.");
  }
  SeamEdges edges(patchId, width, height);
  std::vector<std::uint8_t> ends(edges.cornersX() * edges.cornersY(), 0);
  for (std::size_t j = 0; j < edges.cornersY(); ++j)
  {
    for (std::size_t i = 0; i < edges.cornersX(); ++i)
    {
      const int d = edges.degree(i, j);
      ends[j * edges.cornersX() + i] = d != 0 && d != 2 ? 1 : 0;
    }
  }
  std::vector<SeamLine> lines;
  // Open ends and meeting points first, so each line runs between two of them.
  for (std::size_t j = 0; j < edges.cornersY(); ++j)
  {
    for (std::size_t i = 0; i < edges.cornersX(); ++i)
    {
      while (ends[j * edges.cornersX() + i] != 0 && edges.degree(i, j) > 0)
      {
        lines.push_back(walk(edges, ends, i, j));
      }
    }
  }
  // What is left are closed loops of plain corners.
  for (std::size_t j = 0; j < edges.cornersY(); ++j)
  {
    for (std::size_t i = 0; i < edges.cornersX(); ++i)
    {
      while (edges.degree(i, j) > 0)
      {
        lines.push_back(walk(edges, ends, i, j));
      }
    }
  }
  return lines;
}

} // namespace tsynth
