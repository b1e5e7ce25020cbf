// Helpers shared by the Optimisation tests: crops and a quarter-resolution copy of the bundled
// Colorado DEM.
#pragma once

#include "Core/HeightfieldIO.h"
#include "Optimisation/Pyramid.h"
#include "TestData.h"

namespace tsynth::test::optimisation
{

inline Heightfield crop(const Heightfield& hf, int x0, int y0, int w, int h)
{
  Heightfield out(w, h);
  out.cellX = hf.cellX;
  out.cellY = hf.cellY;
  out.cellSizeKnown = hf.cellSizeKnown;
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      out.at(i, j) = hf.at(x0 + i, y0 + j);
    }
  }
  return out;
}

// Colorado at a quarter of its resolution (162 x 162 cells of 360 m).
inline const Heightfield& source()
{
  static const Heightfield s = optim::gaussianPyramid(
    readHeightfield((test::bundledData() / "dems" / "colorado.png").string()), 2)
                                 .back();
  return s;
}

} // namespace tsynth::test::optimisation
