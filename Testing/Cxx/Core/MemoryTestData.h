// Helpers shared by the memory budget tests (Core/TestMemory.cxx, Distance/TestDistanceMemory.cxx).
#pragma once

#include "Core/Memory.h"

#include <string>

namespace tsynth::test::memory
{

// "about N MB" as bytesText prints the estimate.
inline std::string about(double bytes)
{
  return "needs about " + bytesText(bytes) + " but the memory budget is ";
}

} // namespace tsynth::test::memory
