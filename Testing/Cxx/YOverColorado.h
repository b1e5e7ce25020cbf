// The set-up several synthesis tests share: a 256 x 256 terrain at patch 32
// from the bundled Colorado DEM and the bundled Y of ridges, on the CPU
// matcher, prepared once per test program.
#pragma once

#include "Core/HeightfieldIO.h"
#include "Synthesis/Setup.h"
#include "TestData.h"

namespace tsynth::test
{

constexpr int kYSize = 256;
constexpr int kYPatch = 32;

inline const SynthesisSetup& yOverColoradoSetup()
{
  static const SynthesisSetup setup = []
  {
    SetupInputs in;
    in.exemplars.push_back(readHeightfield(realDem("colorado.png")));
    in.sketch = readColourImage((bundledData() / "sketches" / "strokes_y_ridges.png").string());
    in.grid.width = kYSize;
    in.grid.height = kYSize;
    in.patchSize = kYPatch;
    in.matcherBackend = Backend::Cpu;
    return prepareSynthesis(in);
  }();
  return setup;
}

} // namespace tsynth::test
