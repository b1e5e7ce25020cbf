#include "GridMaxFlow.h"

#include "../Core/Grid.h"

#include <algorithm>
#include <limits>

namespace tsynth
{

namespace
{
constexpr int InfiniteDistance = std::numeric_limits<int>::max();
}

void GridMaxFlow::reset(int width, int height)
{
  width_ = std::max(width, 0);
  height_ = std::max(height, 0);
  stride_ = width_ + 2;
  const std::size_t n = cellCount(stride_, height_ + 2);
  offset_[PlusX] = 1;
  offset_[MinusX] = -1;
  offset_[PlusY] = stride_;
  offset_[MinusY] = -stride_;
  // assign() reuses the capacity of earlier, larger problems. The per-node
  // tree state is set by solve() (the frame is never visited).
  cap_.assign(4 * n, 0.0);
  tr_.assign(n, 0.0);
  parent_.assign(n, None);
  sink_.resize(n);
  up_.resize(n);
  next_.resize(n);
  ts_.resize(n);
  dist_.resize(n);
  path_.resize(n);
  orphans_.clear();
  flow_ = 0.0;
}

void GridMaxFlow::addTerminal(int k, double toSource, double toSink)
{
  const int n = inner(k);
  // Only the difference matters; the common part is flow already pushed
  // (merged with what the node already has, as in Kolmogorov's add_tweights).
  const double delta = tr_[n];
  if (delta > 0.0)
    toSource += delta;
  else
    toSink -= delta;
  flow_ += std::min(toSource, toSink);
  tr_[n] = toSource - toSink;
}

void GridMaxFlow::setActive(int k)
{
  if (next_[k] != NotActive)
  {
    return;
  }
  // The last queued node links to itself, as in Kolmogorov's code.
  if (queueLast_ >= 0)
  {
    next_[queueLast_] = k;
  }
  else
  {
    queueFirst_ = k;
  }
  queueLast_ = k;
  next_[k] = k;
}

int GridMaxFlow::nextActive()
{
  while (queueFirst_ >= 0)
  {
    const int k = queueFirst_;
    if (next_[k] == k)
    {
      queueFirst_ = queueLast_ = -1;
    }
    else
    {
      queueFirst_ = next_[k];
    }
    next_[k] = NotActive;
    if (parent_[k] != None) // a queued node is active only while in a tree
    {
      return k;
    }
  }
  return -1;
}

void GridMaxFlow::attach(int k, int d, int p, int ts, int dist)
{
  parent_[k] = static_cast<std::int8_t>(d);
  up_[k] = p;
  ts_[k] = ts;
  dist_[k] = dist;
}

void GridMaxFlow::augment(int s, int d)
{
  // Raw pointers: the int8 stores below may alias anything, so the vectors'
  // data pointers would otherwise be reloaded after each of them.
  double* const cap = cap_.data();
  std::int8_t* const parent = parent_.data();
  const int* const up = up_.data();
  int* const path = path_.data();
  const int t = neighbour(s, d);
  // One walk up each tree (a chain of up_ loads, the capacities are read off
  // the chain) finds the bottleneck and records the path for the update.
  double bottleneck = cap[4 * s + d];
  int length = 0;
  int k = s;
  while (parent[k] != Terminal)
  {
    const int p = up[k];
    bottleneck = std::min(bottleneck, cap[4 * p + (parent[k] ^ 1)]);
    path[length++] = k;
    k = p;
  }
  const int sourceRoot = k;
  const int sourceLength = length;
  bottleneck = std::min(bottleneck, tr_[k]);
  k = t;
  while (parent[k] != Terminal)
  {
    bottleneck = std::min(bottleneck, cap[4 * k + parent[k]]);
    path[length++] = k;
    k = up[k];
  }
  const int sinkRoot = k;
  bottleneck = std::min(bottleneck, -tr_[k]);

  cap[4 * s + d] -= bottleneck;
  cap[4 * t + (d ^ 1)] += bottleneck;
  // An edge whose residual reaches 0 leaves its child node an orphan.
  for (int e = 0; e < length; ++e)
  {
    k = path[e];
    const int a = parent[k];
    const int down = 4 * up[k] + (a ^ 1); // parent -> k
    const int toUp = 4 * k + a;           // k -> parent
    const bool sourceSide = e < sourceLength;
    cap[sourceSide ? toUp : down] += bottleneck;
    const int used = sourceSide ? down : toUp;
    cap[used] -= bottleneck;
    if (cap[used] <= 0.0)
    {
      parent[k] = Orphan;
      orphans_.push_back(k);
    }
  }
  tr_[sourceRoot] -= bottleneck;
  if (tr_[sourceRoot] <= 0.0)
  {
    parent[sourceRoot] = Orphan;
    orphans_.push_back(sourceRoot);
  }
  tr_[sinkRoot] += bottleneck;
  if (tr_[sinkRoot] >= 0.0)
  {
    parent[sinkRoot] = Orphan;
    orphans_.push_back(sinkRoot);
  }
  flow_ += bottleneck;
}

// Both trees are handled by one body: in the sink tree every edge is used in
// the other direction (child -> parent), which is all that differs.
template<bool Sink>
void GridMaxFlow::processOrphan(int i)
{
  const double* const cap = cap_.data();
  // Residual capacity of the edge from the (candidate) parent j, in direction
  // d ^ 1 from j, down to i.
  auto residual = [&](int d, int j) { return Sink ? cap[4 * i + d] : cap[4 * j + (d ^ 1)]; };
  int bestDir = -1;
  int bestDist = InfiniteDistance;
  for (int d = 0; d < 4; ++d)
  {
    const int first = neighbour(i, d);
    if (parent_[first] == None || sink_[first] != Sink || residual(d, first) <= 0.0)
    {
      continue;
    }
    // Is it still rooted at the terminal? Walk up, using the time stamps as a cache.
    int j = first;
    int dist = 0;
    for (;;)
    {
      if (ts_[j] == time_)
      {
        dist += dist_[j];
        break;
      }
      const int a = parent_[j];
      ++dist;
      if (a == Terminal)
      {
        ts_[j] = time_;
        dist_[j] = 1;
        break;
      }
      if (a == Orphan)
      {
        dist = InfiniteDistance;
        break;
      }
      j = up_[j];
    }
    if (dist < InfiniteDistance)
    {
      if (dist < bestDist)
      {
        bestDir = d;
        bestDist = dist;
      }
      for (j = first; ts_[j] != time_; j = up_[j])
      {
        ts_[j] = time_;
        dist_[j] = dist--;
      }
    }
  }
  if (bestDir >= 0)
  {
    attach(i, bestDir, neighbour(i, bestDir), time_, bestDist + 1);
    return;
  }
  // No valid parent: i becomes free, its children become orphans and the
  // neighbours that could regrow into it become active.
  for (int d = 0; d < 4; ++d)
  {
    const int j = neighbour(i, d);
    const int a = parent_[j];
    if (a == None || sink_[j] != Sink)
    {
      continue;
    }
    if (residual(d, j) > 0.0)
    {
      setActive(j);
    }
    if (a != Terminal && a != Orphan && up_[j] == i)
    {
      parent_[j] = Orphan;
      orphans_.push_back(j);
    }
  }
  parent_[i] = None;
}

// Grows the tree of active node i by one layer; returns the direction from i
// of the first edge found into the other tree, or -1.
template<bool Sink>
int GridMaxFlow::grow(int i)
{
  const double* const cap = cap_.data();
  for (int d = 0; d < 4; ++d)
  {
    const int j = neighbour(i, d);
    // The edge the flow would use: i -> j in the source tree, j -> i in the sink tree.
    if ((Sink ? cap[4 * j + (d ^ 1)] : cap[4 * i + d]) <= 0.0)
    {
      continue;
    }
    if (parent_[j] == None)
    {
      sink_[j] = Sink;
      attach(j, d ^ 1, i, ts_[i], dist_[i] + 1);
      setActive(j);
    }
    else if (sink_[j] != Sink)
    {
      return d;
    }
    else if (ts_[j] <= ts_[i] && dist_[j] > dist_[i])
    {
      // A shorter path to the terminal through i (Kolmogorov's heuristic).
      attach(j, d ^ 1, i, ts_[i], dist_[i] + 1);
    }
  }
  return -1;
}

double GridMaxFlow::solve()
{
  queueFirst_ = queueLast_ = -1;
  time_ = 0;
  orphans_.clear();
  for (int j = 0; j < height_; ++j)
  {
    for (int i = 0; i < width_; ++i)
    {
      const int k = (j + 1) * stride_ + i + 1;
      next_[k] = NotActive;
      ts_[k] = 0;
      dist_[k] = 1;
      parent_[k] = tr_[k] != 0.0 ? Terminal : None;
      sink_[k] = tr_[k] < 0.0;
      if (tr_[k] != 0.0)
      {
        setActive(k);
      }
    }
  }

  int current = -1;
  for (;;)
  {
    int i = current;
    if (i >= 0)
    {
      next_[i] = NotActive;
      if (parent_[i] == None)
      {
        i = -1;
      }
    }
    if (i < 0)
    {
      i = nextActive();
      if (i < 0)
      {
        break;
      }
    }

    // Grow the tree of i; stop at the first edge that reaches the other tree.
    const bool inSink = sink_[i] != 0;
    const int bridge = inSink ? grow<true>(i) : grow<false>(i);
    ++time_;
    if (bridge < 0)
    {
      current = -1;
      continue;
    }
    next_[i] = i; // keep i active without queueing it: it is grown again next
    current = i;
    // The path runs from the source tree to the sink tree.
    if (inSink)
      augment(neighbour(i, bridge), bridge ^ 1);
    else
      augment(i, bridge);
    // Adopt orphans (FIFO; the order only affects speed).
    for (std::size_t o = 0; o < orphans_.size(); ++o)
    {
      const int k = orphans_[o];
      if (sink_[k])
      {
        processOrphan<true>(k);
      }
      else
      {
        processOrphan<false>(k);
      }
    }
    orphans_.clear();
  }
  return flow_;
}

} // namespace tsynth
