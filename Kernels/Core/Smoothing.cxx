#include "Smoothing.h"

#include "Grid.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace tsynth
{
namespace
{

constexpr int kBoxPasses = 3;

// Odd box widths whose variances add up to sigma^2 (as near as odd widths allow).
std::array<int, kBoxPasses> boxWidths(double sigma)
{
  const double n = kBoxPasses;
  const double ideal = std::sqrt(12.0 * sigma * sigma / n + 1.0);
  int lower = static_cast<int>(std::floor(ideal));
  if (lower % 2 == 0)
  {
    --lower;
  }
  lower = std::max(1, lower);
  const double m = std::round(
    (12.0 * sigma * sigma - n * lower * lower - 4.0 * n * lower - 3.0 * n) / (-4.0 * lower - 4.0));
  std::array<int, kBoxPasses> widths{};
  for (std::size_t k = 0; k < widths.size(); ++k)
  {
    widths[k] = k < m ? lower : lower + 2;
  }
  return widths;
}

// One box pass along a line of n values read and written with a stride:
// running sums of value and weight, the window clipped at the ends.
void boxLine(double* value,
  double* weight,
  std::size_t n,
  std::size_t stride,
  int width,
  std::vector<double>& v,
  std::vector<double>& w)
{
  v.resize(n + 1);
  w.resize(n + 1);
  v[0] = w[0] = 0.0;
  for (std::size_t k = 0; k < n; ++k)
  {
    v[k + 1] = v[k] + value[k * stride];
    w[k + 1] = w[k] + weight[k * stride];
  }
  const std::size_t r = static_cast<std::size_t>(width / 2);
  for (std::size_t k = 0; k < n; ++k)
  {
    const std::size_t lo = k >= r ? k - r : 0;
    const std::size_t hi = std::min(n, k + r + 1);
    value[k * stride] = v[hi] - v[lo];
    weight[k * stride] = w[hi] - w[lo];
  }
}

// One box pass down every column at once, row by row: a running sum per
// column of rows j - r .. j + r (clipped), read and written row-contiguously,
// in place. The sum drops row j - r - 1 after that row was overwritten, so the
// last r + 1 rows' old values are kept in a ring (`ring`): a few rows rather
// than a second plane of doubles, which set the peak of large terrains.
void boxColumns(std::vector<double>& value,
  std::size_t w,
  std::size_t h,
  int width,
  std::vector<double>& ring)
{
  const std::size_t r = static_cast<std::size_t>(width / 2);
  const std::size_t kept = r + 1; // rows in the ring
  const bool drops = kept < h;
  std::vector<double> sum(w, 0.0);
  ring.assign(drops ? kept * w : 0, 0.0);
  for (std::size_t j = 0; j < std::min(h, r); ++j)
  {
    for (std::size_t i = 0; i < w; ++i)
    {
      sum[i] += value[j * w + i];
    }
  }
  for (std::size_t j = 0; j < h; ++j)
  {
    double* row = value.data() + j * w;
    if (j + r < h)
    {
      const double* add = value.data() + (j + r) * w;
      for (std::size_t i = 0; i < w; ++i)
      {
        sum[i] += add[i];
      }
    }
    if (drops)
    {
      // Row j - r - 1's old values sit where row j's go: (j - r - 1) mod (r + 1) = j mod (r + 1).
      double* slot = ring.data() + (j % kept) * w;
      if (j >= kept)
      {
        for (std::size_t i = 0; i < w; ++i)
        {
          sum[i] -= slot[i];
        }
      }
      std::copy(row, row + w, slot);
    }
    std::copy(sum.begin(), sum.end(), row);
  }
}

} // namespace

Heightfield smoothLarge(const Heightfield& hf, double sigma)
{
  if (!(sigma > 0.0))
  {
    return hf;
  }
  const std::size_t w = static_cast<std::size_t>(hf.width);
  const std::size_t h = static_cast<std::size_t>(hf.height);
  // Weighted sums: value * weight and weight, so invalid cells count for nothing.
  std::vector<double> value(hf.size());
  std::vector<double> weight(hf.size());
  for (std::size_t k = 0; k < hf.size(); ++k)
  {
    const bool ok = hf.isValid(k) && std::isfinite(hf.z[k]);
    value[k] = ok ? hf.z[k] : 0.0;
    weight[k] = ok ? 1.0 : 0.0;
  }
  const std::array<int, kBoxPasses> widths = boxWidths(sigma);
#pragma omp parallel
  {
    std::vector<double> v, s;
#pragma omp for schedule(static)
    for (long j = 0; j < static_cast<long>(h); ++j)
    {
      for (int width : widths)
      {
        boxLine(
          value.data() + rowMajor(0, j, w), weight.data() + rowMajor(0, j, w), w, 1, width, v, s);
      }
    }
  }
  std::vector<double> ring;
  for (int width : widths)
  {
    boxColumns(value, w, h, width, ring);
    boxColumns(weight, w, h, width, ring);
  }
  Heightfield out = hf;
  for (std::size_t k = 0; k < out.size(); ++k)
  {
    if (hf.isValid(k) && weight[k] > 0.0)
    {
      out.z[k] = static_cast<float>(value[k] / weight[k]);
    }
  }
  return out;
}

} // namespace tsynth
