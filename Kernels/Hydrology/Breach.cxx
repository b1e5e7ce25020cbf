#include "Breach.h"

#include "../Core/Cancellation.h"
#include "../Core/Error.h"
#include "../Core/Grid.h"
#include "FloodKeys.h"
#include "Flow.h"
#include "RadixHeap.h"

#include <algorithm>
#include <array>
#include <functional>
#include <limits>
#include <queue>
#include <string>

namespace tsynth
{

namespace
{

// Per-cell state bits of the flood.
constexpr std::uint8_t kClosed = 1;   // reached (or never open: frame, invalid cell)
constexpr std::uint8_t kBlocked = 2;  // frame or invalid cell: never traversed, never changed
constexpr std::uint8_t kUserSink = 4; // in the user's sink mask: kept at its height if possible
constexpr std::uint8_t kLakeTree = 8; // its flow-map chain ends at a user sink
constexpr std::uint8_t kDrains = 16;  // reopened for rerouting but drains already: no carving

constexpr std::int8_t kRoot = -1; // flow-map code of a sink: the chain ends here

// What carving from a cell down to below `target` would do.
struct CarvePlan
{
  std::size_t cells = 0;
  double maxCut = 0.0; // metres below the original surface
  bool lowersUserSink = false;
};

// Soille's breaching flood on a copy of the grid with a one-cell frame of
// blocked cells (as the fill in Flow.cxx), so neighbour loops need no bounds
// checks.
//
// Order: exactly that of one priority queue keyed on (height when reached,
// cell index). Cells reached at or above the level of the last cell taken from
// the radix heap go into it (its keys must not decrease); cells reached below
// that level -- the inside of the depression being entered -- go into a small
// binary heap ("pit" heap) that is emptied first. Every key in the pit heap is
// below that level and every key in the radix heap at or above it, so the
// smallest key overall is always the top of the first non-empty one.
//
// Flow map: each reached cell keeps the D8 code of the cell it was reached
// from; sinks have kRoot. Cells are lowered only along such chains, and only
// cells already expanded are on a chain, so the flood order and the flow map
// depend on the original heights alone.
class BreachFlood
{
public:
  BreachFlood(const Heightfield& dem, const std::vector<std::uint8_t>* sinks, bool keepOriginal)
    : width_(dem.width + 2)
    , z_(cellCount(width_, dem.height + 2), 0.0f)
    , state_(z_.size(), kClosed | kBlocked)
    , from_(z_.size(), kRoot)
  {
    if (z_.size() > std::numeric_limits<std::uint32_t>::max())
    {
      throw Error("The terrain is too large to breach (" + std::to_string(dem.size()) +
        " cells; at most about 4.29 billion); breach it in tiles.");
    }
    for (int c = 0; c < kD8Directions; ++c)
    {
      offsets_[static_cast<std::size_t>(c)] = d8Offset(c, width_);
    }
    for (int j = 0; j < dem.height; ++j)
    {
      for (int i = 0; i < dem.width; ++i)
      {
        const std::size_t k = dem.index(i, j);
        if (isUsableCell(dem, k))
        {
          z_[framed(i, j)] = dem.z[k];
          state_[framed(i, j)] = (sinks != nullptr && (*sinks)[k] != 0) ? kUserSink : 0;
        }
      }
    }
    if (keepOriginal)
    {
      original_ = z_;
    }
    checkCancellation(); // framing a large DEM takes a few tenths of a second
    seedSinks();
  }

  float height(std::size_t p) const { return z_[p]; }
  bool inLakeTree(std::size_t p) const { return (state_[p] & kLakeTree) != 0; }

