#include "Flow.h"

#include "../Core/Cancellation.h"
#include "../Core/Error.h"
#include "../Core/Grid.h"
#include "FloodKeys.h"
#include "RadixHeap.h"

#include <cmath>
#include <limits>
#include <string>

namespace tsynth
{

std::array<double, kD8Directions> d8Distances(double cellX, double cellY)
{
  std::array<double, kD8Directions> d{};
  for (std::size_t c = 0; c < d.size(); ++c)
  {
    d[c] = std::hypot(kD8Dx[c] * cellX, kD8Dy[c] * cellY);
  }
  return d;
}

namespace
{

// The neighbour of cell (i, j) along D8 code `code` (0..7; codes are ints, kNoFlow is -1).
GridCell d8Neighbour(int i, int j, int code)
{
  const std::size_t c = static_cast<std::size_t>(code);
  return { i + kD8Dx[c], j + kD8Dy[c] };
}

bool inGrid(const Heightfield& dem, int i, int j)
{
  return i >= 0 && j >= 0 && i < dem.width && j < dem.height;
}

void checkSinks(const Heightfield& dem, const std::vector<std::uint8_t>* sinks)
{
  if (sinks != nullptr && sinks->size() != dem.size())
  {
    throw Error("The sink mask has " + std::to_string(sinks->size()) +
      " cells but the terrain has " + std::to_string(dem.size()) +
      "; give one byte per terrain cell.");
  }
}

} // namespace

bool isSeedCell(const Heightfield& dem, const std::vector<std::uint8_t>* sinks, int i, int j)
{
  const std::size_t k = dem.index(i, j);
  if (!isUsableCell(dem, k))
  {
    return false;
  }
  if (sinks != nullptr && (*sinks)[k] != 0)
  {
    return true;
  }
  for (int c = 0; c < kD8Directions; ++c)
  {
    const auto [ni, nj] = d8Neighbour(i, j, c);
    if (!inGrid(dem, ni, nj) || !isUsableCell(dem, dem.index(ni, nj)))
    {
      return true;
    }
  }
  return false;
}

namespace
{

// The flood on a copy of the grid with a one-cell frame of closed cells, so
// neighbour loops need no bounds checks. See fillDepressions for the contract.
//
// Order: the cell popped next is the lower of the pit queue's front and the
// priority queue's top, so cells are settled in non-decreasing height as in the
// plain algorithm. A cell reached from one at height h takes max(its height,
// nextafter(h)) from the first neighbour settled, which is then a lowest one;
// ties between equal heights cannot change that value, so the heights equal
// those of a plain priority-queue fill. Cells raised to nextafter(h) join the
// FIFO pit queue (pushed in non-decreasing order, so it stays sorted).
//
// Slopes: a cell strictly higher than a settled neighbour keeps its own height
// whatever else happens (it already drains), so it is settled at once and
// climbs further ("slope" stack) without waiting for its turn; it enters the
// priority queue only if it has an unsettled neighbour no higher than itself,
// which must be raised in flood order.
class PriorityFlood
{
public:
  PriorityFlood(const Heightfield& dem, const std::vector<std::uint8_t>* sinks)
    : width_(dem.width + 2)
    , z_(cellCount(width_, dem.height + 2), 0.0f)
    , closed_(z_.size(), 1)
  {
    int code = 0;
    for (std::ptrdiff_t& o : offsets_)
    {
      o = d8Offset(code++, width_);
    }
    for (int j = 0; j < dem.height; ++j)
    {
      for (int i = 0; i < dem.width; ++i)
      {
        const std::size_t k = dem.index(i, j);
        if (isUsableCell(dem, k)) // invalid cells stay closed: never raised, never a path
        {
          z_[framed(i, j)] = dem.z[k];
          closed_[framed(i, j)] = 0;
        }
      }
    }
    // Seeds: sinks and cells next to a closed one (the frame or an invalid cell).
    std::vector<std::uint32_t> seeds;
    for (int j = 0; j < dem.height; ++j)
    {
      for (int i = 0; i < dem.width; ++i)
      {
        const std::size_t p = framed(i, j);
        if (closed_[p] == 0 &&
          ((sinks != nullptr && (*sinks)[dem.index(i, j)] != 0) || touchesClosed(p)))
        {
          seeds.push_back(static_cast<std::uint32_t>(p));
        }
      }
    }
    for (const std::uint32_t p : seeds)
    {
      closed_[p] = 1;
      heap_.push(floodKey(z_[p], p));
    }
  }

