#include "DistanceMemory.h"

#include "../Core/Memory.h"
#include "DistanceSynthesis.h"

#include <omp.h>

namespace tsynth
{
namespace
{

// Peak resident memory of `tsynth distance` measured with /usr/bin/time -v on
// two threads: one poly-line (--size) 177 / 453 / 1558 MB at 1024^2 / 2048^2 /
// 4096^2 cells; mountain_range_strokes scaled up with its profiles and 60
// dendritic ridges 236 / 578 / 1860 MB; 400 dots at 2048^2 538 MB and 1600 at
// 4096^2 1734 MB. That is 88 to 108 bytes a cell (16 of them the two
// threads' search fields) and about 85 MB before any cell. Rounded up:
constexpr double kDistanceBaseBytes = 128.0e6;
constexpr double kBytesPerCell = 100.0;
constexpr double kBytesPerCellAndThread = 8.0; // a search field: cost and source

} // namespace

double distanceMemoryEstimate(int width, int height, int threads)
{
  const double cells = static_cast<double>(width) * static_cast<double>(height);
  return kDistanceBaseBytes + cells * (kBytesPerCell + kBytesPerCellAndThread * threads);
}

void checkDistanceMemory(const DistanceInputs& in, const DistanceOptions& o)
{
  checkMemoryBudget(distanceMemoryEstimate(in.width, in.height, omp_get_max_threads()),
    o.memoryBudget,
    "This distance synthesis of " + std::to_string(in.width) + " x " + std::to_string(in.height) +
      " cells",
    "give a smaller " + o.sizeOption,
    o.memoryOption);
}

} // namespace tsynth