  // Runs the flood until both heaps are empty. onEvent(p, n) is called when
  // the expanded cell p reaches an open cell n lower than itself that does not
  // drain yet; it may carve or raise, and returns false to leave n open.
  template<class OnEvent>
  void run(OnEvent&& onEvent)
  {
    for (;;)
    {
      pollCancellation();
      std::uint64_t key = 0;
      if (!pit_.empty())
      {
        key = pit_.top();
        pit_.pop();
      }
      else if (!heap_.empty())
      {
        key = heap_.pop();
        level_ = key;
        levelHeight_ = z_[cellOfKey(key)];
        depression_ = kNone;
      }
      else
      {
        return;
      }
      expand(cellOfKey(key), onEvent);
    }
  }

  // Carving from p along the flow map: each cell that is not already below the
  // running level goes one float step below it, until a lower cell or a sink.
  CarvePlan plan(std::size_t p, float target) const
  {
    CarvePlan r;
    float z = target;
    for (std::size_t q = p; z_[q] >= z; q = parent(q))
    {
      z = loweredBelow(z);
      ++r.cells;
      if (!original_.empty())
      {
        r.maxCut = std::max(r.maxCut, static_cast<double>(original_[q]) - z);
      }
      r.lowersUserSink = r.lowersUserSink || (state_[q] & kUserSink) != 0;
      if (from_[q] == kRoot)
      {
        break;
      }
    }
    return r;
  }

  void carve(std::size_t p, float target)
  {
    float z = target;
    for (std::size_t q = p; z_[q] >= z; q = parent(q))
    {
      z = loweredBelow(z);
      z_[q] = z;
      if (from_[q] == kRoot)
      {
        return;
      }
    }
  }

  // The epsilon fill's step: n one float step above p.
  void raiseAbove(std::size_t n, std::size_t p) { z_[n] = raisedAbove(z_[p]); }

  // Rerouting (after cells were left open because draining them would lower a
  // user sink): every cell reached only through user sinks is opened again as
  // already draining, and the flood restarts from the cells that drain to the
  // other sinks next to the open region, so the stranded pits get channels to
  // those sinks instead. Returns false if nothing was left open.
  bool reopenLakeTrees()
  {
    if (!hasOpenCells())
    {
      return false;
    }
    for (std::uint8_t& s : state_)
    {
      if ((s & (kClosed | kBlocked | kUserSink | kLakeTree)) == (kClosed | kLakeTree))
      {
        s = static_cast<std::uint8_t>((s & ~kClosed) | kDrains);
      }
    }
    restartFrom([this](std::size_t p) { return !inLakeTree(p); });
    return true;
  }

  // Last resort, for open cells whose region touches no other sink (the user
  // marked every outlet): restart from every reached cell next to them; their
  // channels may then lower a user sink. Returns false if nothing is open.
  bool reseedAroundOpenCells()
  {
    if (!hasOpenCells())
    {
      return false;
    }
    restartFrom([](std::size_t) { return true; });
    return true;
  }

  // Depressions met so far (hybrid bookkeeping): the one being flooded now,
  // created by its first carve, and the one each cell reached below the flood
  // level after that carve belongs to.
  void trackDepressions() { depressionOf_.assign(z_.size(), kNone); }
  std::uint32_t currentDepression()
  {
    if (depression_ == kNone)
    {
      depressions_.emplace_back();
      depression_ = static_cast<std::uint32_t>(depressions_.size() - 1);
      depressions_.back().spill = levelHeight_;
    }
    return depression_;
  }
  std::vector<DepressionChannel>& depressions() { return depressions_; }
  std::vector<std::uint32_t>& depressionOf() { return depressionOf_; }

  void copyTo(Heightfield& out) const
  {
    for (int j = 0; j < out.height; ++j)
    {
      for (int i = 0; i < out.width; ++i)
      {
        if (isUsableCell(out, out.index(i, j)))
        {
          out.z[out.index(i, j)] = z_[framed(i, j)];
        }
      }
    }
  }

  static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

private:
  std::size_t framed(int i, int j) const { return rowMajor(i + 1, j + 1, width_); }

  std::size_t neighbour(std::size_t p, std::size_t code) const
  {
    return offsetCell(p, offsets_[code]);
  }

