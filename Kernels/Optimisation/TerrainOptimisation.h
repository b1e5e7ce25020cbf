// Terrain optimisation (Scott & Dodgson 2021, after Kwatra et al. 2005): a
// terrain rebuilt entirely from patches of one source DEM so that it follows a
// guide. Gaussian pyramids of source and guide; per level a dense
// correspondence map (for each output cell the centre of a source patch) found
// by PatchMatch (M-step), and the terrain as the average of the overlapping
// source patches blended with the guide (E-step); optional pit removal after
// each E-step on every level but the finest.
// In ParaView: vtkTerrainOptimisation (Terrain Optimisation), in Filters/.
#pragma once

#include "../Core/Heightfield.h"
#include "../Core/OptionTable.h"
#include "../Core/Progress.h"
#include "../Hydrology/PitRemoval.h"
#include "OptimisationLimits.h"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace tsynth
{

// Patch sizes accepted: odd, 3..15 (a patch row is read as one or two rows of
// 8 lanes; 15 is the largest that fits two).
constexpr int kMinPatchSize = 3;
constexpr int kMaxPatchSize = 15;
// With levels = 0 the pyramid gets as many levels as keep the coarsest guide
// and source at least this many cells on their shorter side (L = 3 for a 648^2
// source and a 1024^2 guide; see the measurements below).
constexpr int kMinCoarsestSide = 64;

// Defaults, measured (tsynth_bench_optimisation, 1024^2 output, guide = a
// different DEM box-reduced 16x, up-sampled bilinearly, heights mapped onto
// the source's range; pit removal Fill; seed 0; 2 shared cores, times noisy).
// E0 = finest energy (m^2 per patch), rms16 = RMS to the guide at 1/16 scale
// (the guide's own scale; the source mirror-tiled scores 575 m / 977 m),
// pits0 = strict local minima of the output (1M cells).
//   source colorado (648^2, 90 m) <- guide alps-montblanc:
//     N=7 L=4 a=0.5 pm=4:  E0  3956  rms16  76.4  pits0  4634   6.0 s
//     N=5 / N=9:           E0  1145 / 10248 rms16 51.2 / 103.4  pits0 4745 / 3598
//     a=0.25 / 0.8 / 1.0:  E0  3767 / 3887 / 3923  rms16 102.6 / 53.8 / 43.7
//     pm=2 / 6:            E0  4345 / 3668  rms16 81.3 / 74.6  time 3.0 / 6.6 s
//     L=3 / L=5:           E0  4025 / 3858  rms16 35.4 / 158.3  pits0 3515 / 4431
//     a=0.8 L=3:           E0  4079  rms16  24.8  pits0  3632   4.8 s
//   source alps-montblanc (647^2, 93 m) <- guide andes-chile:
//     N=7 L=4 a=0.5 pm=4:  E0 11633  rms16 166.7  pits0 13889   5.0 s
//     N=5 / N=9:           E0  3542 / 31858  rms16 119.6 / 207.5
//     a=0.25 / 0.8 / 1.0:  E0 11634 / 12171 / 12244  rms16 218.2 / 136.2 / 122.3
//     pm=2 / 6:            E0 13356 / 11242  rms16 173.6 / 161.1
//     L=3 / L=5:           E0 12063 / 11507  rms16 113.7 / 309.4  pits0 14484 / 8296
//     a=0.8 L=3:           E0 12282  rms16 105.3  pits0 13721   4.8 s
// Choices: alpha 0.8: the guide is followed 30% (colorado) / 18% (alps) more
// closely than at 0.5 for 1.5% / 4.6% more energy; 1.0 gains less per step
// and leaves no margin. L = 3 (coarsest side >= 64): with alpha 0.8 it halves
// (colorado) or cuts by a quarter (alps) the guide error of L = 4 for 5% / 1%
// more energy and 19% / 13% fewer pits; L = 5 (a 21-cell source level) doubles
// the guide error. 4 PatchMatch iterations: 2 -> 4 lowers the energy 9% / 13%,
// 4 -> 6 only 7% / 3% for 50% more search time. N = 7: N = 5 scores lower per
// cell (easier to match, 25 cells) and looked smoother in the hillshades; N = 9
// raised the guide error by a third and the time by 10-90%; 7 is the middle of
// the paper's range.

struct OptimisationOptions
{
  int patchSize = 7;          // N, odd, cells
  int levels = 0;             // L; 0: as many as keep the coarsest level >= kMinCoarsestSide
  double alpha = 0.8;         // guide weight at the coarsest level (exponential schedule)
  int iterationsPerLevel = 2; // mu (the paper's value)
  int patchMatchIterations = 4;
  // The paper's continuous rotation angles are reduced to the grid's exact ones:
  // quarter turns (90, 180, 270 degrees) and a mirror, so no patch is resampled.
  bool rotations = false;   // source patches also turned by 90, 180 and 270 degrees
  bool reflections = false; // and mirrored (with every allowed turn)
  bool removePits = true;
  PitRemovalOptions pitRemoval; // method defaults to Breach, as the paper chose
  // Beyond the paper: the output itself made to drain at the end, as the
  // synthesis' --drainage does (MultiscalePitRemoval.h: pitRemoval.method on
  // block means from the coarsest level's scale down to 2 cells, the last
  // few-cell pits filled). Off by default, as in the paper, which leaves the
  // finest level alone; measured on 1024^2 from Colorado with a Mont Blanc
  // guide, the paper's coarse-level removal leaves 32 depressions deeper than
  // 20 m (46 without it; the source itself has 2.4 per 10^6 cells, ours 30).
  bool drainOutput = false;
  std::uint64_t seed = 0;
  // How far the guide is to be trusted per guide cell (0..1; empty: 1
  // everywhere): the guide's weight in every E-step is multiplied by it, and
  // where it is below 1 the coarsest start blends the guide with random
  // regions of the source (randomRegions) instead of taking the guide alone.
  // A stroke sketch's target is confident near the lines only
  // (SynthesisTarget::weight); the land between them is left to the source.
  std::vector<float> guideConfidence;
  // Told the fraction done (0..1, stage "optimise"; Core/Progress.h); the
  // caller's CancellationScope stops the optimisation with tsynth::Cancelled.
  ProgressReport progress;
  // A run whose optimisationMemoryEstimate is above this many bytes (0:
  // defaultMemoryBudget()) is refused before any work (by buildOptimisationGuide
  // and optimiseTerrain), naming the front end's options to change.
  double memoryBudget = 0.0;
  std::string memoryOption = "the memory budget";
  std::string sizeOption = "the output size";
};

// The options `tsynth optimise` and the Terrain Optimisation filter share (Core/OptionTable.h),
// their defaults a default OptimisationOptions': patch size, levels, alpha, iterations, search
// iterations, rotations, reflections, pit removal (off or a method), drain output, seed, output
// size and memory budget (GB).
const std::vector<OptionRow>& optimisationOptionRows();

// Peak memory in bytes of an optimisation of a width x height output from a
// source of sourceCells cells (at the output's cell size), as `tsynth optimise`
// and the Terrain Optimisation filter run it: per output cell the guide (built
// like a synthesis target) and its pyramid, the correspondence map, costs and
// terrain of a level, the E-step's sums and the coarse levels' pit removal; per
// source cell the read DEM, its pyramid and features, and one oriented copy
// (heights, valid centres) per orientation (quarter turns x mirrors); and the
// program itself. Measured (TerrainOptimisation.cxx) and rounded up: 1.2 to
// 1.4 times the measured peak from 512^2 outputs on.
double optimisationMemoryEstimate(int width,
  int height,
  std::size_t sourceCells,
  const OptimisationOptions& options);

// Throws tsynth::Error (checkMemoryBudget's sentence, with the estimate) if the
// run exceeds options.memoryBudget.
void checkOptimisationMemory(int width,
  int height,
  std::size_t sourceCells,
  const OptimisationOptions& options);

struct OptimisationLevel
{
  int level = 0; // k: 0 is the finest
  int width = 0;
  int height = 0;
  std::vector<double> energy; // E_t (mean SSD per patch, m^2) after each iteration's M-step
  // countPits (strict local minima) of the level's terrain after its last E-step,
  // before and after that E-step's pit removal (equal on level 0, which is the
  // output and has no pit removal, unless drainOutput drains it; equal when
  // removePits is off).
  std::size_t pitsBeforeRemoval = 0;
  std::size_t pitsAfter = 0;
  double seconds = 0.0;
};

// Inputs: heights are matched as they are (no height offset, as the paper
// advises), so the guide should lie in the source's height range. A source on
// another cell size than the guide's is resampled to it (bilinear). Invalid
// source cells never enter: a patch centre is used only if its whole patch (in
// its orientation) is valid. At invalid guide cells the guide term is off (the
// cell is the mean of the patches alone; the coarsest start uses the level's
// mean guide height there). The output is valid everywhere.
struct OptimisationResult
{
  Heightfield terrain;                   // at the guide's size and cell size
  std::vector<OptimisationLevel> levels; // coarsest first
  std::size_t pitsBeforeDraining = 0;    // with drainOutput: the output's pits before it
};

// Throws tsynth::Error (one sentence) for a source without a valid cell or a
// flat one (nothing to copy); what the front ends check before building a guide.
void checkOptimisationSource(const Heightfield& source);

// Throws tsynth::Error (one sentence) for: a source or guide without valid
// cells, a patch size that is even or outside 3..kMaxPatchSize, a guide or
// source too small for the pyramid asked for, alpha outside 0..1, iteration
// counts below 1.
OptimisationResult optimiseTerrain(const Heightfield& source,
  const Heightfield& guide,
  const OptimisationOptions& options);

} // namespace tsynth
