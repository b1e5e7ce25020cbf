// The label-setting searches of distance-based synthesis (Rusnell 2009, eq.
// 3.4) on the 8-connected lattice: generator nodes, the per-cell search state,
// the priority queues and the propagation itself. Internal to
// DistanceSynthesis.cxx (templates over its halting and settling rules).
#pragma once

#include "CostScaling.h"
#include "Generators.h"
#include "Lattice.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <queue>
#include <utility>
#include <vector>

namespace tsynth
{
namespace detail
{

constexpr float kUnreached = std::numeric_limits<float>::infinity();
constexpr std::int32_t kNone = -1;

// A generator node with its feature, in one flat array (each feature a run).
struct Source
{
  std::int32_t cell = 0;
  float cost = 0.0f;
  std::int32_t profile = kNoProfile;
  std::int32_t feature = 0;
};

// Float costs as unsigned keys of the same order (negative costs included).
std::uint32_t floatKey(float f)
{
  std::uint32_t b = 0;
  std::memcpy(&b, &f, sizeof b);
  return (b & 0x80000000u) != 0 ? ~b : (b | 0x80000000u);
}

float keyFloat(std::uint32_t k)
{
  const std::uint32_t b = (k & 0x80000000u) != 0 ? (k & 0x7fffffffu) : ~k;
  float f = 0.0f;
  std::memcpy(&f, &b, sizeof f);
  return f;
}

// A monotone radix heap (Ahuja et al. 1990) on 32-bit keys: each element moves
// down at most 32 buckets, so a push and a pop cost O(1) amortised plus a scan.
class RadixHeap
{
public:
  bool empty() const { return size_ == 0; }
  void push(float cost, std::uint32_t node)
  {
    const std::uint32_t key = floatKey(cost);
    buckets_[bucket(key)].push_back({ key, node });
    ++size_;
  }
  std::pair<float, std::uint32_t> pop()
  {
    if (buckets_[0].empty())
    {
      std::size_t i = 1;
      while (buckets_[i].empty())
      {
        ++i;
      }
      std::uint32_t least = buckets_[i].front().first;
      for (const auto& e : buckets_[i])
      {
        least = std::min(least, e.first);
      }
      last_ = least;
      for (const auto& e : buckets_[i])
      {
        buckets_[bucket(e.first)].push_back(e);
      }
      buckets_[i].clear();
    }
    const auto e = buckets_[0].back();
    buckets_[0].pop_back();
    --size_;
    return { keyFloat(e.first), e.second };
  }

private:
  std::size_t bucket(std::uint32_t key) const
  {
    return key == last_ ? 0 : static_cast<std::size_t>(32 - __builtin_clz(key ^ last_));
  }
  std::array<std::vector<std::pair<std::uint32_t, std::uint32_t>>, 33> buckets_;
  std::uint32_t last_ = 0;
  std::size_t size_ = 0;
};

class BinaryHeap
{
public:
  bool empty() const { return heap_.empty(); }
  void push(float cost, std::uint32_t node) { heap_.push({ cost, node }); }
  std::pair<float, std::uint32_t> pop()
  {
    const auto e = heap_.top();
    heap_.pop();
    return e;
  }

private:
  using Entry = std::pair<float, std::uint32_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> heap_;
};

// What every search reads.
struct Search
{
  const Lattice& lattice;
  const std::vector<ScalingFunction>& scaling; // by profile id
  const std::vector<Source>& sources;
  const std::vector<std::int32_t>& regionOf; // region index per cell, or kNone
  const std::vector<DistanceRegion>& regions;
  float seaCost = 0.0f;

  bool blocked(std::size_t cell, std::int32_t feature) const
  {
    const std::int32_t r = regionOf[cell];
    return r != kNone && regions[static_cast<std::size_t>(r)].feature != feature;
  }
  // w_s at a settled node: its region's profile inside a region, else its
  // generator's, evaluated at the modified cost of eq. 3.6.
  float scalingAt(std::size_t cell, float cost, const Source& g) const
  {
    const std::int32_t r = regionOf[cell];
    const std::int32_t profile =
      r != kNone ? regions[static_cast<std::size_t>(r)].profile : g.profile;
    if (profile == kNoProfile)
    {
      return 1.0f;
    }
    const float modified = (cost - g.cost) / (seaCost - g.cost) * seaCost;
    return scaling[static_cast<std::size_t>(profile)](modified);
  }
};

// One search's per-cell state; cells it touched are listed so that it can be
// reset in time proportional to its footprint.
struct Field
{
  std::vector<float> cost;
  std::vector<std::int32_t> source;
  std::vector<std::int32_t> pred; // empty unless wanted
  std::vector<std::uint32_t> touched;

