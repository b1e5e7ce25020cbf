// Helpers shared by the benchmarks.
#pragma once

#include "Core/Heightfield.h"

#include <algorithm>
#include <chrono>
#include <functional>
#include <limits>

namespace tsynth::bench
{

// A size x size heightfield made of mirrored copies of src (no seams), to
// benchmark on real terrain larger than the bundled DEMs.
inline Heightfield mirrorTile(const Heightfield& src, int size)
{
  Heightfield out(size, size);
  out.cellX = src.cellX;
  out.cellY = src.cellY;
  auto reflect = [](int v, int n)
  {
    const int period = 2 * n - 2;
    v %= period;
    return v < n ? v : period - v;
  };
  for (int j = 0; j < size; ++j)
  {
    for (int i = 0; i < size; ++i)
    {
      out.at(i, j) = src.at(reflect(i, src.width), reflect(j, src.height));
    }
  }
  return out;
}

// The best wall-clock seconds of `repetitions` calls of f.
inline double bestSeconds(int repetitions, const std::function<void()>& f)
{
  double best = std::numeric_limits<double>::infinity();
  for (int r = 0; r < repetitions; ++r)
  {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    best =
      std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  return best;
}

} // namespace tsynth::bench
