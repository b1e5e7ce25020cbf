#include "PatchSize.h"

#include <cmath>

#include "Error.h"

namespace tsynth
{

void checkPatchSize(int patchSize, const std::string& name)
{
  if (patchSize < kMinSynthesisPatch || patchSize > kMaxSynthesisPatch ||
    patchSize % kPatchSizeStep != 0)
  {
    throw Error(name + " must be a multiple of " + std::to_string(kPatchSizeStep) + " from " +
      std::to_string(kMinSynthesisPatch) + " to " + std::to_string(kMaxSynthesisPatch) +
      " cells, not " + std::to_string(patchSize) + ".");
  }
}

void checkPatchSizeInRange(int patchSize, const std::string& name)
{
  if (patchSize < kMinSynthesisPatch || patchSize > kMaxSynthesisPatch)
  {
    throw Error(name + " must be from " + std::to_string(kMinSynthesisPatch) + " to " +
      std::to_string(kMaxSynthesisPatch) + " cells, not " + std::to_string(patchSize) + ".");
  }
}

int windowCorner(double centre, int patchSize)
{
  return static_cast<int>(std::lround(centre)) - patchSize / 2;
}

} // namespace tsynth
