// Helpers shared by Synthesis/TestLandform.cxx and Synthesis/TestTarget.cxx: analytic terrains
// on 30 m cells.
#pragma once

#include "Core/Heightfield.h"

#include <functional>

namespace tsynth::test::landform
{

constexpr double kCell = 30.0; // metres

inline Heightfield terrain(int w, int h, const std::function<double(int, int)>& f)
{
  Heightfield hf(w, h);
  hf.cellX = hf.cellY = kCell;
  hf.cellSizeKnown = true;
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      hf.at(i, j) = static_cast<float>(f(i, j));
    }
  }
  return hf;
}

} // namespace tsynth::test::landform
