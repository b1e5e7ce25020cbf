// The label-setting searches of distance-based synthesis (Rusnell 2009, eq.
// 3.4) on the 8-connected lattice: generator nodes, the per-cell search state,
// the priority queues and the propagation itself. Internal to
// DistanceSynthesis.cxx (templates over its halting and settling rules).
#pragma once

#include "CostScaling.h"
#include "DistanceSynthesis.h"
#include "Generators.h"
#include "Lattice.h"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
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

// The range of a w_s table (w_s = 1 without a profile).
struct ScalingBounds
{
  float least = 1.0f;
  float greatest = 1.0f;
};

// What every search reads.
struct Search
{
  const Lattice& lattice;
  const std::vector<ScalingFunction>& scaling;     // by profile id
  const std::vector<ScalingBounds>& scalingBounds; // by profile id
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
    return scalingOf(
      r != kNone ? regions[static_cast<std::size_t>(r)].profile : g.profile, cost, g);
  }
  float scalingOf(std::int32_t profile, float cost, const Source& g) const
  {
    if (profile == kNoProfile)
    {
      return 1.0f;
    }
    const float modified = (cost - g.cost) / (seaCost - g.cost) * seaCost;
    return scaling[static_cast<std::size_t>(profile)](modified);
  }
};

// Bucket numbers of costs: [base + b width, base + (b + 1) width) is bucket b.
// A value the searches keep in registers.
struct BucketIndex
{
  double base = 0.0;
  double inverseWidth = 0.0;

  // Costs below base never occur: they are at least the cheapest generator's.
  // Via a signed integer: one instruction (the value is below 2^63).
  std::uint64_t operator()(float cost) const
  {
    return static_cast<std::uint64_t>(
      static_cast<std::int64_t>((static_cast<double>(cost) - base) * inverseWidth));
  }
};

// Dial's bucket queue with Dinitz's width: bucket b holds the cells whose cost
// lies in [base + b width, base + (b + 1) width). A power-of-two ring of
// buckets, large enough for the costs a search has queued at any time (they
// lie within the greatest step of the cheapest); each bucket keeps its storage
// from search to search.
class BucketRing
{
public:
  void start(double base, double width, std::size_t span)
  {
    std::size_t size = 1;
    while (size < span)
    {
      size *= 2;
    }
    if (slots_.size() < size)
    {
      slots_.resize(size);
    }
    mask_ = size - 1;
    index_ = { base, 1.0 / width };
    queued_ = 0;
  }
  std::size_t span() const { return mask_ + 1; }
  BucketIndex index() const { return index_; }
  void push(std::uint64_t bucket, std::uint32_t cell)
  {
    slots_[bucket & mask_].push_back(cell);
    ++queued_;
  }
  bool empty() const { return queued_ == 0; }
  std::vector<std::uint32_t>& slot(std::uint64_t bucket) { return slots_[bucket & mask_]; }
  void clear(std::uint64_t bucket)
  {
    std::vector<std::uint32_t>& s = slot(bucket);
    queued_ -= s.size();
    s.clear();
  }
  // The generator cells of a search by cost: they enter the ring when the search
  // reaches their bucket, so that the ring need not span all their costs.
  std::vector<std::pair<float, std::uint32_t>> pending;

private:
  std::vector<std::vector<std::uint32_t>> slots_;
  std::size_t mask_ = 0;
  BucketIndex index_;
  std::size_t queued_ = 0;
};

// The cells a search has reached, each once, so that its state can be reset
// in time proportional to its footprint: room for all n cells, and one more
// for addIf's store past the last.
class CellList
{
public:
  explicit CellList(std::size_t n)
    : cells_(n + 1)
  {
  }
  void add(std::uint32_t cell) { cells_[size_++] = cell; }
  // add(cell) if yes, with no branch to mispredict.
  void addIf(std::uint32_t cell, bool yes)
  {
    cells_[size_] = cell;
    size_ += yes ? 1 : 0;
  }
  const std::uint32_t* begin() const { return cells_.data(); }
  const std::uint32_t* end() const { return cells_.data() + size_; }
  void clear() { size_ = 0; }

private:
  std::vector<std::uint32_t> cells_;
  std::size_t size_ = 0;
};