  std::size_t parent(std::size_t q) const
  {
    return neighbour(q, static_cast<std::size_t>(from_[q]));
  }

  bool touches(std::size_t p, std::uint8_t bits, std::uint8_t value) const
  {
    for (std::size_t c = 0; c < offsets_.size(); ++c)
    {
      if ((state_[neighbour(p, c)] & bits) == value)
      {
        return true;
      }
    }
    return false;
  }

  // Seeds as isSeedCell: user sinks and cells next to a blocked one.
  void seedSinks()
  {
    std::vector<std::size_t> seeds;
    for (std::size_t p = 0; p < z_.size(); ++p)
    {
      if ((state_[p] & kBlocked) == 0 &&
        ((state_[p] & kUserSink) != 0 || touches(p, kBlocked, kBlocked)))
      {
        seeds.push_back(p);
      }
    }
    for (const std::size_t p : seeds)
    {
      state_[p] |= kClosed;
      if ((state_[p] & kUserSink) != 0)
      {
        state_[p] |= kLakeTree;
      }
      push(p);
    }
  }

  bool hasOpenCells() const
  {
    return std::any_of(
      state_.begin(), state_.end(), [](std::uint8_t s) { return (s & kClosed) == 0; });
  }

  // A new flood whose seeds are the reached cells next to an open one that
  // `accept` takes, at their present heights (they drain already).
  void restartFrom(const std::function<bool(std::size_t)>& accept)
  {
    heap_ = MonotoneRadixHeap();
    level_ = 0;
    std::vector<std::size_t> seeds;
    for (std::size_t p = 0; p < z_.size(); ++p)
    {
      if ((state_[p] & (kClosed | kBlocked)) == kClosed && touches(p, kClosed, 0) && accept(p))
      {
        seeds.push_back(p);
      }
    }
    for (const std::size_t p : seeds)
    {
      push(p);
    }
  }

  template<class OnEvent>
  void expand(std::size_t p, OnEvent& onEvent)
  {
    for (std::size_t c = 0; c < offsets_.size(); ++c)
    {
      const std::size_t n = neighbour(p, c);
      if ((state_[n] & kClosed) != 0)
      {
        continue;
      }
      // z_[p] is read again each time: a carve for an earlier neighbour may have lowered p.
      if (z_[n] < z_[p] && (state_[n] & kDrains) == 0 && !onEvent(p, n))
      {
        continue;
      }
      state_[n] =
        static_cast<std::uint8_t>((state_[n] & ~kLakeTree) | (state_[p] & kLakeTree) | kClosed);
      from_[n] = static_cast<std::int8_t>(oppositeD8(static_cast<int>(c)));
      push(n);
    }
  }

  void push(std::size_t p)
  {
    const std::uint64_t key = floodKey(z_[p], static_cast<std::uint32_t>(p));
    if (key < level_)
    {
      pit_.push(key);
      // A depression starts at its first carve: cells at the level of a flat
      // enter the pit heap too (smaller index) but need no channel.
      if (!depressionOf_.empty() && depression_ != kNone)
      {
        const std::uint32_t d = currentDepression();
        depressionOf_[p] = d;
        ++depressions_[d].cells;
      }
      return;
    }
    heap_.push(key);
  }

