// Helpers shared by Synthesis/TestPreview.cxx and Synthesis/TestSetup.cxx: the set-up inputs of
// a flat exemplar on 90 m cells and a blank sketch.
#pragma once

#include "Synthesis/Setup.h"

#include <cstddef>

namespace tsynth::test::preview
{

constexpr double kCell = 90.0;

inline SetupInputs inputsFor(int sketchPixels, int patch)
{
  SetupInputs in;
  Heightfield exemplar(200, 200, 100.0f);
  exemplar.cellX = kCell;
  exemplar.cellY = kCell;
  exemplar.cellSizeKnown = true;
  in.exemplars.push_back(exemplar);
  ColourImage sketch;
  sketch.width = sketchPixels;
  sketch.height = sketchPixels / 2;
  sketch.channels = 3;
  sketch.data.assign(static_cast<std::size_t>(sketch.width) * sketch.height * 3, 255);
  in.sketch = sketch;
  in.patchSize = patch;
  return in;
}

} // namespace tsynth::test::preview
