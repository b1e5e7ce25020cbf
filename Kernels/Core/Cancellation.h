// Stopping a long kernel from outside (ParaView's abort, Ctrl-C in the command line) without a
// callback in every signature. The caller opens a CancellationScope on its thread with a test
// that says whether to stop; the kernels' long loops poll it, and the poll throws
// tsynth::Cancelled once the test says stop. Without a scope, polling costs a null check.
//
// Polls run on the thread that opened the scope, never inside an OpenMP parallel region (an
// exception must not leave one): parallel loops poll between bands of rows (forRowBands).
#pragma once

#include "Core/Error.h"

#include <algorithm>
#include <atomic>
#include <functional>

namespace tsynth
{

class CancellationScope
{
public:
  // shouldStop is called at most every kCancellationStride polls and between bands.
  explicit CancellationScope(std::function<bool()> shouldStop);
  ~CancellationScope();
  CancellationScope(const CancellationScope&) = delete;
  CancellationScope& operator=(const CancellationScope&) = delete;

private:
  friend void pollCancellationInScope();
  friend bool cancellationRequested();
  std::function<bool()> shouldStop_;
  unsigned polls_ = 0;
  CancellationScope* outer_;
};

// Per-item polls between two tests of shouldStop: a priority flood settles a few million
// cells a second, so this tests a few hundred times a second, well within the one second a
// user waits for a stop.
constexpr unsigned kCancellationStride = 1u << 14;

// How many scopes are open on any thread: the polls' fast path reads only this, so a kernel
// run with no scope (a test, a benchmark) pays one relaxed load per poll.
extern std::atomic<int> openCancellationScopes;

void pollCancellationInScope();

// For loops over cells: throws tsynth::Cancelled when the scope's test (run every
// kCancellationStride calls) says stop.
inline void pollCancellation()
{
  if (openCancellationScopes.load(std::memory_order_relaxed) != 0)
  {
    pollCancellationInScope();
  }
}

// Between stages and bands: runs the scope's test now and throws tsynth::Cancelled if it says
// stop.
void checkCancellation();

// Whether the scope's test says stop now, without throwing: for callbacks that C code calls
// (GDAL's progress function) and that must answer rather than unwind through it.
bool cancellationRequested();

// Rows of a parallel pass per cancellation check: 256 rows of a 5000-cell-wide DEM are a
// few milliseconds of work, and a barrier per band costs far less than that.
constexpr int kCancellationBandRows = 256;

// Runs rowBody(j) for j in [0, rows) as an OpenMP parallel loop (static schedule, so each row
// is done exactly as in one loop), band by band, checking for cancellation between bands.
template<class RowBody>
void forRowBands(int rows, const RowBody& rowBody)
{
  for (int first = 0; first < rows; first += kCancellationBandRows)
  {
    const int last = std::min(rows, first + kCancellationBandRows);
#pragma omp parallel for schedule(static)
    for (int j = first; j < last; ++j)
    {
      rowBody(j);
    }
    checkCancellation();
  }
}

} // namespace tsynth
