#include "NoiseVariance.h"

#include "../Features/Ppa.h"

#include <algorithm>
#include <cmath>

namespace tsynth
{

NoiseVariance::NoiseVariance(const Heightfield& hf)
{
  const std::size_t stride = static_cast<std::size_t>(hf.width + 1);
  const std::size_t n = stride * static_cast<std::size_t>(hf.height + 1);
  auto at = [stride](int i, int j)
  { return static_cast<std::size_t>(j) * stride + static_cast<std::size_t>(i); };
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
  for (int l = 0; l < kNoiseLevels; ++l)
  {
    const Heightfield coarser = gaussianSmooth(hf, std::pow(2.0, l));
    Table& t = levels_[static_cast<std::size_t>(l)];
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
  for (int l = 0; l < kNoiseLevels; ++l)
  {
    const Table& t = levels_[static_cast<std::size_t>(l)];
    if (t.width == 0)
    {
      continue;
    }
    const int i0 = std::clamp(static_cast<int>(std::lround(cx - 0.5 * size)), 0, t.width);
    const int j0 = std::clamp(static_cast<int>(std::lround(cy - 0.5 * size)), 0, t.height);
    const int i1 = std::clamp(i0 + size, 0, t.width);
    const int j1 = std::clamp(j0 + size, 0, t.height);
    const std::size_t stride = static_cast<std::size_t>(t.width + 1);
    auto rect = [&](const std::vector<double>& a)
    {
      return a[static_cast<std::size_t>(j1) * stride + static_cast<std::size_t>(i1)] -
        a[static_cast<std::size_t>(j0) * stride + static_cast<std::size_t>(i1)] -
        a[static_cast<std::size_t>(j1) * stride + static_cast<std::size_t>(i0)] +
        a[static_cast<std::size_t>(j0) * stride + static_cast<std::size_t>(i0)];
    };
    const double n =
      count_.empty() ? static_cast<double>(i1 - i0) * static_cast<double>(j1 - j0) : rect(count_);
    if (n > 1.0)
    {
      const double mean = rect(t.sum) / n;
      out[static_cast<std::size_t>(l)] =
        static_cast<float>(std::max(0.0, rect(t.square) / n - mean * mean));
    }
  }
  return out;
}

} // namespace tsynth