// Its own cache lines: threads' fields side by side in a vector would share
// lines, and a search writes its list and ring counters at every step.
constexpr std::size_t kCacheLine = 64;

// One search's per-cell state; the cells it reached are listed so that it can
// be reset in time proportional to its footprint.
struct alignas(kCacheLine) Field
{
  std::vector<float> cost;
  std::vector<std::int32_t> source;
  std::vector<std::int32_t> pred; // empty unless wanted (the bucket queue wants it)
  CellList touched;
  BucketRing ring; // the bucket queue's, kept from search to search

  explicit Field(std::size_t n, bool withPred)
    : cost(n, kUnreached)
    , source(n, kNone)
    , pred(withPred ? n : 0, kNone)
    , touched(n)
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
      f.touched.add(static_cast<std::uint32_t>(k));
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
    const auto [col, row] = cellOf(u, w);
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
      const std::size_t v = offsetCell(u, offset[d]);
      const float next = c + weights[d] * ws;
      if (next < s.seaCost && next < f.cost[v] && !s.blocked(v, g.feature))
      {
        improve(v, next, source, static_cast<std::int32_t>(u));
      }
    }
  }
}

// ---------------------------------------------------------------------------
// The bucket queue (DijkstraQueue::Bucket)
//
// Every step c -> fl(c + fl(w w_s)) of a search is at least StepRange::least >
// 0, and buckets are narrower than that, so each relaxation lands in a later
// bucket than the cell it starts from. When the search reaches bucket b, every
// cell that could still lower a cell of b (or tie with it) lies in an earlier
// bucket and has been expanded: all of b is final, and b is settled in any
// order, with no heap. The costs are the radix heap's bit for bit, being the
// same float sums minimised over the same predecessors. What the order still
// decides is which predecessor keeps a cell that two paths reach at exactly the
// same float cost (and so its generator, its w_s and its ridge path): the first
// to be expanded. The bucket queue decides such ties by the radix heap's order
// (popsBefore), so it gives the radix heap's results even on lattices full of
// ties (r = 0).

// Above this many buckets (a greatest step this many times the least: r close
// to mu_w, or w_s tables spanning a wide range) a search walks mostly empty
// buckets and the radix heap is faster. The 512^2 benchmark scene on one
// thread: at r = 0.999 mu_w (all spans under 2^14) buckets take 0.68 times the
// radix heap's time; at r = 0.9999 mu_w (spans of about 3e4 to 1.5e5) 1.4
// times with no limit, 0.99 times with this one (67 of 101 searches left to
// the radix heap) and with 2^14 (all left to it) alike.
constexpr std::size_t kMaxRingBuckets = std::size_t(1) << 16;
// Buckets a shade narrower than the least step, for the rounding of the bucket
// index in double (relative error ~1e-16 at costs up to 2^24 least steps).
constexpr double kBucketWidthShare = 1.0 - 1.0 / (1 << 20);

// Bounds on one step fl(c + fl(w w_s)) - c of a search.
struct StepRange
{
  double least = 0.0;
  double most = 0.0;
};

// w in [leastWeight, greatestWeight] (stored floats); w_s from tables in
// [scaling.least, scaling.greatest], up to the rounding of their linear
// interpolation a + f (b - a) (under 2 float epsilons of the larger end); kept
// costs of magnitude below costMagnitude, so that the float sum c + p is within
// one float epsilon of costMagnitude of the exact one.
inline StepRange stepRange(float leastWeight,
  float greatestWeight,
  const ScalingBounds& scaling,
  double costMagnitude)
{
  const double e = FLT_EPSILON;
  const double leastScaling = scaling.least - 2.0 * e * scaling.greatest;
  const double mostScaling = scaling.greatest * (1.0 + 2.0 * e);
  const double sumError = e * costMagnitude;
  return { leastWeight * leastScaling * (1.0 - e) - sumError,
    greatestWeight * mostScaling * (1.0 + e) + sumError };
}

// The bucket layout of a search: the first bucket starts at the cheapest
// generator; span buckets hold every cost queued at once. span 0: the radix
// heap should search instead.
struct BucketPlan
{
  double base = 0.0;
  double width = 0.0;
  std::size_t span = 0;
};

