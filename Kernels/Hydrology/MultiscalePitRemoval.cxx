#include "MultiscalePitRemoval.h"

#include "../Core/Error.h"
#include "../Core/Smoothing.h"
#include "Flow.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace tsynth
{
namespace
{

// The spread of a level's change: a Gaussian of half a coarse cell, which
// removes the kinks of bilinear interpolation and keeps the change as wide as
// the depressions that level sees.
constexpr double kSpreadInCoarseCells = 0.5;

// The mean of the valid cells of each factor x factor block (invalid if none).
Heightfield blockMean(const Heightfield& fine, int factor)
{
  const int w = (fine.width + factor - 1) / factor;
  const int h = (fine.height + factor - 1) / factor;
  Heightfield coarse(w, h, 0.0f);
  coarse.cellX = fine.cellX * factor;
  coarse.cellY = fine.cellY * factor;
  coarse.cellSizeKnown = fine.cellSizeKnown;
  std::vector<double> sum(coarse.size(), 0.0);
  std::vector<int> count(coarse.size(), 0);
  for (int j = 0; j < fine.height; ++j)
  {
    for (int i = 0; i < fine.width; ++i)
    {
      const std::size_t k = fine.index(i, j);
      if (isUsableCell(fine, k))
      {
        const std::size_t c = coarse.index(i / factor, j / factor);
        sum[c] += fine.z[k];
        ++count[c];
      }
    }
  }
  for (std::size_t c = 0; c < coarse.size(); ++c)
  {
    coarse.z[c] = count[c] > 0 ? static_cast<float>(sum[c] / count[c])
                               : std::numeric_limits<float>::quiet_NaN();
  }
  normaliseMask(coarse);
  return coarse;
}

// A block is a sink if any of its cells is.
std::vector<std::uint8_t> blockSinks(const std::vector<std::uint8_t>& sinks,
  const Heightfield& fine,
  const Heightfield& coarse,
  int factor)
{
  std::vector<std::uint8_t> out(coarse.size(), 0);
  for (int j = 0; j < fine.height; ++j)
  {
    for (int i = 0; i < fine.width; ++i)
    {
      if (sinks[fine.index(i, j)] != 0)
      {
        out[coarse.index(i / factor, j / factor)] = 1;
      }
    }
  }
  return out;
}

// The coarse change at the centre of fine cell (i, j), bilinear between block
// centres (0 where a block is invalid).
float changeAt(const Heightfield& change, int factor, int i, int j)
{
  const double x = (i + 0.5) / factor - 0.5;
  const double y = (j + 0.5) / factor - 0.5;
  const int x0 = std::clamp(static_cast<int>(std::floor(x)), 0, change.width - 1);
  const int y0 = std::clamp(static_cast<int>(std::floor(y)), 0, change.height - 1);
  const int x1 = std::min(x0 + 1, change.width - 1);
  const int y1 = std::min(y0 + 1, change.height - 1);
  const double fx = std::clamp(x - x0, 0.0, 1.0);
  const double fy = std::clamp(y - y0, 0.0, 1.0);
  auto v = [&](int a, int b)
  {
    const float d = change.at(a, b);
    return std::isfinite(d) ? static_cast<double>(d) : 0.0;
  };
  const double bottom = v(x0, y0) * (1.0 - fx) + v(x1, y0) * fx;
  const double top = v(x0, y1) * (1.0 - fx) + v(x1, y1) * fx;
  return static_cast<float>(bottom * (1.0 - fy) + top * fy);
}

// One coarse level: drain the block means, spread their change over the fine grid.
void drainLevel(Heightfield& dem, int factor, const MultiscalePitRemovalOptions& options)
{
  const Heightfield coarse = blockMean(dem, factor);
  PitRemovalOptions level = options.pitRemoval;
  std::vector<std::uint8_t> sinks;
  if (options.pitRemoval.sinks != nullptr)
  {
    sinks = blockSinks(*options.pitRemoval.sinks, dem, coarse, factor);
    level.sinks = &sinks;
  }
  Heightfield change = removePits(coarse, level).dem;
  for (std::size_t c = 0; c < change.size(); ++c)
  {
    change.z[c] -= coarse.z[c];
  }
  Heightfield spread(dem.width, dem.height, 0.0f);
  for (int j = 0; j < dem.height; ++j)
  {
    for (int i = 0; i < dem.width; ++i)
    {
      spread.at(i, j) = changeAt(change, factor, i, j);
    }
  }
  spread = smoothLarge(spread, kSpreadInCoarseCells * factor);
  for (std::size_t k = 0; k < dem.size(); ++k)
  {
    if (isUsableCell(dem, k))
    {
      dem.z[k] += spread.z[k];
    }
  }
}

void summarise(const Heightfield& before, const Heightfield& after, MultiscalePitRemovalReport& r)
{
  double total = 0.0;
  std::size_t cells = 0;
  for (std::size_t k = 0; k < before.size(); ++k)
  {
    if (!isUsableCell(before, k))
    {
      continue;
    }
    const double d = static_cast<double>(after.z[k]) - before.z[k];
    r.raisedCells += d > 0.0 ? 1 : 0;
    r.loweredCells += d < 0.0 ? 1 : 0;
    r.largestRaise = std::max(r.largestRaise, d);
    r.largestLowering = std::max(r.largestLowering, -d);
    total += std::abs(d);
    ++cells;
  }
  r.meanAbsoluteChange = cells > 0 ? total / static_cast<double>(cells) : 0.0;
}

} // namespace

MultiscalePitRemovalReport removePitsMultiscale(Heightfield& dem,
  const MultiscalePitRemovalOptions& options)
{
  if (options.coarsestFactor < 1)
  {
    throw Error("The coarsest level of the pit removal must be at least 1 cell per cell.");
  }
  MultiscalePitRemovalReport r;
  const Heightfield before = dem;
  r.pitsBefore = countPits(dem);
  // A level needs a few blocks a side to hold a depression and its rim.
  constexpr int kMinBlocksPerSide = 4;
  for (int factor = options.coarsestFactor; factor >= 2; factor /= 2)
  {
    if (dem.width / factor >= kMinBlocksPerSide && dem.height / factor >= kMinBlocksPerSide)
    {
      drainLevel(dem, factor, options);
      ++r.levels;
    }
  }
  PitRemovalOptions finest = options.pitRemoval;
  finest.method = options.finestMethod;
  dem = removePits(dem, finest).dem;
  ++r.levels;
  r.pitsAfter = countPits(dem);
  summarise(before, dem, r);
  return r;
}

} // namespace tsynth
