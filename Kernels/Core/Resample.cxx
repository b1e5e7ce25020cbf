#include "Resample.h"

#include "Error.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tsynth
{

Heightfield resampleToCellSize(const Heightfield& hf, double cellX, double cellY)
{
  if (!(cellX > 0.0) || !(cellY > 0.0))
  {
    throw Error("Resampling needs a positive cell size.");
  }
  const int w = std::max(1, static_cast<int>(std::floor((hf.width - 1) * hf.cellX / cellX)) + 1);
  const int h = std::max(1, static_cast<int>(std::floor((hf.height - 1) * hf.cellY / cellY)) + 1);
  Heightfield out(w, h, std::numeric_limits<float>::quiet_NaN());
  out.cellX = cellX;
  out.cellY = cellY;
  out.cellSizeKnown = true;
  out.sourceZUnit = hf.sourceZUnit;
  for (int j = 0; j < h; ++j)
  {
    const double y = j * cellY / hf.cellY;
    const int j0 = std::min(static_cast<int>(y), hf.height - 1);
    const int j1 = std::min(j0 + 1, hf.height - 1);
    const double fy = y - j0;
    for (int i = 0; i < w; ++i)
    {
      const double x = i * cellX / hf.cellX;
      const int i0 = std::min(static_cast<int>(x), hf.width - 1);
      const int i1 = std::min(i0 + 1, hf.width - 1);
      const double fx = x - i0;
      if (!hf.isValid(i0, j0) || !hf.isValid(i1, j0) || !hf.isValid(i0, j1) || !hf.isValid(i1, j1))
      {
        continue;
      }
      out.at(i, j) = static_cast<float>((1 - fy) * ((1 - fx) * hf.at(i0, j0) + fx * hf.at(i1, j0)) +
        fy * ((1 - fx) * hf.at(i0, j1) + fx * hf.at(i1, j1)));
    }
  }
  normaliseMask(out);
  return out;
}

Heightfield resampleNearest(const Heightfield& in, int width, int height)
{
  Heightfield out(width, height);
  for (int j = 0; j < height; ++j)
  {
    const int sj =
      std::min(in.height - 1, static_cast<int>(static_cast<double>(j) * in.height / height));
    for (int i = 0; i < width; ++i)
    {
      const int si =
        std::min(in.width - 1, static_cast<int>(static_cast<double>(i) * in.width / width));
      out.at(i, j) = in.isValid(si, sj) ? in.at(si, sj) : std::numeric_limits<float>::quiet_NaN();
    }
  }
  normaliseMask(out);
  return out;
}

} // namespace tsynth
