// Hydrology on a 4096 x 4096 real terrain (a bundled DEM mirror-tiled):
// depression filling, breaching and the hybrid, D8 directions and flow
// accumulation, with each pit removal's ratio to a plain priority-queue epsilon
// fill (Barnes et al. 2014, Algorithm "Priority-Flood+epsilon" without the pit
// queue) written here as the reference, a check that the fill gives the same
// heights bit for bit, and the pit-free check on every result.
// Usage: tsynth_bench_hydrology [DEM] [size] [repetitions]
//        tsynth_bench_hydrology --survey DEM...   (the hybrid's limits on native-size DEMs)
#include "BenchUtilities.h"
#include "Core/HeightfieldIO.h"
#include "Hydrology/Breach.h"
#include "Hydrology/Flow.h"
#include "Hydrology/PitRemoval.h"

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
using bench::bestSeconds;

namespace
{
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

// Cells changed by a pit removal: raised, lowered, and the volumes (cells x metres).
struct Changes
{
  std::size_t raised = 0;
  std::size_t lowered = 0;
  double raisedVolume = 0.0;
  double loweredVolume = 0.0;
};

Changes changesOf(const Heightfield& before, const Heightfield& after)
{
  Changes c;
  for (std::size_t k = 0; k < before.size(); ++k)
  {
    const double d = static_cast<double>(after.z[k]) - before.z[k];
    if (d > 0.0)
    {
      ++c.raised;
      c.raisedVolume += d;
    }
    else if (d < 0.0)
    {
      ++c.lowered;
      c.loweredVolume -= d;
    }
  }
  return c;
}

// Candidate hybrid limits (depth in metres, length in cells).
constexpr double kSurveyDepths[] = { 1.0, 2.0, 5.0, 10.0, 20.0, 50.0 };
constexpr int kSurveyLengths[] = { 10, 20, 50, 100, 1000000 };

// For each DEM: how many depressions each pair of limits breaches, and the
// cells and volumes the hybrid then cuts and fills, next to fill and breach.
int survey(int argc, char** argv)
{
  for (int a = 2; a < argc; ++a)
  {
    const Heightfield dem = readHeightfield(argv[a]);
    const std::vector<DepressionChannel> channels = surveyDepressions(dem, nullptr);
    const Changes fill = changesOf(dem, fillDepressions(dem));
    const Changes breach = changesOf(dem, breachDepressions(dem));
    std::printf(
      "\n%s: %d x %d, %.1f m cells, %zu depressions; fill raises %zu cells (%.0f cell-metres), "
      "breach lowers %zu (%.0f)\n",
      argv[a],
      dem.width,
      dem.height,
      dem.cellX,
      channels.size(),
      fill.raised,
      fill.raisedVolume,
      breach.lowered,
      breach.loweredVolume);
    std::vector<double> cuts;
    std::vector<double> lengths;
    for (const DepressionChannel& c : channels)
    {
      cuts.push_back(c.maxCut);
      lengths.push_back(static_cast<double>(c.maxLength));
    }
    std::sort(cuts.begin(), cuts.end());
    std::sort(lengths.begin(), lengths.end());
    auto q = [](const std::vector<double>& v, double p) {
      return v.empty() ? 0.0 : v[static_cast<std::size_t>(p * static_cast<double>(v.size() - 1))];
    };
    std::printf("  cut m   p50 %.2f p90 %.2f p99 %.2f max %.2f; length cells p50 %.0f p90 %.0f p99 "
                "%.0f max %.0f\n",
      q(cuts, 0.5),
      q(cuts, 0.9),
      q(cuts, 0.99),
      q(cuts, 1.0),
      q(lengths, 0.5),
      q(lengths, 0.9),
      q(lengths, 0.99),
      q(lengths, 1.0));
    std::printf("  %8s %8s %9s %9s %9s %11s %9s %11s %6s\n",
      "depth",
      "length",
      "breached",
      "filled",
      "lowered",
      "cut vol",
      "raised",
      "fill vol",
      "drains");
    for (const double depth : kSurveyDepths)
    {
      for (const int length : kSurveyLengths)
      {
        std::size_t breached = 0;
        for (const DepressionChannel& c : channels)
        {
          breached += c.maxCut <= depth && c.maxLength <= static_cast<std::size_t>(length) ? 1 : 0;
        }
        const Heightfield hybrid = breachOrFillDepressions(dem, depth, length);
        const Changes h = changesOf(dem, hybrid);
        std::printf("  %8.1f %8d %9zu %9zu %9zu %11.0f %9zu %11.0f %6s\n",
          depth,
          length,
          breached,
          channels.size() - breached,
          h.lowered,
          h.loweredVolume,
          h.raised,
          h.raisedVolume,
          drainsEverywhere(hybrid, nullptr) ? "yes" : "NO");
      }
    }
  }
  return 0;
}

} // namespace