// The w_s range of the search from sources[first, last): their profiles, and
// those of the regions it may enter (its own feature's; all if it has several).
inline ScalingBounds searchScaling(const Search& s, std::size_t first, std::size_t last)
{
  ScalingBounds b{ std::numeric_limits<float>::infinity(), 0.0f };
  auto include = [&](std::int32_t profile)
  {
    const ScalingBounds p =
      profile == kNoProfile ? ScalingBounds{} : s.scalingBounds[static_cast<std::size_t>(profile)];
    b.least = std::min(b.least, p.least);
    b.greatest = std::max(b.greatest, p.greatest);
  };
  std::int32_t lowFeature = std::numeric_limits<std::int32_t>::max();
  std::int32_t highFeature = std::numeric_limits<std::int32_t>::min();
  for (std::size_t i = first; i < last; ++i)
  {
    include(s.sources[i].profile);
    lowFeature = std::min(lowFeature, s.sources[i].feature);
    highFeature = std::max(highFeature, s.sources[i].feature);
  }
  for (const DistanceRegion& r : s.regions)
  {
    if (lowFeature != highFeature || r.feature == lowFeature)
    {
      include(r.profile);
    }
  }
  return b;
}

inline BucketPlan planBuckets(const Search& s, std::size_t first, std::size_t last)
{
  if (first == last)
  {
    return {};
  }
  float base = std::numeric_limits<float>::infinity();
  for (std::size_t i = first; i < last; ++i)
  {
    base = std::min(base, s.sources[i].cost);
  }
  const double magnitude =
    std::max(std::fabs(static_cast<double>(base)), std::fabs(static_cast<double>(s.seaCost)));
  const StepRange step = stepRange(s.lattice.leastEdgeWeight(),
    s.lattice.greatestEdgeWeight(),
    searchScaling(s, first, last),
    magnitude);
  const double width = step.least * kBucketWidthShare;
  // Finite steps and a ratio that fits the ring; else (and for a lattice without
  // edges, whose least weight is +inf) the radix heap.
  if (!(width > 0.0) || !std::isfinite(width) || !std::isfinite(step.most) ||
    !(step.most / width < static_cast<double>(kMaxRingBuckets - 2)))
  {
    return {};
  }
  return { base, width, static_cast<std::size_t>(step.most / width) + 2 };
}

// Sets the generators' costs as propagate does (the cheapest at a cell, the
// first of equals) and lists each seeded cell once, by cost, in ring.pending.
inline void seedBuckets(const Search& s, std::size_t first, std::size_t last, Field& f)
{
  for (std::size_t i = first; i < last; ++i)
  {
    const Source& g = s.sources[i];
    const auto k = static_cast<std::size_t>(g.cell);
    if (!s.blocked(k, g.feature) && g.cost < f.cost[k])
    {
      if (f.cost[k] == kUnreached)
      {
        f.touched.add(static_cast<std::uint32_t>(k));
      }
      f.cost[k] = g.cost;
      f.source[k] = static_cast<std::int32_t>(i);
      f.pred[k] = kNone;
    }
  }
  f.ring.pending.clear();
  for (std::size_t i = first; i < last; ++i)
  {
    const Source& g = s.sources[i];
    const auto k = static_cast<std::size_t>(g.cell);
    if (f.source[k] == static_cast<std::int32_t>(i) && f.cost[k] == g.cost)
    {
      f.ring.pending.push_back({ g.cost, static_cast<std::uint32_t>(k) });
    }
  }
  std::sort(f.ring.pending.begin(), f.ring.pending.end());
}

// Queues the pending generators of bucket b (from index next on) whose cost no
// path has lowered out of b; returns the index of the first later one.
inline std::size_t injectGenerators(Field& f, std::size_t next, std::uint64_t b)
{
  BucketRing& ring = f.ring;
  const BucketIndex bucketOf = ring.index();
  for (; next < ring.pending.size() && bucketOf(ring.pending[next].first) == b; ++next)
  {
    const std::uint32_t k = ring.pending[next].second;
    if (bucketOf(f.cost[k]) == b)
    {
      ring.push(b, k);
    }
  }
  return next;
}

