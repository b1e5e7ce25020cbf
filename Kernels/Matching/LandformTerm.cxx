#include "LandformTerm.h"

#include "../Core/Smoothing.h"

#include <algorithm>
#include <cmath>

namespace tsynth
{

int landformCell(int k, int patchSize, int blockSize)
{
  const int f = std::max(1, blockSize);
  const int blocks = patchSize / f;
  const double spacing = static_cast<double>(blocks) / kLandformSide;
  const int block = std::clamp(static_cast<int>(std::floor((k + 0.5) * spacing)), 0, blocks - 1);
  return block * f + f / 2;
}

Heightfield landformImage(const Heightfield& exemplar, int patchSize)
{
  return smoothLarge(exemplar, landformSigma(patchSize));
}

bool LandformQuery::empty() const
{
  return std::all_of(weights.begin(), weights.end(), [](float w) { return !(w > 0.0f); });
}

} // namespace tsynth