  explicit Field(std::size_t n, bool withPred)
    : cost(n, kUnreached)
    , source(n, kNone)
    , pred(withPred ? n : 0, kNone)
  {
  }
  void reset()
  {
    for (const std::uint32_t k : touched)
    {
      cost[k] = kUnreached;
    }
    touched.clear();
  }
};

// Label-setting propagation of eq. 3.4 from sources[first, last): pops the
// cheapest node, reports it (settle), and unless halt says so relaxes its eight
// edges with c + w_e w_s(c_m). Only costs below c_s are kept.
template<class Queue, class Halt, class Settle>
void propagate(const Search& s,
  std::size_t first,
  std::size_t last,
  Field& f,
  Halt halt,
  Settle settle)
{
  Queue queue;
  const bool withPred = !f.pred.empty();
  auto improve = [&](std::size_t k, float c, std::int32_t source, std::int32_t from)
  {
    if (f.cost[k] == kUnreached)
    {
      f.touched.push_back(static_cast<std::uint32_t>(k));
    }
    f.cost[k] = c;
    f.source[k] = source;
    if (withPred)
    {
      f.pred[k] = from;
    }
    queue.push(c, static_cast<std::uint32_t>(k));
  };
  for (std::size_t i = first; i < last; ++i)
  {
    const Source& g = s.sources[i];
    const auto k = static_cast<std::size_t>(g.cell);
    if (!s.blocked(k, g.feature) && g.cost < f.cost[k])
    {
      improve(k, g.cost, static_cast<std::int32_t>(i), kNone);
    }
  }
  const int w = s.lattice.width();
  const int h = s.lattice.height();
  const auto sw = static_cast<std::ptrdiff_t>(w);
  const std::array<std::ptrdiff_t, kDirectionCount> offset = {
    1, -1, sw, -sw, sw + 1, -sw - 1, sw - 1, -sw + 1
  };
  const std::array<int, kDirectionCount> dx = { 1, -1, 0, 0, 1, -1, -1, 1 };
  const std::array<int, kDirectionCount> dy = { 0, 0, 1, -1, 1, -1, 1, -1 };
  while (!queue.empty())
  {
    const auto [c, node] = queue.pop();
    const std::size_t u = node;
    if (c != f.cost[u])
    {
      continue; // superseded by a cheaper path
    }
    settle(u, c);
    if (halt(u, c))
    {
      continue;
    }
    const std::int32_t source = f.source[u];
    const Source& g = s.sources[static_cast<std::size_t>(source)];
    const float ws = s.scalingAt(u, c, g);
    const int col = static_cast<int>(u % static_cast<std::size_t>(w));
    const int row = static_cast<int>(u / static_cast<std::size_t>(w));
    const bool interior = col > 0 && row > 0 && col + 1 < w && row + 1 < h;
    const float* weights = s.lattice.weights(u);
    for (std::size_t d = 0; d < kDirectionCount; ++d)
    {
      if (!interior)
      {
        const int nc = col + dx[d];
        const int nr = row + dy[d];
        if (nc < 0 || nr < 0 || nc >= w || nr >= h)
        {
          continue;
        }
      }
      const auto v = static_cast<std::size_t>(static_cast<std::ptrdiff_t>(u) + offset[d]);
      const float next = c + weights[d] * ws;
      if (next < s.seaCost && next < f.cost[v] && !s.blocked(v, g.feature))
      {
        improve(v, next, source, static_cast<std::int32_t>(u));
      }
    }
  }
}

template<class Halt, class Settle>
void run(DijkstraQueue queue,
  const Search& s,
  std::size_t first,
  std::size_t last,
  Field& f,
  Halt halt,
  Settle settle)
{
  if (queue == DijkstraQueue::Radix)
  {
    propagate<RadixHeap>(s, first, last, f, halt, settle);
  }
  else
  {
    propagate<BinaryHeap>(s, first, last, f, halt, settle);
  }
}

} // namespace detail
} // namespace tsynth
