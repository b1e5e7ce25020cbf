#include "Pyramid.h"

#include "../Core/Grid.h"

#include <array>
#include <cmath>
#include <cstddef>
#include <limits>

namespace tsynth::optim
{
namespace
{

// The binomial kernel of the pyramid (Burt & Adelson 1983's a = 3/8 kernel).
constexpr int kTaps = 5;
constexpr int kRadius = kTaps / 2;
constexpr std::array<double, kTaps> kBinomial = { 1.0 / 16,
  4.0 / 16,
  6.0 / 16,
  4.0 / 16,
  1.0 / 16 };

// The kernel's weight at tap t (-kRadius..kRadius).
double binomial(int t)
{
  return kBinomial[static_cast<std::size_t>(t + kRadius)];
}

bool usable(const Heightfield& hf, std::size_t k)
{
  return hf.isValid(k) && std::isfinite(hf.z[k]);
}

} // namespace

int levelSide(int n, int k)
{
  for (int l = 0; l < k; ++l)
  {
    n = (n + 1) / 2;
  }
  return n;
}

Heightfield downsampleHalf(const Heightfield& fine)
{
  const int w = levelSide(fine.width, 1);
  const int h = levelSide(fine.height, 1);
  // Horizontal pass at every fine row, every second column: value and weight sums.
  std::vector<double> value(cellCount(w, fine.height));
  std::vector<double> weight(value.size());
  for (int j = 0; j < fine.height; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      double v = 0.0;
      double s = 0.0;
      for (int t = -kRadius; t <= kRadius; ++t)
      {
        const int x = 2 * i + t;
        if (x < 0 || x >= fine.width)
        {
          continue;
        }
        const std::size_t k = fine.index(x, j);
        if (usable(fine, k))
        {
          const double c = binomial(t);
          v += c * fine.z[k];
          s += c;
        }
      }
      const std::size_t o = rowMajor(i, j, w);
      value[o] = v;
      weight[o] = s;
    }
  }
  Heightfield out(w, h, std::numeric_limits<float>::quiet_NaN());
  out.cellX = fine.cellX * 2.0;
  out.cellY = fine.cellY * 2.0;
  out.cellSizeKnown = fine.cellSizeKnown;
  out.sourceZUnit = fine.sourceZUnit;
  out.valid.assign(out.size(), 1);
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      bool blockValid = true;
      for (int dy = 0; dy < 2; ++dy)
      {
        for (int dx = 0; dx < 2; ++dx)
        {
          const int x = 2 * i + dx;
          const int y = 2 * j + dy;
          if (x < fine.width && y < fine.height && !usable(fine, fine.index(x, y)))
          {
            blockValid = false;
          }
        }
      }
      double v = 0.0;
      double s = 0.0;
      for (int t = -kRadius; t <= kRadius; ++t)
      {
        const int y = 2 * j + t;
        if (y < 0 || y >= fine.height)
        {
          continue;
        }
        const std::size_t o = rowMajor(i, y, w);
        const double c = binomial(t);
        v += c * value[o];
        s += c * weight[o];
      }
      const std::size_t k = out.index(i, j);
      if (blockValid && s > 0.0)
      {
        out.z[k] = static_cast<float>(v / s);
      }
      else
      {
        out.valid[k] = 0;
      }
    }
  }
  normaliseMask(out);
  return out;
}

std::vector<Heightfield> gaussianPyramid(const Heightfield& hf, int levels)
{
  std::vector<Heightfield> pyramid;
  pyramid.reserve(static_cast<std::size_t>(levels) + 1);
  pyramid.push_back(hf);
  for (int k = 1; k <= levels; ++k)
  {
    pyramid.push_back(downsampleHalf(pyramid.back()));
  }
  return pyramid;
}

} // namespace tsynth::optim
