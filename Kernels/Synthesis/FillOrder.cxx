#include "FillOrder.h"

#include "../Core/Random.h"

#include <algorithm>
#include <cmath>
#include <queue>

namespace tsynth
{
namespace
{

// The seed moves the fill's inner windows by up to this share of a patch (less
// where the windows are spaced so wide that they would not overlap by
// kMinFillOverlapInPatches).
constexpr double kGridJitterInPatches = 0.125;
// Windows per axis are fewer than this (it spaces the seed's draws per axis).
constexpr std::uint64_t kMaxGridWindows = 1u << 20;
// The data term samples the target's slope every few cells: plenty for a mean.
constexpr int kDataTermStride = 4;

// A window's place in the best-first heap.
struct HeapEntry
{
  double priority;
  double tie;
  std::size_t site;
  int stamp;
  bool operator<(const HeapEntry& o) const
  {
    return priority != o.priority ? priority < o.priority : tie < o.tie;
  }
};

// A patch placed at a window touches the windows this many grid steps round
// it (at most a patch at half-patch spacing, and the jitter).
constexpr std::size_t kRescoreReach = 2;

} // namespace

std::vector<int> fillGridLine(int length,
  int patchSize,
  double spacing,
  std::uint64_t seed,
  std::uint64_t axis)
{
  const int P = patchSize;
  const int step = std::max(1, static_cast<int>(std::lround(spacing * P)));
  const double jitterInPatches =
    std::min(kGridJitterInPatches, (1.0 - kMinFillOverlapInPatches - spacing) / 2.0);
  const int span = std::max(0, length - P);
  const int windows = std::max(1, (span + step - 1) / step);
  std::vector<int> v;
  for (int k = 0; k <= windows; ++k)
  {
    const double even = static_cast<double>(k) * span / windows;
    const bool inner = k > 0 && k < windows;
    const double jitter = inner
      ? (seededUniform(seed, kStreamGrid, axis * kMaxGridWindows + static_cast<std::uint64_t>(k)) -
          0.5) *
        jitterInPatches * 2.0 * P
      : 0.0;
    v.push_back(std::clamp(static_cast<int>(std::lround(even + jitter)), 0, span));
  }
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

FillGrid fillGrid(int width, int height, int patchSize, double spacing, std::uint64_t seed)
{
  FillGrid g;
  g.xs = fillGridLine(width, patchSize, spacing, seed, 0);
  g.ys = fillGridLine(height, patchSize, spacing, seed, 1);
  return g;
}

std::vector<double> fillDataTerms(const Heightfield& t, const FillGrid& g, int patchSize)
{
  std::vector<double> data(g.size(), 0.0);
  for (std::size_t s = 0; s < g.size(); ++s)
  {
    for (int j = g.y0(s); j < std::min(t.height - 1, g.y0(s) + patchSize); j += kDataTermStride)
    {
      for (int i = g.x0(s); i < std::min(t.width - 1, g.x0(s) + patchSize); i += kDataTermStride)
      {
        if (t.isValid(i, j) && t.isValid(i + 1, j) && t.isValid(i, j + 1))
        {
          data[s] += std::hypot(
            (t.at(i + 1, j) - t.at(i, j)) / t.cellX, (t.at(i, j + 1) - t.at(i, j)) / t.cellY);
        }
      }
    }
  }
  const double top = data.empty() ? 0.0 : *std::max_element(data.begin(), data.end());
  for (double& d : data)
  {
    d = top > 0 ? d / top : 0.0;
  }
  return data;
}

void runFill(const FillGrid& g,
  const std::vector<double>& data,
  FillOrder order,
  std::uint64_t seed,
  const FillSteps& steps)
{
  auto priorityOf = [&](std::size_t s, double& priority)
  {
    const double known = steps.filledShare(g.x0(s), g.y0(s));
    priority = known + (order == FillOrder::BestFirst ? data[s] : 0.0);
    return known < 1.0; // still has empty cells
  };
  std::priority_queue<HeapEntry> heap;
  std::vector<int> version(g.size(), 0);
  std::vector<int> attempts(g.size(), 0);
  std::vector<std::uint8_t> retired(g.size(), 0);
  auto push = [&](std::size_t s)
  {
    double p = 0.0;
    if (retired[s] == 0 && priorityOf(s, p))
    {
      heap.push({ p, seededUniform(seed, kStreamFillOrder, s), s, ++version[s] });
      return true;
    }
    return false;
  };
  std::size_t open = 0;
  for (std::size_t s = 0; s < g.size(); ++s)
  {
    open += push(s) ? 1 : 0;
  }
  const std::size_t initial = std::max<std::size_t>(1, open);
  std::size_t done = 0;
  while (!heap.empty())
  {
    const HeapEntry e = heap.top();
    heap.pop();
    double now = 0.0;
    if (e.stamp != version[e.site] || retired[e.site] != 0 || !priorityOf(e.site, now))
    {
      continue; // superseded by a newer score, or done
    }
    // A window whose empty cells no candidate can cover (they fall outside
    // every rotated exemplar's valid area) is retired, never retried forever.
    if (steps.fillWindow(g.x0(e.site), g.y0(e.site)) == 0 || ++attempts[e.site] >= kMaxFillAttempts)
    {
      retired[e.site] = 1;
    }
    ++done;
    // Re-score the windows this patch touched.
    const std::size_t cx = e.site % g.xs.size();
    const std::size_t cy = e.site / g.xs.size();
    const std::size_t r = kRescoreReach;
    for (std::size_t by = cy > r ? cy - r : 0; by <= std::min(g.ys.size() - 1, cy + r); ++by)
    {
      for (std::size_t bx = cx > r ? cx - r : 0; bx <= std::min(g.xs.size() - 1, cx + r); ++bx)
      {
        push(by * g.xs.size() + bx);
      }
    }
    if (steps.progress)
    {
      steps.progress(std::min(1.0, static_cast<double>(done) / static_cast<double>(initial)));
    }
  }
}

} // namespace tsynth