// The lattice steps of a search, and the cells whose eight neighbours all exist.
struct Neighbourhood
{
  std::size_t width = 0;
  std::size_t height = 0;
  std::array<std::ptrdiff_t, kDirectionCount> offset{};

  explicit Neighbourhood(const Lattice& lattice)
    : width(static_cast<std::size_t>(lattice.width()))
    , height(static_cast<std::size_t>(lattice.height()))
  {
    for (std::size_t d = 0; d < kDirectionCount; ++d)
    {
      offset[d] = kDirectionDx[d] + kDirectionDy[d] * static_cast<std::ptrdiff_t>(width);
    }
  }
  bool has(std::size_t col, std::size_t row, std::size_t d) const
  {
    const auto c = static_cast<std::ptrdiff_t>(col) + kDirectionDx[d];
    const auto r = static_cast<std::ptrdiff_t>(row) + kDirectionDy[d];
    return c >= 0 && r >= 0 && c < static_cast<std::ptrdiff_t>(width) &&
      r < static_cast<std::ptrdiff_t>(height);
  }
};

// The direction of the step from cell `from` to its neighbour `to`.
inline std::size_t directionOf(const Neighbourhood& nb, std::size_t from, std::size_t to)
{
  const auto dx =
    static_cast<std::ptrdiff_t>(to % nb.width) - static_cast<std::ptrdiff_t>(from % nb.width);
  const auto dy =
    static_cast<std::ptrdiff_t>(to / nb.width) - static_cast<std::ptrdiff_t>(from / nb.width);
  std::size_t d = 0;
  while (kDirectionDx[d] != dx || kDirectionDy[d] != dy)
  {
    ++d;
  }
  return d;
}

// Whether the radix heap would pop settled cell a before settled cell b: the
// lower cost key first; of equal keys the later pushed (its bucket 0 is a
// stack, and equal keys always share a bucket, in the order they came). A cell
// is pushed when its predecessor is expanded, in direction order; generators
// before all others, in index order.
inline bool popsBefore(const Neighbourhood& nb, const Field& f, std::size_t a, std::size_t b)
{
  while (true)
  {
    const std::uint32_t ka = floatKey(f.cost[a]);
    const std::uint32_t kb = floatKey(f.cost[b]);
    if (ka != kb)
    {
      return ka < kb;
    }
    const std::int32_t pa = f.pred[a];
    const std::int32_t pb = f.pred[b];
    if (pa == kNone || pb == kNone)
    {
      return pa != kNone || (pb == kNone && f.source[a] > f.source[b]);
    }
    const auto ua = static_cast<std::size_t>(pa);
    const auto ub = static_cast<std::size_t>(pb);
    if (ua == ub)
    {
      return directionOf(nb, ua, a) > directionOf(nb, ub, b);
    }
    a = ub; // a was pushed after b if and only if its predecessor popped after b's
    b = ua;
  }
}

// Cell u reaches v at v's present cost: does u take v over? It does if the
// radix heap would have expanded u before v's present predecessor, which then
// would have found v taken. Generators keep their cells.
inline bool winsTie(const Neighbourhood& nb, const Field& f, std::size_t u, std::size_t v)
{
  const std::int32_t p = f.pred[v];
  return p != kNone && popsBefore(nb, f, u, static_cast<std::size_t>(p));
}

