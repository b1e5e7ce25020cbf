// How much memory a distance-based synthesis needs, and its refusal above the
// budget: kept beside the algorithm (DistanceSynthesis.h), which checks it
// before any work.
#pragma once

#include <string>

namespace tsynth
{

struct DistanceInputs;
struct DistanceOptions;

// Peak memory in bytes of synthesiseByDistance on a width x height grid with
// `threads` OpenMP threads, as `tsynth distance` and the Terrain Distance Synthesis
// run it: per cell the lattice's eight edge weights, the approximate search's
// field (cost, source, with ridges the predecessor), one search field per
// thread, the blend's sums and contributor counts, the approximate and final
// heights, the region map and fBm costs, the stroke map read and the output
// written; the bounded per-feature searches' visits of a batch stay within the
// margin (measured with 1 to 400 features); and the program itself. Measured
// (DistanceMemory.cxx) and rounded up: 1.05 to 1.45 times the measured peak
// from 1024^2 cells on.
double distanceMemoryEstimate(int width, int height, int threads);

// Throws tsynth::Error (checkMemoryBudget's sentence, with the estimate) if a
// synthesis of `inputs` with this machine's OpenMP threads exceeds
// options.memoryBudget.
void checkDistanceMemory(const DistanceInputs& inputs, const DistanceOptions& options);

} // namespace tsynth
