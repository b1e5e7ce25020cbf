// The exact distance transform (Kernels/Distance/DistanceField.h) at terrain
// size: a 4096^2 mask of random strokes, like a large sketch's line cells.
// Prints the best of five for the distances alone and for distances with the
// nearest seeds, their ratio, and how much each call adds to the peak resident
// memory. Run the same binary against another build's library to compare
// builds: LD_LIBRARY_PATH=OTHER/build/lib ./tsynth_bench_distance_field
//   tsynth_bench_distance_field [SIZE [STROKES]]
#include "BenchUtilities.h"
#include "Distance/DistanceField.h"

#include <cstdio>
#include <cstdlib>
#include <random>
#include <sys/resource.h>
#include <vector>

namespace
{

constexpr int kRepetitions = 5;
// A stroke: this many cells, each one step east and 0..2 steps north of the last.
constexpr int kStrokeCells = 200;

std::vector<std::uint8_t> strokeMask(int size, int strokes)
{
  const std::size_t n = static_cast<std::size_t>(size);
  std::vector<std::uint8_t> mask(n * n, 0);
  std::mt19937 random(1);
  for (int k = 0; k < strokes; ++k)
  {
    std::size_t x = random() % n, y = random() % n;
    for (int t = 0; t < kStrokeCells; ++t)
    {
      mask[y * n + x] = 1;
      x = (x + 1) % n;
      y = (y + random() % 3) % n;
    }
  }
  return mask;
}

double peakResidentMB()
{
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0; // kB on Linux
}

} // namespace

int main(int argc, char** argv)
{
  const int size = argc > 1 ? std::atoi(argv[1]) : 4096;
  const int strokes = argc > 2 ? std::atoi(argv[2]) : 2000;
  if (size < 2 || strokes < 1)
  {
    std::fprintf(stderr, "usage: tsynth_bench_distance_field [SIZE >= 2 [STROKES >= 1]]\n");
    return 2;
  }
  const auto mask = strokeMask(size, strokes);
  const double planeMB = static_cast<double>(mask.size()) * sizeof(float) / 1048576.0;
  const double before = peakResidentMB();
  float checksum = 0.0F;
  const double distancesOnly = tsynth::bench::bestSeconds(kRepetitions,
    [&]
    {
      const auto d = tsynth::distanceTransform(mask, size, size);
      checksum += d[d.size() / 3];
    });
  const double afterDistances = peakResidentMB();
  const double withNearest = tsynth::bench::bestSeconds(kRepetitions,
    [&]
    {
      const auto o = tsynth::nearestSeeds(mask, size, size);
      checksum += o.distance[o.distance.size() / 3] + static_cast<float>(o.nearest[7] % 2);
    });
  const double afterNearest = peakResidentMB();
  std::printf("%d^2 cells, %d strokes (one float plane: %.0f MB), best of %d\n",
    size,
    strokes,
    planeMB,
    kRepetitions);
  std::printf("distanceTransform  %.3f s, peak grew %.0f MB (%.1f planes)\n",
    distancesOnly,
    afterDistances - before,
    (afterDistances - before) / planeMB);
  std::printf("nearestSeeds       %.3f s, peak grew %.0f MB more\n",
    withNearest,
    afterNearest - afterDistances);
  std::printf("ratio nearestSeeds / distanceTransform: %.2f (checksum %g)\n",
    withNearest / distancesOnly,
    static_cast<double>(checksum));
  return 0;
}