  void run()
  {
    for (;;)
    {
      pollCancellation();
      std::uint32_t cell = 0;
      if (pitHead_ < pit_.size())
      {
        const std::uint32_t front = pit_[pitHead_];
        if (heap_.hasKeyBelow(floodKey(z_[front], 0)))
        {
          cell = cellOfKey(heap_.pop());
        }
        else
        {
          cell = front;
          if (++pitHead_ == pit_.size())
          {
            pit_.clear();
            pitHead_ = 0;
          }
        }
      }
      else if (!heap_.empty())
      {
        cell = cellOfKey(heap_.pop());
      }
      else
      {
        return;
      }
      settleNeighbours(cell);
      climbSlopes();
    }
  }

  void copyTo(Heightfield& out) const
  {
    for (int j = 0; j < out.height; ++j)
    {
      for (int i = 0; i < out.width; ++i)
      {
        const std::size_t k = out.index(i, j);
        if (isUsableCell(out, k))
        {
          out.z[k] = z_[framed(i, j)];
        }
      }
    }
  }

private:
  std::size_t framed(int i, int j) const { return rowMajor(i + 1, j + 1, width_); }

  std::size_t neighbour(std::uint32_t cell, std::size_t code) const
  {
    return offsetCell(cell, offsets_[code]);
  }

  bool touchesClosed(std::size_t p) const
  {
    for (const std::ptrdiff_t o : offsets_)
    {
      if (closed_[offsetCell(p, o)] != 0)
      {
        return true;
      }
    }
    return false;
  }

  // In flood order: raise lower neighbours, settle higher ones as slopes.
  void settleNeighbours(std::uint32_t cell)
  {
    const float h = z_[cell];
    const float raised = raisedAbove(h);
    for (std::size_t c = 0; c < offsets_.size(); ++c)
    {
      const std::size_t n = neighbour(cell, c);
      if (closed_[n] != 0)
      {
        continue;
      }
      closed_[n] = 1;
      if (z_[n] > h)
      {
        slope_.push_back(static_cast<std::uint32_t>(n));
      }
      else
      {
        z_[n] = raised;
        pit_.push_back(static_cast<std::uint32_t>(n));
      }
    }
  }

  void climbSlopes()
  {
    while (!slope_.empty())
    {
      const std::uint32_t cell = slope_.back();
      slope_.pop_back();
      const float h = z_[cell];
      bool lowerOpen = false;
      for (std::size_t c = 0; c < offsets_.size(); ++c)
      {
        const std::size_t n = neighbour(cell, c);
        if (closed_[n] != 0)
        {
          continue;
        }
        if (z_[n] > h)
        {
          closed_[n] = 1;
          slope_.push_back(static_cast<std::uint32_t>(n));
        }
        else
        {
          lowerOpen = true;
        }
      }
      if (lowerOpen)
      {
        heap_.push(floodKey(h, cell));
      }
    }
  }

