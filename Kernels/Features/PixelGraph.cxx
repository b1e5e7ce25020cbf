#include "PixelGraph.h"

#include "../Core/Grid.h"

#include <algorithm>
#include <bitset>
#include <limits>

namespace tsynth
{

constexpr int PixelGraph::kDx[8];
constexpr int PixelGraph::kDy[8];

namespace
{
constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
}

PixelGraph::PixelGraph(int width, int height)
  : width_(width)
  , height_(height)
  , links_(cellCount(width, height), 0)
{
}

std::size_t PixelGraph::neighbour(std::size_t idx, int k) const
{
  const int i = column(idx) + kDx[k];
  const int j = row(idx) + kDy[k];
  if (i < 0 || j < 0 || i >= width_ || j >= height_)
  {
    return kNone;
  }
  return index(i, j);
}

int PixelGraph::degree(std::size_t idx) const
{
  return static_cast<int>(std::bitset<8>(links_[idx]).count());
}

void PixelGraph::link(std::size_t idx, int k)
{
  const std::size_t n = neighbour(idx, k);
  links_[idx] = static_cast<std::uint8_t>(links_[idx] | (1U << k));
  links_[n] = static_cast<std::uint8_t>(links_[n] | (1U << opposite(k)));
}

void PixelGraph::unlink(std::size_t idx, int k)
{
  const std::size_t n = neighbour(idx, k);
  links_[idx] = static_cast<std::uint8_t>(links_[idx] & ~(1U << k));
  links_[n] = static_cast<std::uint8_t>(links_[n] & ~(1U << opposite(k)));
}

void PixelGraph::isolate(std::size_t idx)
{
  for (int k = 0; k < 8; ++k)
  {
    if (hasLink(idx, k))
    {
      unlink(idx, k);
    }
  }
}

std::size_t PixelGraph::edgeCount() const
{
  std::size_t twice = 0;
  for (std::uint8_t m : links_)
  {
    twice += std::bitset<8>(m).count();
  }
  return twice / 2;
}

std::size_t PixelGraph::nodeCount() const
{
  return static_cast<std::size_t>(
    std::count_if(links_.begin(), links_.end(), [](std::uint8_t m) { return m != 0; }));
}

void PixelGraph::removeEndSegments(int times)
{
  std::vector<std::size_t> ends;
  for (std::size_t idx = 0; idx < links_.size(); ++idx)
  {
    if (links_[idx] != 0 && degree(idx) == 1)
    {
      ends.push_back(idx);
    }
  }
  for (int pass = 0; pass < times && !ends.empty(); ++pass)
  {
    std::vector<std::size_t> next;
    for (std::size_t idx : ends)
    {
      if (degree(idx) != 1)
      {
        continue; // already removed with its partner (an isolated two-cell segment)
      }
      const int k = __builtin_ctz(static_cast<unsigned>(links_[idx]));
      const std::size_t n = neighbour(idx, k);
      unlink(idx, k);
      next.push_back(n);
    }
    ends.clear();
    for (std::size_t idx : next)
    {
      if (degree(idx) == 1)
      {
        ends.push_back(idx);
      }
    }
    std::sort(ends.begin(), ends.end());
    ends.erase(std::unique(ends.begin(), ends.end()), ends.end());
  }
}

std::vector<std::size_t> PixelGraph::traceBranch(std::size_t start, std::size_t& junction) const
{
  std::vector<std::size_t> cells{ start };
  std::size_t prev = kNone;
  std::size_t cur = start;
  junction = kNone;
  while (true)
  {
    std::size_t next = kNone;
    for (int k = 0; k < 8; ++k)
    {
      if (hasLink(cur, k) && neighbour(cur, k) != prev)
      {
        next = neighbour(cur, k);
        break;
      }
    }
    if (next == kNone)
    {
      return cells; // reached another end: an isolated chain
    }
    const int d = degree(next);
    if (d != 2)
    {
      junction = d >= 3 ? next : kNone;
      if (d == 1)
      {
        cells.push_back(next);
      }
      return cells;
    }
    cells.push_back(next);
    prev = cur;
    cur = next;
  }
}

void PixelGraph::pruneShortBranches(int minLength)
{
  if (minLength <= 1)
  {
    return;
  }
  for (bool changed = true; changed;)
  {
    changed = false;
    struct Branch
    {
      std::vector<std::size_t> cells;
      std::size_t junction;
    };
    std::vector<Branch> branches;
    for (std::size_t idx = 0; idx < links_.size(); ++idx)
    {
      if (links_[idx] != 0 && degree(idx) == 1)
      {
        std::size_t junction = kNone;
        std::vector<std::size_t> cells = traceBranch(idx, junction);
        if (junction != kNone && static_cast<int>(cells.size()) < minLength)
        {
          branches.push_back({ std::move(cells), junction });
        }
      }
    }
    std::stable_sort(branches.begin(),
      branches.end(),
      [](const Branch& a, const Branch& b) { return a.cells.size() < b.cells.size(); });
    for (const Branch& b : branches)
    {
      // Another pruned branch may have turned this junction into a path cell.
      if (degree(b.junction) < 3 || degree(b.cells.front()) != 1)
      {
        continue;
      }
      for (std::size_t c : b.cells)
      {
        isolate(c);
      }
      changed = true;
    }
  }
}

void PixelGraph::removeSmallComponents(int minCells)
{
  std::vector<std::uint8_t> seen(links_.size(), 0);
  std::vector<std::size_t> stack;
  std::vector<std::size_t> component;
  for (std::size_t start = 0; start < links_.size(); ++start)
  {
    if (links_[start] == 0 || seen[start] != 0)
    {
      continue;
    }
    component.clear();
    stack.push_back(start);
    seen[start] = 1;
    while (!stack.empty())
    {
      const std::size_t c = stack.back();
      stack.pop_back();
      component.push_back(c);
      for (int k = 0; k < 8; ++k)
      {
        if (hasLink(c, k))
        {
          const std::size_t n = neighbour(c, k);
          if (seen[n] == 0)
          {
            seen[n] = 1;
            stack.push_back(n);
          }
        }
      }
    }
    if (static_cast<int>(component.size()) < minCells)
    {
      for (std::size_t c : component)
      {
        isolate(c);
      }
    }
  }
}

bool PixelGraph::isForest() const
{
  // A graph is a forest iff edges = nodes - components.
  std::vector<std::uint8_t> seen(links_.size(), 0);
  std::vector<std::size_t> stack;
  std::size_t components = 0;
  for (std::size_t start = 0; start < links_.size(); ++start)
  {
    if (links_[start] == 0 || seen[start] != 0)
    {
      continue;
    }
    ++components;
    stack.push_back(start);
    seen[start] = 1;
    while (!stack.empty())
    {
      const std::size_t c = stack.back();
      stack.pop_back();
      for (int k = 0; k < 8; ++k)
      {
        if (hasLink(c, k) && seen[neighbour(c, k)] == 0)
        {
          seen[neighbour(c, k)] = 1;
          stack.push_back(neighbour(c, k));
        }
      }
    }
  }
  return edgeCount() == nodeCount() - components;
}

} // namespace tsynth
