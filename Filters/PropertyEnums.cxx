#include "PropertyEnums.h"

#include "Core/Error.h"

#include <string>

namespace tsynth
{

Backend backendFromProperty(int value)
{
  switch (value)
  {
    case 0:
      return Backend::Auto;
    case 1:
      return Backend::OpenCL;
    case 2:
      return Backend::Cpu;
    default:
      throw Error("Backend " + std::to_string(value) + " is none of 0 auto, 1 OpenCL, 2 CPU.");
  }
}

MergeMode mergeModeFromProperty(int value)
{
  switch (value)
  {
    case 0:
      return MergeMode::Cut;
    case 1:
      return MergeMode::Poisson;
    case 2:
      return MergeMode::Shepard;
    case 3:
      return MergeMode::New;
    default:
      throw Error(
        "Merge mode " + std::to_string(value) + " is none of 0 cut, 1 poisson, 2 shepard, 3 new.");
  }
}

FillOrder fillOrderFromProperty(int value)
{
  switch (value)
  {
    case 0:
      return FillOrder::BestFirst;
    case 1:
      return FillOrder::Concentric;
    default:
      throw Error(
        "Fill order " + std::to_string(value) + " is none of 0 best-first, 1 concentric.");
  }
}

PitRemovalMethod pitRemovalMethodFromProperty(int value)
{
  switch (value)
  {
    case 0:
      return PitRemovalMethod::Fill;
    case 2:
      return PitRemovalMethod::Hybrid;
    default:
      return PitRemovalMethod::Breach;
  }
}

std::optional<PitRemovalMethod> drainageFromProperty(int value)
{
  if (value <= 0)
  {
    return std::nullopt;
  }
  return pitRemovalMethodFromProperty(value - 1);
}

} // namespace tsynth