int main(int argc, char** argv)
{
  if (argc > 1 && std::string(argv[1]) == "--survey")
  {
    return survey(argc, argv);
  }
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
  Heightfield breached;
  Heightfield hybrid;
  const PitRemovalOptions defaults;
  const double breach = bestSeconds(repetitions, [&] { breached = breachDepressions(dem); });
  const double hybridSeconds = bestSeconds(repetitions,
    [&]
    { hybrid = breachOrFillDepressions(dem, defaults.maxBreachDepth, defaults.maxBreachLength); });

  std::size_t raised = 0;
  std::size_t differ = 0;
  for (std::size_t k = 0; k < dem.size(); ++k)
  {
    raised += filled.z[k] != dem.z[k] ? 1 : 0;
    differ += filled.z[k] != reference[k] ? 1 : 0;
  }
  const bool drains = drainsEverywhere(filled, nullptr) && drainsEverywhere(breached, nullptr) &&
    drainsEverywhere(hybrid, nullptr);
  std::printf("\n%-34s %10s\n", "step", "ms");
  std::printf("%-34s %10.1f\n", "fill (ours)", 1e3 * fill);
  std::printf("%-34s %10.1f\n", "D8 directions", 1e3 * d8);
  std::printf("%-34s %10.1f\n", "flow accumulation", 1e3 * accumulate);
  std::printf("%-34s %10.1f\n", "fill + D8 + accumulation", 1e3 * (fill + d8 + accumulate));
  std::printf("%-34s %10.1f\n", "breach", 1e3 * breach);
  std::printf("%-34s %10.1f\n", "hybrid (default limits)", 1e3 * hybridSeconds);
  std::printf("%-34s %10.1f\n", "reference priority-queue fill", 1e3 * plain);
  std::printf("\npits before %zu, after %zu; cells raised %zu (%.2f%%); drains everywhere: %s\n",
    countPits(dem),
    countPits(filled),
    raised,
    100.0 * static_cast<double>(raised) / static_cast<double>(dem.size()),
    drains ? "yes" : "NO");
  const Changes b = changesOf(dem, breached);
  const Changes h = changesOf(dem, hybrid);
  std::printf("breach: lowered %zu cells, raised %zu; hybrid (%.0f m, %d cells): lowered %zu, "
              "raised %zu; all three drain everywhere: %s\n",
    b.lowered,
    b.raised,
    defaults.maxBreachDepth,
    defaults.maxBreachLength,
    h.lowered,
    h.raised,
    drains ? "yes" : "NO");
  std::printf("largest accumulation %u cells\n", *std::max_element(acc.begin(), acc.end()));
  std::printf("time / reference fill: fill %.2f, breach %.2f, hybrid %.2f\n",
    fill / plain,
    breach / plain,
    hybridSeconds / plain);
  std::printf("fill vs reference: %.2fx faster; heights differing: %zu\n", plain / fill, differ);
  std::printf(
    "fill + D8 + accumulation vs reference fill alone: %.2fx\n", plain / (fill + d8 + accumulate));
  return differ == 0 && drains ? 0 : 1;
}