// Relaxes the edges of the settled cell u (cost c, in bucket b). Returns false
// if a step lands outside (b, b + span): the step bounds did not hold, and the
// search must be redone by the radix heap.
template<bool Regions>
bool expandCell(const Search& s,
  const Neighbourhood& nb,
  Field& f,
  std::size_t u,
  float c,
  std::uint64_t b)
{
  BucketRing& ring = f.ring;
  const BucketIndex bucketOf = ring.index();
  const std::int32_t source = f.source[u];
  const Source& g = s.sources[static_cast<std::size_t>(source)];
  const float ws = Regions ? s.scalingAt(u, c, g) : s.scalingOf(g.profile, c, g);
  const std::int32_t feature = g.feature;
  const std::size_t col = u % nb.width;
  const std::size_t row = u / nb.width;
  const bool interior = col > 0 && row > 0 && col + 1 < nb.width && row + 1 < nb.height;
  const float* weights = s.lattice.weights(u);
  const std::uint64_t span = ring.span();
  for (std::size_t d = 0; d < kDirectionCount; ++d)
  {
    if (!interior && !nb.has(col, row, d))
    {
      continue;
    }
    const std::size_t v = offsetCell(u, nb.offset[d]);
    const float next = c + weights[d] * ws;
    if (!(next < s.seaCost) || next > f.cost[v] || (Regions && s.blocked(v, feature)))
    {
      continue;
    }
    const std::uint64_t to = bucketOf(next);
    if (to - b - 1 >= span - 1) // to <= b or beyond the ring
    {
      return false;
    }
    const float old = f.cost[v];
    if (next == old && !winsTie(nb, f, u, v))
    {
      continue;
    }
    f.touched.addIf(static_cast<std::uint32_t>(v), old == kUnreached);
    f.cost[v] = next;
    f.source[v] = source;
    f.pred[v] = static_cast<std::int32_t>(u);
    if (old == kUnreached || bucketOf(old) != to)
    {
      ring.push(to, static_cast<std::uint32_t>(v)); // else it is queued there already
    }
  }
  return true;
}

// propagate with the bucket queue: the same costs, sources and predecessors
// (see above), or false if the search must be redone by the radix heap (the
// field then holds a partial search; settle has seen part of it).
template<bool Regions, class Halt, class Settle>
bool propagateBuckets(const Search& s,
  std::size_t first,
  std::size_t last,
  const BucketPlan& plan,
  Field& f,
  Halt halt,
  Settle settle)
{
  BucketRing& ring = f.ring;
  ring.start(plan.base, plan.width, plan.span);
  const BucketIndex bucketOf = ring.index();
  seedBuckets(s, first, last, f);
  const Neighbourhood nb(s.lattice);
  std::size_t pending = 0;
  std::uint64_t b = 0;
  while (!ring.empty() || pending < ring.pending.size())
  {
    if (ring.empty()) // nothing queued: on to the next generator's bucket
    {
      b = std::max(b, bucketOf(ring.pending[pending].first));
    }
    pending = injectGenerators(f, pending, b);
    // First drop the cells lowered into an earlier bucket (and settled there),
    // without a branch: which cells are stale is as good as random.
    std::vector<std::uint32_t>& cells = ring.slot(b);
    std::size_t live = 0;
    for (const std::uint32_t u : cells)
    {
      cells[live] = u;
      live += bucketOf(f.cost[u]) == b ? 1 : 0;
    }
    for (std::size_t i = 0; i < live; ++i)
    {
      const std::uint32_t u = cells[i];
      const float c = f.cost[u];
      settle(u, c);
      if (!halt(u, c) && !expandCell<Regions>(s, nb, f, u, c, b))
      {
        return false;
      }
    }
    ring.clear(b);
    ++b;
  }
  return true;
}

// One search from sources[first, last) with the chosen queue. restart() is
// called before the radix heap redoes a search the bucket queue gave up
// (settle saw part of it); returns true if the radix heap searched in the
// bucket queue's place.
template<class Halt, class Settle, class Restart>
bool run(DijkstraQueue queue,
  const Search& s,
  std::size_t first,
  std::size_t last,
  Field& f,
  Halt halt,
  Settle settle,
  Restart restart)
{
  if (queue == DijkstraQueue::Bucket)
  {
    const BucketPlan plan = planBuckets(s, first, last);
    if (plan.span > 0)
    {
      const bool done = s.regions.empty()
        ? propagateBuckets<false>(s, first, last, plan, f, halt, settle)
        : propagateBuckets<true>(s, first, last, plan, f, halt, settle);
      if (done)
      {
        return false;
      }
      f.reset();
      restart();
    }
    propagate<RadixHeap>(s, first, last, f, halt, settle);
    return true;
  }
  if (queue == DijkstraQueue::Radix)
  {
    propagate<RadixHeap>(s, first, last, f, halt, settle);
  }
  else
  {
    propagate<BinaryHeap>(s, first, last, f, halt, settle);
  }
  return false;
}

} // namespace detail
} // namespace tsynth
