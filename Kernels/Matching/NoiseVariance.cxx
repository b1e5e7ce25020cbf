#include "NoiseVariance.h"

#include "../Features/Ppa.h"

#include <algorithm>
#include <cmath>

namespace tsynth
{

NoiseVariance::NoiseVariance(const Heightfield& hf)
{
  // Summed-area tables: one row and one column more than the heights.
  const std::size_t n = cellCount(hf.width + 1, hf.height + 1);
  auto at = [&hf](int i, int j) { return rowMajor(i, j, hf.width + 1); };
  if (hf.hasMask())
  {
    count_.assign(n, 0.0);
    for (int j = 0; j < hf.height; ++j)
    {
      double rc = 0.0;
      for (int i = 0; i < hf.width; ++i)
      {
        rc += hf.isValid(i, j) ? 1.0 : 0.0;
        count_[at(i + 1, j + 1)] = count_[at(i + 1, j)] + rc;
      }
    }
  }
  // Band l = G_l - G_{l+1}, with G_l the heights blurred by sigma 2^l (all at full
  // resolution, so windows are read at the same cells on every level).
  Heightfield finer = hf;
  for (std::size_t l = 0; l < levels_.size(); ++l)
  {
    const Heightfield coarser = gaussianSmooth(hf, std::pow(2.0, l));
    Table& t = levels_[l];
    t.width = hf.width;
    t.height = hf.height;
    t.sum.assign(n, 0.0);
    t.square.assign(n, 0.0);
    for (int j = 0; j < hf.height; ++j)
    {
      double rs = 0.0;
      double rq = 0.0;
      for (int i = 0; i < hf.width; ++i)
      {
        if (hf.isValid(i, j))
        {
          const double b = static_cast<double>(finer.at(i, j)) - coarser.at(i, j);
          rs += b;
          rq += b * b;
        }
        t.sum[at(i + 1, j + 1)] = t.sum[at(i + 1, j)] + rs;
        t.square[at(i + 1, j + 1)] = t.square[at(i + 1, j)] + rq;
      }
    }
    finer = coarser;
  }
}

std::array<float, kNoiseLevels> NoiseVariance::window(double cx, double cy, int size) const
{
  std::array<float, kNoiseLevels> out{};
  for (std::size_t l = 0; l < levels_.size(); ++l)
  {
    const Table& t = levels_[l];
    if (t.width == 0)
    {
      continue;
    }
    const int i0 = std::clamp(static_cast<int>(std::lround(cx - 0.5 * size)), 0, t.width);
    const int j0 = std::clamp(static_cast<int>(std::lround(cy - 0.5 * size)), 0, t.height);
    const int i1 = std::clamp(i0 + size, 0, t.width);
    const int j1 = std::clamp(j0 + size, 0, t.height);
    const std::size_t stride = static_cast<std::size_t>(t.width + 1); // a row of the table
    auto at = [stride](int i, int j) { return rowMajor(i, j, stride); };
    auto rect = [&](const std::vector<double>& a)
    { return a[at(i1, j1)] - a[at(i1, j0)] - a[at(i0, j1)] + a[at(i0, j0)]; };
    const double n =
      count_.empty() ? static_cast<double>(i1 - i0) * static_cast<double>(j1 - j0) : rect(count_);
    if (n > 1.0)
    {
      const double mean = rect(t.sum) / n;
      out[l] = static_cast<float>(std::max(0.0, rect(t.square) / n - mean * mean));
    }
  }
  return out;
}

} // namespace tsynth
