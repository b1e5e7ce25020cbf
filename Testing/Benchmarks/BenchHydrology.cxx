// Hydrology on a 4096 x 4096 real terrain (a bundled DEM mirror-tiled):
// depression filling, D8 directions and flow accumulation, with the fill's
// ratio to a plain priority-queue epsilon fill (Barnes et al. 2014, Algorithm
// "Priority-Flood+epsilon" without the pit queue) written here as the
// reference, and a check that both give the same heights bit for bit.
// Usage: tsynth_bench_hydrology [DEM] [size] [repetitions]
#include "BenchUtilities.h"
#include "Core/HeightfieldIO.h"
#include "Hydrology/Flow.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>
#include <queue>
#include <string>
#include <utility>
#include <vector>

using namespace tsynth;
using Clock = std::chrono::steady_clock;

namespace
{

// Best wall-clock seconds of `repetitions` calls.
double bestSeconds(int repetitions, const std::function<void()>& f)
{
  double best = std::numeric_limits<double>::infinity();
  for (int r = 0; r < repetitions; ++r)
  {
    const auto t0 = Clock::now();
    f();
    best = std::min(best, std::chrono::duration<double>(Clock::now() - t0).count());
  }
  return best;
}

// The textbook epsilon fill: one std::priority_queue of (height, cell), border
// cells as seeds, every reached cell raised to at least one float step above
// the cell it was reached from. Assumes every cell is valid (a mirror tile is).
std::vector<float> referenceFill(const Heightfield& dem)
{
  std::vector<float> z = dem.z;
  std::vector<std::uint8_t> closed(z.size(), 0);
  using Item = std::pair<float, std::uint32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  for (int j = 0; j < dem.height; ++j)
  {
    for (int i = 0; i < dem.width; ++i)
    {
      if (i == 0 || j == 0 || i == dem.width - 1 || j == dem.height - 1)
      {
        const std::size_t k = dem.index(i, j);
        closed[k] = 1;
        open.push({ z[k], static_cast<std::uint32_t>(k) });
      }
    }
  }
  while (!open.empty())
  {
    const std::uint32_t c = open.top().second;
    open.pop();
    const int ci = static_cast<int>(c % static_cast<std::uint32_t>(dem.width));
    const int cj = static_cast<int>(c / static_cast<std::uint32_t>(dem.width));
    const float raised = std::nextafter(z[c], std::numeric_limits<float>::infinity());
    for (int d = 0; d < kD8Directions; ++d)
    {
      const int ni = ci + kD8Dx[static_cast<std::size_t>(d)];
      const int nj = cj + kD8Dy[static_cast<std::size_t>(d)];
      if (ni < 0 || nj < 0 || ni >= dem.width || nj >= dem.height)
      {
        continue;
      }
      const std::size_t n = dem.index(ni, nj);
      if (closed[n] != 0)
      {
        continue;
      }
      closed[n] = 1;
      z[n] = std::max(z[n], raised);
      open.push({ z[n], static_cast<std::uint32_t>(n) });
    }
  }
  return z;
}

} // namespace

int main(int argc, char** argv)
{
  const std::string path =
    argc > 1 ? argv[1] : std::string(TSYNTH_BUNDLED_DATA) + "/dems/colorado.png";
  const int size = argc > 2 ? std::max(3, std::atoi(argv[2])) : 4096;
  const int repetitions = argc > 3 ? std::max(1, std::atoi(argv[3])) : 3;
  const Heightfield dem = bench::mirrorTile(readHeightfield(path), size);
  std::printf("Hydrology benchmark: %s mirror-tiled to %d x %d (%.1f M cells), best of %d, "
              "%d threads\n",
    path.c_str(),
    dem.width,
    dem.height,
    1e-6 * static_cast<double>(dem.size()),
    repetitions,
    omp_get_max_threads());

  Heightfield filled;
  std::vector<std::int8_t> dir;
  std::vector<std::uint32_t> acc;
  std::vector<float> reference;
  const double fill = bestSeconds(repetitions, [&] { filled = fillDepressions(dem); });
  const double d8 = bestSeconds(repetitions, [&] { dir = flowDirections(filled); });
  const double accumulate =
    bestSeconds(repetitions, [&] { acc = flowAccumulation(dir, dem.width, dem.height); });
  const double plain = bestSeconds(repetitions, [&] { reference = referenceFill(dem); });

  std::size_t raised = 0;
  std::size_t differ = 0;
  for (std::size_t k = 0; k < dem.size(); ++k)
  {
    raised += filled.z[k] != dem.z[k] ? 1 : 0;
    differ += filled.z[k] != reference[k] ? 1 : 0;
  }
  const bool drains = drainsEverywhere(filled, nullptr);
  std::printf("\n%-34s %10s\n", "step", "ms");
  std::printf("%-34s %10.1f\n", "fill (ours)", 1e3 * fill);
  std::printf("%-34s %10.1f\n", "D8 directions", 1e3 * d8);
  std::printf("%-34s %10.1f\n", "flow accumulation", 1e3 * accumulate);
  std::printf("%-34s %10.1f\n", "fill + D8 + accumulation", 1e3 * (fill + d8 + accumulate));
  std::printf("%-34s %10.1f\n", "reference priority-queue fill", 1e3 * plain);
  std::printf("\npits before %zu, after %zu; cells raised %zu (%.2f%%); drains everywhere: %s\n",
    countPits(dem),
    countPits(filled),
    raised,
    100.0 * static_cast<double>(raised) / static_cast<double>(dem.size()),
    drains ? "yes" : "NO");
  std::printf("largest accumulation %u cells\n", *std::max_element(acc.begin(), acc.end()));
  std::printf("fill vs reference: %.2fx faster; heights differing: %zu\n", plain / fill, differ);
  std::printf(
    "fill + D8 + accumulation vs reference fill alone: %.2fx\n", plain / (fill + d8 + accumulate));
  return differ == 0 && drains ? 0 : 1;
}
