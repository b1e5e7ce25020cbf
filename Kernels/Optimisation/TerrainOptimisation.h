// Terrain optimisation (Scott & Dodgson 2021, after Kwatra et al. 2005): a
// terrain rebuilt entirely from patches of one source DEM so that it follows a
// guide. Gaussian pyramids of source and guide; per level a dense
// correspondence map (for each output cell the centre of a source patch) found
// by PatchMatch (M-step), and the terrain as the average of the overlapping
// source patches blended with the guide (E-step); optional pit removal after
// each E-step on every level but the finest.
#pragma once

#include "../Core/Heightfield.h"
#include "../Hydrology/PitRemoval.h"

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
// and source at least this many cells on their shorter side.
constexpr int kMinCoarsestSide = 32;

struct OptimisationOptions
{
  int patchSize = 7;          // N, odd, cells
  int levels = 0;             // L; 0: as many as keep the coarsest level >= kMinCoarsestSide
  double alpha = 0.5;         // guide weight at the coarsest level (exponential schedule)
  int iterationsPerLevel = 2; // mu (the paper's value)
  int patchMatchIterations = 4;
  bool rotations = false;   // source patches also turned by 90, 180 and 270 degrees
  bool reflections = false; // and mirrored
  bool removePits = true;
  PitRemovalOptions pitRemoval; // method defaults to Breach, as the paper chose
  std::uint64_t seed = 0;
  // Called with the fraction done (0..1); return false to stop (the call then
  // throws tsynth::Cancelled).
  std::function<bool(double)> progress;
};

struct OptimisationLevel
{
  int level = 0; // k: 0 is the finest
  int width = 0;
  int height = 0;
  std::vector<double> energy; // E_t (mean SSD per patch, m^2) after each iteration's M-step
  // countPits (strict local minima) of the level's terrain after its last E-step,
  // before and after that E-step's pit removal (equal on level 0, which is the
  // output and has no pit removal, and when removePits is off).
  std::size_t pitsBeforeRemoval = 0;
  std::size_t pitsAfter = 0;
  double seconds = 0.0;
};

struct OptimisationResult
{
  Heightfield terrain;                   // at the guide's size and cell size
  std::vector<OptimisationLevel> levels; // coarsest first
};

// Throws tsynth::Error (one sentence) for: a source or guide without valid
// cells, a patch size that is even or outside 3..kMaxPatchSize, a guide or
// source too small for the pyramid asked for, alpha outside 0..1, iteration
// counts below 1.
OptimisationResult optimiseTerrain(const Heightfield& source,
  const Heightfield& guide,
  const OptimisationOptions& options);

} // namespace tsynth
