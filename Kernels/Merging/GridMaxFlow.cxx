#include "GridMaxFlow.h"

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
  const std::size_t n = static_cast<std::size_t>(stride_) * static_cast<std::size_t>(height_ + 2);
  offset_[PlusX] = 1;
  offset_[MinusX] = -1;
  offset_[PlusY] = stride_;
  offset_[MinusY] = -stride_;
  // assign() reuses the capacity of earlier, larger problems.
  cap_.assign(4 * n, 0.0);
  tr_.assign(n, 0.0);
  parent_.assign(n, None);
  sink_.assign(n, 0);
  next_.assign(n, NotActive);
  ts_.assign(n, 0);
  dist_.assign(n, 0);
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

void GridMaxFlow::setEdge(int k, Direction d, double forward, double backward)
{
  const int n = inner(k);
  const int m = neighbour(n, d);
  cap_[4 * n + d] = forward;
  cap_[4 * m + (d ^ 1)] = backward;
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

void GridMaxFlow::augment(int s, int d)
{
  const int t = neighbour(s, d);
  // Bottleneck along source tree -> bridge -> sink tree.
  double bottleneck = cap_[4 * s + d];
  int k = s;
  while (parent_[k] != Terminal)
  {
    const int a = parent_[k];
    const int p = neighbour(k, a);
    bottleneck = std::min(bottleneck, cap_[4 * p + (a ^ 1)]);
    k = p;
  }
  bottleneck = std::min(bottleneck, tr_[k]);
  k = t;
  while (parent_[k] != Terminal)
  {
    const int a = parent_[k];
    bottleneck = std::min(bottleneck, cap_[4 * k + a]);
    k = neighbour(k, a);
  }
  bottleneck = std::min(bottleneck, -tr_[k]);

  cap_[4 * s + d] -= bottleneck;
  cap_[4 * t + (d ^ 1)] += bottleneck;
  k = s;
  while (parent_[k] != Terminal)
  {
    const int a = parent_[k];
    const int p = neighbour(k, a);
    cap_[4 * k + a] += bottleneck;
    cap_[4 * p + (a ^ 1)] -= bottleneck;
    if (cap_[4 * p + (a ^ 1)] <= 0.0)
    {
      parent_[k] = Orphan;
      orphans_.push_back(k);
    }
    k = p;
  }
  tr_[k] -= bottleneck;
  if (tr_[k] <= 0.0)
  {
    parent_[k] = Orphan;
    orphans_.push_back(k);
  }
  k = t;
  while (parent_[k] != Terminal)
  {
    const int a = parent_[k];
    const int p = neighbour(k, a);
    cap_[4 * p + (a ^ 1)] += bottleneck;
    cap_[4 * k + a] -= bottleneck;
    if (cap_[4 * k + a] <= 0.0)
    {
      parent_[k] = Orphan;
      orphans_.push_back(k);
    }
    k = p;
  }
  tr_[k] += bottleneck;
  if (tr_[k] >= 0.0)
  {
    parent_[k] = Orphan;
    orphans_.push_back(k);
  }
  flow_ += bottleneck;
}

void GridMaxFlow::processSourceOrphan(int i)
{
  int bestDir = -1;
  int bestDist = InfiniteDistance;
  for (int d = 0; d < 4; ++d)
  {
    int j = neighbour(i, d);
    if (cap_[4 * j + (d ^ 1)] <= 0.0 || sink_[j] || parent_[j] == None)
    {
      continue;
    }
    // Is j still rooted at the source? Walk up, using the time stamps as a cache.
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
      j = neighbour(j, a);
    }
    if (dist < InfiniteDistance)
    {
      if (dist < bestDist)
      {
        bestDir = d;
        bestDist = dist;
      }
      for (j = neighbour(i, d); ts_[j] != time_; j = neighbour(j, parent_[j]))
      {
        ts_[j] = time_;
        dist_[j] = dist--;
      }
    }
  }
  if (bestDir >= 0)
  {
    parent_[i] = static_cast<std::int8_t>(bestDir);
    ts_[i] = time_;
    dist_[i] = bestDist + 1;
    return;
  }
  // No valid parent: i becomes free, its children become orphans.
  for (int d = 0; d < 4; ++d)
  {
    const int j = neighbour(i, d);
    const int a = parent_[j];
    if (sink_[j] || a == None)
    {
      continue;
    }
    if (cap_[4 * j + (d ^ 1)] > 0.0)
    {
      setActive(j);
    }
    if (a != Terminal && a != Orphan && neighbour(j, a) == i)
    {
      parent_[j] = Orphan;
      orphans_.push_back(j);
    }
  }
  parent_[i] = None;
}

