// Helpers shared by Synthesis/TestPatchPlacement.cxx and Synthesis/TestSynthesiser.cxx: the
// options of the synthesis of the Y over Colorado (YOverColorado.h) on the CPU.
#pragma once

#include "Synthesis/Synthesiser.h"
#include "YOverColorado.h"

namespace tsynth::test::placement
{

constexpr int kPatch = test::kYPatch;

inline SynthesisOptions options()
{
  SynthesisOptions o;
  o.patchSize = kPatch;
  o.backend = Backend::Cpu;
  o.pool = test::yOverColoradoSetup().pool;
  o.seed = test::yOverColoradoSetup().seed; // the one its target was made with

  return o;
}

} // namespace tsynth::test::placement
