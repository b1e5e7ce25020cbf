// The landform term of the matcher: a candidate patch compared with the target
// at coarse scale, low-passed candidate against low-passed target, on a small
// grid of samples across the patch, so that the chosen patches themselves carry
// the sketched ridges and valleys. Both sides are smoothed with the same
// Gaussian; the exemplars' detail finer than it never enters the comparison,
// so the term does not favour smooth patches.
#pragma once

#include "../Core/Heightfield.h"

#include <array>
#include <vector>

namespace tsynth
{

// Samples per side of the patch: 5 x 5, a fifth of a patch apart (16 cells
// for 80-cell patches), enough to see a ridge's crest and both flanks.
constexpr int kLandformSide = 5;
constexpr int kLandformSamples = kLandformSide * kLandformSide;
// Stored per candidate padded to two float16 vectors for the OpenCL kernel.
constexpr int kLandformStride = 32;
// Gaussian sigma of the low-pass, in patches (16 cells for 80-cell patches):
// it keeps what is wider than about a patch (the landforms) and all but drops
// relief of half a patch and less, where most of a terrain's slope lives, so
// rugged candidates are not penalised against a smooth target (at P/8 the
// synthesised terrain came out measurably flatter than the exemplars).
constexpr double kLandformSigmaInPatches = 0.2;

inline double landformSigma(int patchSize)
{
  return kLandformSigmaInPatches * patchSize;
}

// Position (cells from the window's lower-left corner, along one axis) of
// landform sample k: the centre cell of a block of `blockSize` cells, the
// blocks spread evenly over the patch, so the coarse pass can read the same
// sample from its block means.
int landformCell(int k, int patchSize, int blockSize);

// The exemplar seen through the low-pass of the landform term (nodata stays
// out of the averages and stays invalid).
Heightfield landformImage(const Heightfield& exemplar, int patchSize);

// What the target says at the landform samples of one window: heights of the
// low-passed target and the confidence in them (0 = no opinion), row-major,
// sample (a, b) at cells (landformCell(a), landformCell(b)) of the window.
struct LandformQuery
{
  std::array<float, kLandformSamples> heights{};
  std::array<float, kLandformSamples> weights{};
  bool empty() const;
};

} // namespace tsynth