void GridMaxFlow::processSinkOrphan(int i)
{
  int bestDir = -1;
  int bestDist = InfiniteDistance;
  for (int d = 0; d < 4; ++d)
  {
    int j = neighbour(i, d);
    if (cap_[4 * i + d] <= 0.0 || !sink_[j] || parent_[j] == None)
    {
      continue;
    }
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
      j = neighbour(j, a);
    }
    if (dist < InfiniteDistance)
    {
      if (dist < bestDist)
      {
        bestDir = d;
        bestDist = dist;
      }
      for (j = neighbour(i, d); ts_[j] != time_; j = neighbour(j, parent_[j]))
      {
        ts_[j] = time_;
        dist_[j] = dist--;
      }
    }
  }
  if (bestDir >= 0)
  {
    parent_[i] = static_cast<std::int8_t>(bestDir);
    ts_[i] = time_;
    dist_[i] = bestDist + 1;
    return;
  }
  for (int d = 0; d < 4; ++d)
  {
    const int j = neighbour(i, d);
    const int a = parent_[j];
    if (!sink_[j] || a == None)
    {
      continue;
    }
    if (cap_[4 * i + d] > 0.0)
    {
      setActive(j);
    }
    if (a != Terminal && a != Orphan && neighbour(j, a) == i)
    {
      parent_[j] = Orphan;
      orphans_.push_back(j);
    }
  }
  parent_[i] = None;
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
      if (tr_[k] > 0.0)
      {
        sink_[k] = 0;
        parent_[k] = Terminal;
        dist_[k] = 1;
        setActive(k);
      }
      else if (tr_[k] < 0.0)
      {
        sink_[k] = 1;
        parent_[k] = Terminal;
        dist_[k] = 1;
        setActive(k);
      }
      else
      {
        parent_[k] = None;
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
    int bridgeFrom = -1;
    int bridgeDir = -1;
    if (!sink_[i])
    {
      for (int d = 0; d < 4; ++d)
      {
        if (cap_[4 * i + d] <= 0.0)
        {
          continue;
        }
        const int j = neighbour(i, d);
        if (parent_[j] == None)
        {
          sink_[j] = 0;
          parent_[j] = static_cast<std::int8_t>(d ^ 1);
          ts_[j] = ts_[i];
          dist_[j] = dist_[i] + 1;
          setActive(j);
        }
        else if (sink_[j])
        {
          bridgeFrom = i;
          bridgeDir = d;
          break;
        }
        else if (ts_[j] <= ts_[i] && dist_[j] > dist_[i])
        {
          parent_[j] = static_cast<std::int8_t>(d ^ 1);
          ts_[j] = ts_[i];
          dist_[j] = dist_[i] + 1;
        }
      }
    }
    else
    {
      for (int d = 0; d < 4; ++d)
      {
        const int j = neighbour(i, d);
        if (cap_[4 * j + (d ^ 1)] <= 0.0)
        {
          continue;
        }
        if (parent_[j] == None)
        {
          sink_[j] = 1;
          parent_[j] = static_cast<std::int8_t>(d ^ 1);
          ts_[j] = ts_[i];
          dist_[j] = dist_[i] + 1;
          setActive(j);
        }
        else if (!sink_[j])
        {
          bridgeFrom = j;
          bridgeDir = d ^ 1;
          break;
        }
        else if (ts_[j] <= ts_[i] && dist_[j] > dist_[i])
        {
          parent_[j] = static_cast<std::int8_t>(d ^ 1);
          ts_[j] = ts_[i];
          dist_[j] = dist_[i] + 1;
        }
      }
    }

    ++time_;
    if (bridgeFrom < 0)
    {
      current = -1;
      continue;
    }
    next_[i] = i; // keep i active without queueing it: it is grown again next
    current = i;
    augment(bridgeFrom, bridgeDir);
    // Adopt orphans (FIFO; the order only affects speed).
    for (std::size_t o = 0; o < orphans_.size(); ++o)
    {
      const int k = orphans_[o];
      if (sink_[k])
      {
        processSinkOrphan(k);
      }
      else
      {
        processSourceOrphan(k);
      }
    }
    orphans_.clear();
  }
  return flow_;
}

} // namespace tsynth