  int width_;
  std::vector<float> z_;
  std::vector<std::uint8_t> closed_;
  std::array<std::ptrdiff_t, kD8Directions> offsets_{};
  MonotoneRadixHeap heap_;
  std::vector<std::uint32_t> pit_; // FIFO: pit_[pitHead_ ..] are waiting
  std::size_t pitHead_ = 0;
  std::vector<std::uint32_t> slope_;
};

} // namespace

Heightfield fillDepressions(const Heightfield& dem, const std::vector<std::uint8_t>* sinks)
{
  checkSinks(dem, sinks);
  const std::size_t framedCells = cellCount(dem.width + 2, dem.height + 2);
  if (framedCells > std::numeric_limits<std::uint32_t>::max())
  {
    throw Error("The terrain is too large to fill (" + std::to_string(dem.size()) +
      " cells; at most about 4.29 billion); fill it in tiles.");
  }
  PriorityFlood flood(dem, sinks);
  flood.run();
  Heightfield out = dem;
  flood.copyTo(out);
  return out;
}

namespace
{

// Rows below this are not worth a thread team.
constexpr int kParallelRows = 64;

// Steepest strictly-downhill code of cell (i, j), or kNoFlow. `inside` says all
// eight neighbours are on the grid (no bounds checks needed).
std::int8_t steepestDescent(const Heightfield& dem,
  int i,
  int j,
  bool inside,
  const std::array<double, kD8Directions>& distance,
  const std::array<std::ptrdiff_t, kD8Directions>& offset)
{
  const std::size_t k = dem.index(i, j);
  const double h = dem.z[k];
  double steepest = 0.0;
  std::int8_t code = kNoFlow;
  for (int c = 0; c < kD8Directions; ++c)
  {
    const std::size_t u = static_cast<std::size_t>(c); // the code (the result) as a table index
    if (!inside && !inGrid(dem, i + kD8Dx[u], j + kD8Dy[u]))
    {
      continue;
    }
    const std::size_t n = offsetCell(k, offset[u]);
    if (!isUsableCell(dem, n))
    {
      continue;
    }
    const double slope = (h - static_cast<double>(dem.z[n])) / distance[u];
    if (slope > steepest)
    {
      steepest = slope;
      code = static_cast<std::int8_t>(c);
    }
  }
  return code;
}

} // namespace

namespace
{

// Flats that drain (cells without a lower neighbour, joined by equal heights
// to a cell that has one or to a seed) are routed across: a breadth-first walk
// from their exits gives each flat cell the code of the neighbour it was
// reached from, so water takes the shortest way over the flat to its exit.
void routeAcrossFlats(const Heightfield& dem,
  const std::vector<std::uint8_t>* sinks,
  std::vector<std::int8_t>& dir)
{
  auto open = [&](std::size_t k, int i, int j)
  { return dir[k] == kNoFlow && isUsableCell(dem, k) && !isSeedCell(dem, sinks, i, j); };
  auto exit = [&](std::size_t k, int i, int j)
  { return isUsableCell(dem, k) && (dir[k] != kNoFlow || isSeedCell(dem, sinks, i, j)); };
  std::vector<std::uint32_t> queue;
  std::vector<std::uint8_t> queued(dem.size(), 0);
  for (int j = 1; j + 1 < dem.height; ++j)
  {
    for (int i = 1; i + 1 < dem.width; ++i)
    {
      const std::size_t k = dem.index(i, j);
      if (!open(k, i, j))
      {
        continue;
      }
      for (int c = 0; c < kD8Directions; ++c)
      {
        const auto [ni, nj] = d8Neighbour(i, j, c);
        const std::size_t n = dem.index(ni, nj);
        if (dem.z[n] == dem.z[k] && exit(n, ni, nj))
        {
          dir[k] = static_cast<std::int8_t>(c);
          queue.push_back(static_cast<std::uint32_t>(k));
          queued[k] = 1;
          break;
        }
      }
    }
  }
  for (std::size_t head = 0; head < queue.size(); ++head)
  {
    pollCancellation();
    const std::size_t k = queue[head];
    const auto [i, j] = cellOf(k, dem.width);
    for (int c = 0; c < kD8Directions; ++c)
    {
      const auto [ni, nj] = d8Neighbour(i, j, c);
      if (ni < 0 || nj < 0 || ni >= dem.width || nj >= dem.height)
      {
        continue;
      }
      const std::size_t n = dem.index(ni, nj);
      if (queued[n] == 0 && dem.z[n] == dem.z[k] && open(n, ni, nj))
      {
        dir[n] = static_cast<std::int8_t>(oppositeD8(c));
        queue.push_back(static_cast<std::uint32_t>(n));
        queued[n] = 1;
      }
    }
  }
}

} // namespace

std::vector<std::int8_t> flowDirections(const Heightfield& dem,
  const std::vector<std::uint8_t>* sinks)
{
  checkSinks(dem, sinks);
  const std::array<double, kD8Directions> distance = d8Distances(dem.cellX, dem.cellY);
  std::array<std::ptrdiff_t, kD8Directions> offset{};
  int code = 0;
  for (std::ptrdiff_t& o : offset)
  {
    o = d8Offset(code++, dem.width);
  }
  std::vector<std::int8_t> dir(dem.size(), kNoFlow);
#pragma omp parallel for schedule(static) if (dem.height >= kParallelRows)
  for (int j = 0; j < dem.height; ++j)
  {
    const bool innerRow = j > 0 && j + 1 < dem.height;
    for (int i = 0; i < dem.width; ++i)
    {
      if (isUsableCell(dem, dem.index(i, j)))
      {
        const bool inside = innerRow && i > 0 && i + 1 < dem.width;
        dir[dem.index(i, j)] = steepestDescent(dem, i, j, inside, distance, offset);
      }
    }
  }
  routeAcrossFlats(dem, sinks, dir);
  return dir;
}

namespace
{

// Index of the cell `code` points to, after checking it is a valid target.
std::size_t downstreamOf(std::size_t k,
  int code,
  int width,
  int height,
  const std::vector<std::uint8_t>* valid)
{
  if (code < 0 || code >= kD8Directions)
  {
    throw Error("Flow direction " + std::to_string(code) + " at cell " + std::to_string(k) +
      " is not a D8 code (0..7 or -1 for no flow).");
  }
  const GridCell from = cellOf(k, width);
  const auto [i, j] = d8Neighbour(from.i, from.j, code);
  if (i < 0 || j < 0 || i >= width || j >= height)
  {
    throw Error("The flow direction at cell " + std::to_string(k) +
      " points off the grid; directions must come from the same grid.");
  }
  const std::size_t n = rowMajor(i, j, width);
  if (valid != nullptr && (*valid)[n] == 0)
  {
    throw Error("The flow direction at cell " + std::to_string(k) +
      " points into an invalid cell; compute directions with the same mask.");
  }
  return n;
}

} // namespace

std::vector<std::uint32_t> flowAccumulation(const std::vector<std::int8_t>& directions,
  int width,
  int height,
  const std::vector<std::uint8_t>* valid)
{
  const std::size_t n = cellCount(std::max(width, 0), std::max(height, 0));
  if (directions.size() != n || (valid != nullptr && valid->size() != n))
  {
    throw Error("Flow accumulation needs one direction (and one mask byte) per cell of the " +
      std::to_string(width) + " x " + std::to_string(height) + " grid.");
  }
  auto counts = [valid](std::size_t k) { return valid == nullptr || (*valid)[k] != 0; };
  std::vector<std::uint32_t> downstream(n, std::numeric_limits<std::uint32_t>::max());
  std::vector<std::uint8_t> inDegree(n, 0);
  for (std::size_t k = 0; k < n; ++k)
  {
    if (counts(k) && directions[k] != kNoFlow)
    {
      const std::size_t d = downstreamOf(k, directions[k], width, height, valid);
      downstream[k] = static_cast<std::uint32_t>(d);
      ++inDegree[d];
    }
  }
  std::vector<std::uint32_t> acc(n, 0);
  std::vector<std::uint32_t> ready; // cells whose upstream is complete
  std::size_t cells = 0;
  for (std::size_t k = 0; k < n; ++k)
  {
    if (counts(k))
    {
      acc[k] = 1;
      ++cells;
      if (inDegree[k] == 0)
      {
        ready.push_back(static_cast<std::uint32_t>(k));
      }
    }
  }
  std::size_t done = 0;
  while (!ready.empty())
  {
    pollCancellation();
    const std::uint32_t k = ready.back();
    ready.pop_back();
    ++done;
    const std::uint32_t d = downstream[k];
    if (d != std::numeric_limits<std::uint32_t>::max())
    {
      acc[d] += acc[k];
      if (--inDegree[d] == 0)
      {
        ready.push_back(d);
      }
    }
  }
  if (done != cells)
  {
    throw Error("The flow directions form a cycle (" + std::to_string(cells - done) +
      " cells never reach an outlet); compute them on a heightfield with flowDirections.");
  }
  return acc;
}

bool drainsEverywhere(const Heightfield& dem,
  const std::vector<std::uint8_t>* sinks,
  std::size_t* firstBadCell)
{
  checkSinks(dem, sinks);
  std::vector<std::uint8_t> drains(dem.size(), 0);
  std::vector<std::size_t> front;
  for (int j = 0; j < dem.height; ++j)
  {
    for (int i = 0; i < dem.width; ++i)
    {
      const std::size_t k = dem.index(i, j);
      if (!isUsableCell(dem, k))
      {
        continue;
      }
      bool ok = isSeedCell(dem, sinks, i, j);
      for (int c = 0; c < kD8Directions && !ok; ++c)
      {
        const auto [ni, nj] = d8Neighbour(i, j, c);
        ok =
          inGrid(dem, ni, nj) && isUsableCell(dem, dem.index(ni, nj)) && dem.at(ni, nj) < dem.z[k];
      }
      if (ok)
      {
        drains[k] = 1;
        front.push_back(k);
      }
    }
  }
  // Flats: water crosses cells of equal height to one that drains.
  while (!front.empty())
  {
    const std::size_t k = front.back();
    front.pop_back();
    const auto [i, j] = cellOf(k, dem.width);
    for (int c = 0; c < kD8Directions; ++c)
    {
      const auto [ni, nj] = d8Neighbour(i, j, c);
      if (!inGrid(dem, ni, nj))
      {
        continue;
      }
      const std::size_t n = dem.index(ni, nj);
      if (drains[n] == 0 && isUsableCell(dem, n) && dem.z[n] == dem.z[k])
      {
        drains[n] = 1;
        front.push_back(n);
      }
    }
  }
  for (std::size_t k = 0; k < dem.size(); ++k)
  {
    if (drains[k] == 0 && isUsableCell(dem, k))
    {
      if (firstBadCell != nullptr)
      {
        *firstBadCell = k;
      }
      return false;
    }
  }
  return true;
}

std::size_t countPits(const Heightfield& dem)
{
  std::size_t pits = 0;
  for (int j = 1; j + 1 < dem.height; ++j)
  {
    for (int i = 1; i + 1 < dem.width; ++i)
    {
      const std::size_t k = dem.index(i, j);
      if (!isUsableCell(dem, k))
      {
        continue;
      }
      bool pit = true;
      for (int c = 0; c < kD8Directions && pit; ++c)
      {
        const auto [ni, nj] = d8Neighbour(i, j, c);
        const std::size_t n = dem.index(ni, nj);
        pit = isUsableCell(dem, n) && dem.z[n] > dem.z[k];
      }
      pits += pit ? 1 : 0;
    }
  }
  return pits;
}

} // namespace tsynth
