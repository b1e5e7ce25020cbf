// The correspondence search of terrain optimisation: source patches in up to
// eight orientations (quarter turns and mirrors), a dense nearest-patch field
// found by PatchMatch (Barnes et al. 2009), and the E-step that rebuilds a
// terrain from it.
//
// Each orientation t of a source level is stored as its own image ("copy"), in
// which the oriented patches are ordinary axis-aligned windows. A match is a
// patch centre in the copy's cells plus t, so propagation (a neighbour's centre
// shifted by one cell) and the SSD (contiguous rows) are the same code for every
// orientation. The copy maps to the source by source = A_t * copy + b_t.
//
// Determinism: the sweep splits the grid into bands of kBandRows rows (fixed,
// not per thread); a band reads the neighbours outside it from the map as it
// was when the iteration started, and every random draw is a hash of (seed,
// stream, cell, draw). The result does not depend on the number of threads.
#pragma once

#include "../Core/Heightfield.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace tsynth::optim
{

// Patch rows are read kLanes floats at a time (one AVX register), padded with
// zero-weight lanes: patch sizes up to kMaxPatchLanes cells.
constexpr int kLanes = 8;
constexpr int kMaxPatchLanes = 16;
constexpr int kOrientations = 8; // 4 quarter turns x (plain, mirrored)

// An integer map source = A * copy + b with A a rotation or reflection.
struct Orientation
{
  std::array<int, 4> a{ 1, 0, 0, 1 }; // row-major 2 x 2
  std::array<int, 2> b{ 0, 0 };
};

// Quarter turns `turns` (counter-clockwise) then, if `mirrored`, x -> -x, of a
// width x height source; b puts the copy's lowest corner on (0, 0).
Orientation makeOrientation(int turns, bool mirrored, int width, int height);

struct OrientedCopy
{
  int width = 0;
  int height = 0;
  std::size_t stride = 0; // floats per row (width + padding for the last lanes)
  Orientation toSource;
  std::vector<float> z;               // heights; 0 at invalid cells (never read by a patch)
  std::vector<std::uint8_t> centreOk; // per cell: the whole patch around it is valid
  std::vector<std::int32_t> centres;  // the indices with centreOk, in order
};

// One pyramid level of the source in every allowed orientation.
struct SourceLevel
{
  int width = 0; // of the unrotated level
  int height = 0;
  int patch = 0;
  int half = 0;
  int lanes = 0;                 // patch row rounded up to whole kLanes
  std::vector<int> orientations; // allowed t (0 = as is)
  std::array<OrientedCopy, kOrientations> copies;
};

// Throws tsynth::Error if no patch of `patch` x `patch` cells fits in the valid
// cells of the level.
SourceLevel makeSourceLevel(const Heightfield& source,
  int patch,
  bool rotations,
  bool reflections,
  int level);

struct Match
{
  std::int32_t x = 0; // patch centre in the copy's cells
  std::int32_t y = 0;
  std::int32_t t = 0; // orientation
};

// The patch centre of `m` in the unrotated source level's cells, and back.
std::array<int, 2> toSource(const SourceLevel& s, const Match& m);
Match fromSource(const SourceLevel& s, int x, int y, int t);

// A target grid (the current terrain of a level).
struct TargetGrid
{
  int width = 0;
  int height = 0;
  std::vector<float> z;
};

struct PatchMatchSettings
{
  int iterations = 4;
  std::uint64_t seed = 0;
  std::uint64_t stream = 0; // distinguishes levels and EM iterations
  // The plain reference: every candidate's SSD summed in full, one cell at a
  // time, no lanes and no early exit (for the benchmark's ratio).
  bool plainSsd = false;
  // Called after every iteration with the iteration count done; false stops.
  std::function<bool(int)> afterIteration;
};

// Random valid centres in every cell (the initial map of the coarsest level).
std::vector<Match> randomMatches(const SourceLevel& s,
  int width,
  int height,
  std::uint64_t seed,
  std::uint64_t stream);

// Eq. 4 with the child offset turned into the parent's orientation: the map of
// the next finer level (width x height), centres clamped into the valid range;
// a child whose centre is not valid gets a random valid one.
std::vector<Match> upsampleMatches(const std::vector<Match>& coarse,
  int coarseWidth,
  const SourceLevel& coarseSource,
  const SourceLevel& fineSource,
  int width,
  int height,
  std::uint64_t seed,
  std::uint64_t stream);

// Improves `map` (warm start) towards argmin of the patch SSD against
// `target`; `cost` receives each cell's SSD (over the patch cells inside the
// target). Returns false if afterIteration asked to stop.
bool patchMatch(const SourceLevel& s,
  const TargetGrid& target,
  std::vector<Match>& map,
  std::vector<float>& cost,
  const PatchMatchSettings& settings);

// The SSD of every cell's current match (no search).
void matchCosts(const SourceLevel& s,
  const TargetGrid& target,
  const std::vector<Match>& map,
  std::vector<float>& cost,
  bool plain = false);

// Eq. 5: each cell the mean of the overlapping matched patches' values at it
// (over the patches whose centre is inside the grid), blended with the guide
// with `weight` times the cell's `guideWeight` (0..1; 0 at invalid guide
// cells; empty: 1 everywhere).
void reconstruct(const SourceLevel& s,
  const std::vector<Match>& map,
  int width,
  int height,
  const std::vector<float>& guide,
  const std::vector<float>& guideWeight,
  double weight,
  std::vector<float>& out);

// Coherent random matches: the grid cut into blocks of `block` cells, each
// block a copy of one random region of the source (a random valid centre for
// the block's first cell, its neighbours following it cell by cell where their
// centres are valid). The start of free land, where the guide says nothing:
// the source's own structure at the level's scale, not noise.
std::vector<Match> randomRegions(const SourceLevel& s,
  int width,
  int height,
  int block,
  std::uint64_t seed,
  std::uint64_t stream);

} // namespace tsynth::optim