  int width_;
  std::vector<float> z_;
  std::vector<float> original_; // only when cuts are measured (hybrid, survey)
  std::vector<std::uint8_t> state_;
  std::vector<std::int8_t> from_;
  std::array<std::ptrdiff_t, kD8Directions> offsets_{};
  MonotoneRadixHeap heap_;
  std::priority_queue<std::uint64_t, std::vector<std::uint64_t>, std::greater<>> pit_;
  std::uint64_t level_ = 0; // key of the last cell taken from the radix heap
  float levelHeight_ = 0.0f;
  std::uint32_t depression_ = kNone;
  std::vector<DepressionChannel> depressions_;
  std::vector<std::uint32_t> depressionOf_;
};

} // namespace

Heightfield breachFlood(const Heightfield& dem, const std::vector<std::uint8_t>* sinks)
{
  BreachFlood flood(dem, sinks, false);
  // Keep user sinks: a pit whose channel would have to lower one is left open.
  flood.run(
    [&flood](std::size_t p, std::size_t n)
    {
      if (flood.inLakeTree(p) && flood.plan(p, flood.height(n)).lowersUserSink)
      {
        return false;
      }
      flood.carve(p, flood.height(n));
      return true;
    });
  auto carveAlways = [&flood](std::size_t p, std::size_t n)
  {
    flood.carve(p, flood.height(n));
    return true;
  };
  if (flood.reopenLakeTrees())
  {
    flood.run(carveAlways);
    if (flood.reseedAroundOpenCells())
    {
      flood.run(carveAlways);
    }
  }
  Heightfield out = dem;
  flood.copyTo(out);
  return out;
}

namespace
{

bool withinLimits(double cut,
  std::size_t length,
  bool lowersUserSink,
  double maxDepth,
  std::size_t maxLength)
{
  return !lowersUserSink && cut <= maxDepth && length <= maxLength;
}

// Complete breaching that notes, for each depression, the deepest cut and the
// longest carve its channel needs (user sinks may be lowered: this only measures).
void surveyRun(BreachFlood& flood)
{
  flood.trackDepressions();
  flood.run(
    [&flood](std::size_t p, std::size_t n)
    {
      const CarvePlan plan = flood.plan(p, flood.height(n));
      DepressionChannel& d = flood.depressions()[flood.currentDepression()];
      d.maxCut = std::max(d.maxCut, plan.maxCut);
      d.maxLength = std::max(d.maxLength, plan.cells);
      d.lowersUserSink = d.lowersUserSink || plan.lowersUserSink;
      flood.carve(p, flood.height(n));
      return true;
    });
}

} // namespace

std::vector<DepressionChannel> surveyDepressions(const Heightfield& dem,
  const std::vector<std::uint8_t>* sinks)
{
  BreachFlood flood(dem, sinks, true);
  surveyRun(flood);
  return std::move(flood.depressions());
}

Heightfield hybridFlood(const Heightfield& dem,
  double maxBreachDepth,
  std::size_t maxBreachLength,
  const std::vector<std::uint8_t>* sinks)
{
  // 1. The channel complete breaching would carve for each depression, and
  // the depression of each cell below a spill level.
  std::vector<std::uint8_t> breachIt;
  std::vector<std::uint32_t> depressionOf;
  {
    BreachFlood survey(dem, sinks, true);
    surveyRun(survey);
    for (const DepressionChannel& d : survey.depressions())
    {
      breachIt.push_back(
        withinLimits(d.maxCut, d.maxLength, d.lowersUserSink, maxBreachDepth, maxBreachLength) ? 1
                                                                                               : 0);
    }
    depressionOf = std::move(survey.depressionOf());
  }
  // 2. The same flood again: depressions within the limits are carved as
  // before, the others filled (each cell reached below the flood level goes one
  // float step above the cell it was reached from, and floods on from there,
  // as the epsilon fill). A carve that would now break a limit -- its path can
  // differ where it crosses a filled depression -- fills its cell instead.
  BreachFlood flood(dem, sinks, true);
  flood.run(
    [&](std::size_t p, std::size_t n)
    {
      const std::uint32_t d = depressionOf[n];
      if (d == BreachFlood::kNone || breachIt[d] != 0)
      {
        const CarvePlan plan = flood.plan(p, flood.height(n));
        if (withinLimits(
              plan.maxCut, plan.cells, plan.lowersUserSink, maxBreachDepth, maxBreachLength))
        {
          flood.carve(p, flood.height(n));
          return true;
        }
      }
      flood.raiseAbove(n, p);
      return true;
    });
  Heightfield out = dem;
  flood.copyTo(out);
  return out;
}

} // namespace tsynth
