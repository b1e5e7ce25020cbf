#include "Smoothing.h"

#include "Grid.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace tsynth
{

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

namespace
{

// One box pass along a line of n values read and written with a stride: a
// running sum, the window clipped at the ends (`sum`: n + 1 prefix sums).
void boxLine(double* value, std::size_t n, std::size_t stride, int width, std::vector<double>& sum)
{
  sum.resize(n + 1);
  sum[0] = 0.0;
  for (std::size_t k = 0; k < n; ++k)
  {
    sum[k + 1] = sum[k] + value[k * stride];
  }
  const std::size_t r = static_cast<std::size_t>(width / 2);
  for (std::size_t k = 0; k < n; ++k)
  {
    const std::size_t lo = k >= r ? k - r : 0;
    const std::size_t hi = std::min(n, k + r + 1);
    value[k * stride] = sum[hi] - sum[lo];
  }
}

// Whether every cell of hf counts (valid and finite), so that its weights need
// no plane of their own (boxedOnes).
bool everyCellCounts(const Heightfield& hf)
{
  return hf.valid.empty() &&
    std::all_of(hf.z.begin(), hf.z.end(), [](float z) { return std::isfinite(z); });
}

// A line of n ones after the box passes: how many cells each window held.
// Where every cell counts, the weight of cell (i, j) after the passes along
// both axes is ones(w)[i] * ones(h)[j], exactly the plane of weights the
// passes would make: every sum is a whole number far below 2^53, so no
// rounding happens either way.
std::vector<double> boxedOnes(std::size_t n, const std::array<int, kBoxPasses>& widths)
{
  std::vector<double> ones(n, 1.0);
  std::vector<double> sum;
  for (int width : widths)
  {
    boxLine(ones.data(), n, 1, width, sum);
  }
  return ones;
}

// Columns a thread takes at once in boxColumns: a stripe's row segments are
// 4 KB, so each row of the stripe is a few cache lines read in one go.
constexpr std::size_t kColumnStripe = 512;

// One box pass down the columns i0 .. i1 - 1, row by row: a running sum per
// column of rows j - r .. j + r (clipped), read and written row-contiguously,
// in place. The sum drops row j - r - 1 after that row was overwritten, so the
// last r + 1 rows' old values are kept in a ring (`ring`): a few rows rather
// than a second plane of doubles, which set the peak of large terrains.
void boxStripe(double* value,
  std::size_t w,
  std::size_t h,
  std::size_t i0,
  std::size_t i1,
  int width,
  std::vector<double>& sum,
  std::vector<double>& ring)
{
  const std::size_t r = static_cast<std::size_t>(width / 2);
  const std::size_t kept = r + 1; // rows in the ring
  const bool drops = kept < h;
  const std::size_t n = i1 - i0;
  sum.assign(n, 0.0);
  ring.assign(drops ? kept * n : 0, 0.0);
  const auto rowOf = [&](std::size_t j) { return value + j * w + i0; };
  for (std::size_t j = 0; j < std::min(h, r); ++j)
  {
    const double* add = rowOf(j);
    for (std::size_t i = 0; i < n; ++i)
    {
      sum[i] += add[i];
    }
  }
  for (std::size_t j = 0; j < h; ++j)
  {
    double* row = rowOf(j);
    if (j + r < h)
    {
      const double* add = rowOf(j + r);
      for (std::size_t i = 0; i < n; ++i)
      {
        sum[i] += add[i];
      }
    }
    if (drops)
    {
      // Row j - r - 1's old values sit where row j's go: (j - r - 1) mod (r + 1) = j mod (r + 1).
      double* slot = ring.data() + (j % kept) * n;
      if (j >= kept)
      {
        for (std::size_t i = 0; i < n; ++i)
        {
          sum[i] -= slot[i];
        }
      }
      std::copy(row, row + n, slot);
    }
    std::copy(sum.begin(), sum.end(), row);
  }
}

// One box pass down every column: stripes of kColumnStripe columns on all
// threads. Each column's sums are the same additions in the same order
// whichever thread takes its stripe, so the result does not depend on the
// thread count.
void boxColumns(std::vector<double>& value, std::size_t w, std::size_t h, int width)
{
  const auto stripes = static_cast<long>((w + kColumnStripe - 1) / kColumnStripe);
#pragma omp parallel
  {
    std::vector<double> sum, ring;
#pragma omp for schedule(dynamic)
    for (long s = 0; s < stripes; ++s)
    {
      const std::size_t i0 = static_cast<std::size_t>(s) * kColumnStripe;
      boxStripe(value.data(), w, h, i0, std::min(w, i0 + kColumnStripe), width, sum, ring);
    }
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
  const std::size_t n = hf.size();
  const bool whole = everyCellCounts(hf);
  std::vector<double> value(n);
  std::vector<double> weight(whole ? 0 : n);
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < n; ++k)
  {
    const bool ok = whole || (hf.isValid(k) && std::isfinite(hf.z[k]));
    value[k] = ok ? hf.z[k] : 0.0;
    if (!whole)
    {
      weight[k] = ok ? 1.0 : 0.0;
    }
  }
  const std::array<int, kBoxPasses> widths = boxWidths(sigma);
#pragma omp parallel
  {
    std::vector<double> sum;
#pragma omp for schedule(static)
    for (std::size_t j = 0; j < h; ++j)
    {
      for (int width : widths)
      {
        boxLine(value.data() + rowMajor(0, j, w), w, 1, width, sum);
        if (!whole)
        {
          boxLine(weight.data() + rowMajor(0, j, w), w, 1, width, sum);
        }
      }
    }
  }
  for (int width : widths)
  {
    boxColumns(value, w, h, width);
    if (!whole)
    {
      boxColumns(weight, w, h, width);
    }
  }
  const std::vector<double> across = whole ? boxedOnes(w, widths) : std::vector<double>();
  const std::vector<double> down = whole ? boxedOnes(h, widths) : std::vector<double>();
  Heightfield out = hf;
#pragma omp parallel for schedule(static)
  for (std::size_t j = 0; j < h; ++j)
  {
    for (std::size_t i = 0; i < w; ++i)
    {
      const std::size_t k = rowMajor(i, j, w);
      const double wk = whole ? across[i] * down[j] : weight[k];
      if (hf.isValid(k) && wk > 0.0)
      {
        out.z[k] = static_cast<float>(value[k] / wk);
      }
    }
  }
  return out;
}

} // namespace tsynth
