#include "DistanceField.h"

#include "../Core/Error.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tsynth
{
namespace
{

constexpr double kInf = std::numeric_limits<double>::infinity();
// Columns of the first pass done together: 16 doubles, two cache lines per row.
constexpr std::size_t kColumnBlock = 16;
// distanceTransform measures in cells.
constexpr double kUnitCell = 1.0;

// One line of the transform: squared distances f (inf = no seed) at positions
// q * spacing; writes the lower envelope d and, per position, which input
// position it comes from. The work arrays are the caller's, reused per line.
struct LineTransform
{
  std::vector<std::size_t> apex; // positions of the parabolas in the envelope
  std::vector<double> bound;     // where each parabola starts to be the lowest

  void run(const std::vector<double>& f,
    std::size_t n,
    double spacing,
    std::vector<double>& d,
    std::vector<std::int32_t>& from)
  {
    apex.resize(n);
    bound.resize(n + 1);
    auto position = [spacing](std::size_t q) { return static_cast<double>(q) * spacing; };
    // Where the parabolas of p and q (p < q) cross.
    auto crossing = [&](std::size_t p, std::size_t q)
    {
      const double xp = position(p);
      const double xq = position(q);
      return ((f[q] + xq * xq) - (f[p] + xp * xp)) / (2.0 * (xq - xp));
    };
    std::size_t k = 0; // parabolas in the envelope
    for (std::size_t q = 0; q < n; ++q)
    {
      if (!(f[q] < kInf))
      {
        continue;
      }
      while (k > 0 && crossing(apex[k - 1], q) <= bound[k - 1])
      {
        --k;
      }
      apex[k] = q;
      bound[k] = k == 0 ? -kInf : crossing(apex[k - 1], q);
      bound[k + 1] = kInf;
      ++k;
    }
    if (k == 0)
    {
      std::fill(d.begin(), d.begin() + static_cast<long>(n), kInf);
      std::fill(from.begin(), from.begin() + static_cast<long>(n), -1);
      return;
    }
    std::size_t j = 0;
    for (std::size_t q = 0; q < n; ++q)
    {
      while (bound[j + 1] < position(q))
      {
        ++j;
      }
      const std::size_t p = apex[j];
      const double dx = position(q) - position(p);
      d[q] = dx * dx + f[p];
      from[q] = static_cast<std::int32_t>(p);
    }
  }
};

// The grid's width and height in cells (both 0 when either is), checked
// against the seed mask and the int32 cell indices the transform stores.
struct CheckedGrid
{
  std::size_t w = 0, h = 0;
  std::size_t cells() const { return w * h; }
};

CheckedGrid checkedGrid(const std::vector<std::uint8_t>& seeds, int width, int height)
{
  CheckedGrid grid{ static_cast<std::size_t>(std::max(0, width)),
    static_cast<std::size_t>(std::max(0, height)) };
  if (grid.cells() > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
  {
    throw Error("The grid (" + std::to_string(width) + " x " + std::to_string(height) +
      " cells) is too large for the distance transform.");
  }
  if (seeds.size() != grid.cells())
  {
    throw Error("Internal error: the seed mask does not match the grid.");
  }
  if (grid.cells() == 0)
  {
    grid = CheckedGrid{};
  }
  return grid;
}

// Pass 1, down each column: the row of the nearest seed in that column (-1
// when the column has none), into seedRow. Columns go kColumnBlock at a time,
// so that the row segments read and written are contiguous, not one cache
// line per cell. Only the row is kept: pass 2 recomputes the squared distance
// from it with the same arithmetic, so no plane of doubles is needed.
void nearestSeedRowPerColumn(const std::vector<std::uint8_t>& seeds,
  std::size_t w,
  std::size_t h,
  double cellY,
  std::int32_t* seedRow)
{
  const long blocks = static_cast<long>((w + kColumnBlock - 1) / kColumnBlock);
#pragma omp parallel
  {
    LineTransform line;
    std::vector<std::vector<double>> f(kColumnBlock, std::vector<double>(h));
    std::vector<std::vector<double>> d(kColumnBlock, std::vector<double>(h));
    std::vector<std::vector<std::int32_t>> from(kColumnBlock, std::vector<std::int32_t>(h));
#pragma omp for schedule(static)
    for (long b = 0; b < blocks; ++b)
    {
      const std::size_t i0 = static_cast<std::size_t>(b) * kColumnBlock;
      const std::size_t count = std::min(kColumnBlock, w - i0);
      for (std::size_t j = 0; j < h; ++j)
      {
        for (std::size_t c = 0; c < count; ++c)
        {
          f[c][j] = seeds[j * w + i0 + c] != 0 ? 0.0 : kInf;
        }
      }
      for (std::size_t c = 0; c < count; ++c)
      {
        line.run(f[c], h, cellY, d[c], from[c]);
      }
      for (std::size_t j = 0; j < h; ++j)
      {
        for (std::size_t c = 0; c < count; ++c)
        {
          seedRow[j * w + i0 + c] = from[c][j];
        }
      }
    }
  }
}

// Pass 2, along each row: the lower envelope over the columns' squared
// distances, giving each cell's distance and (when nearest is given) its
// nearest seed. seedRow may be the nearest plane itself: each row's column
// results are copied out before the row is written.
void nearestAlongRows(const std::int32_t* seedRow,
  std::size_t w,
  std::size_t h,
  double cellX,
  double cellY,
  float* distance,
  std::int32_t* nearest)
{
#pragma omp parallel
  {
    LineTransform line;
    std::vector<double> f(w), d(w);
    std::vector<std::int32_t> from(w), rowOf(w);
#pragma omp for schedule(static)
    for (long row = 0; row < static_cast<long>(h); ++row)
    {
      const std::size_t j = static_cast<std::size_t>(row);
      std::copy(seedRow + j * w, seedRow + (j + 1) * w, rowOf.begin());
      for (std::size_t i = 0; i < w; ++i)
      {
        // The column pass's squared distance, as LineTransform::run gave it.
        const double dy = static_cast<double>(j) * cellY - static_cast<double>(rowOf[i]) * cellY;
        f[i] = rowOf[i] < 0 ? kInf : dy * dy;
      }
      line.run(f, w, cellX, d, from);
      for (std::size_t i = 0; i < w; ++i)
      {
        const std::size_t c = j * w + i;
        const bool reached = from[i] >= 0 && d[i] < kInf;
        distance[c] =
          reached ? static_cast<float>(std::sqrt(d[i])) : std::numeric_limits<float>::infinity();
        if (nearest != nullptr)
        {
          const std::size_t column = static_cast<std::size_t>(from[i]);
          nearest[c] = reached
            ? static_cast<std::int32_t>(static_cast<std::size_t>(rowOf[column]) * w + column)
            : -1;
        }
      }
    }
  }
}

} // namespace

NearestSeeds nearestSeeds(const std::vector<std::uint8_t>& seeds,
  int width,
  int height,
  double cellX,
  double cellY)
{
  const auto [w, h] = checkedGrid(seeds, width, height);
  const std::size_t cells = w * h;
  NearestSeeds out;
  out.width = width;
  out.height = height;
  out.distance.resize(cells);
  out.nearest.resize(cells);
  // The nearest plane holds the column pass's rows until pass 2 overwrites it.
  nearestSeedRowPerColumn(seeds, w, h, cellY, out.nearest.data());
  nearestAlongRows(out.nearest.data(), w, h, cellX, cellY, out.distance.data(), out.nearest.data());
  return out;
}

std::vector<float> distanceTransform(const std::vector<std::uint8_t>& seeds, int width, int height)
{
  const auto [w, h] = checkedGrid(seeds, width, height);
  const std::size_t cells = w * h;
  std::vector<std::int32_t> seedRow(cells);
  nearestSeedRowPerColumn(seeds, w, h, kUnitCell, seedRow.data());
  std::vector<float> distance(cells);
  nearestAlongRows(seedRow.data(), w, h, kUnitCell, kUnitCell, distance.data(), nullptr);
  return distance;
}

} // namespace tsynth
