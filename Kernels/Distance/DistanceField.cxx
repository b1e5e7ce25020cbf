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

} // namespace

NearestSeeds nearestSeeds(const std::vector<std::uint8_t>& seeds,
  int width,
  int height,
  double cellX,
  double cellY)
{
  const std::size_t w = static_cast<std::size_t>(std::max(0, width));
  const std::size_t h = static_cast<std::size_t>(std::max(0, height));
  if (w * h > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
  {
    throw Error("The grid (" + std::to_string(width) + " x " + std::to_string(height) +
      " cells) is too large for the distance transform.");
  }
  if (seeds.size() != w * h)
  {
    throw Error("Internal error: the seed mask does not match the grid.");
  }
  NearestSeeds out;
  out.width = width;
  out.height = height;
  out.distance.assign(w * h, std::numeric_limits<float>::infinity());
  out.nearest.assign(w * h, -1);
  // Pass 1, down each column: squared distance to the nearest seed of that
  // column and its row.
  std::vector<double> columnD(w * h);
  std::vector<std::int32_t> columnRow(w * h);
  {
    std::vector<double> f(h), d(h);
    std::vector<std::int32_t> from(h);
    LineTransform line;
    for (std::size_t i = 0; i < w; ++i)
    {
      for (std::size_t j = 0; j < h; ++j)
      {
        f[j] = seeds[j * w + i] != 0 ? 0.0 : kInf;
      }
      line.run(f, h, cellY, d, from);
      for (std::size_t j = 0; j < h; ++j)
      {
        columnD[j * w + i] = d[j];
        columnRow[j * w + i] = from[j];
      }
    }
  }
  // Pass 2, along each row over the column results.
  std::vector<double> f(w), d(w);
  std::vector<std::int32_t> from(w);
  LineTransform line;
  for (std::size_t j = 0; j < h; ++j)
  {
    for (std::size_t i = 0; i < w; ++i)
    {
      f[i] = columnD[j * w + i];
    }
    line.run(f, w, cellX, d, from);
    for (std::size_t i = 0; i < w; ++i)
    {
      if (from[i] < 0 || !(d[i] < kInf))
      {
        continue;
      }
      const std::size_t column = static_cast<std::size_t>(from[i]);
      const std::size_t row = static_cast<std::size_t>(columnRow[j * w + column]);
      out.distance[j * w + i] = static_cast<float>(std::sqrt(d[i]));
      out.nearest[j * w + i] = static_cast<std::int32_t>(row * w + column);
    }
  }
  return out;
}

std::vector<float> distanceTransform(const std::vector<std::uint8_t>& seeds, int width, int height)
{
  return nearestSeeds(seeds, width, height).distance;
}

} // namespace tsynth
