// The filters' enumeration properties (their XML EnumerationDomains and the
// classes' enums) mapped to the kernels' enums in one place, so every filter
// numbers them alike.
#pragma once

#include "Hydrology/PitRemoval.h"
#include "Matching/OpenClMatcher.h"
#include "Merging/PatchMerger.h"
#include "Synthesis/Synthesiser.h"

#include <optional>

namespace tsynth
{

// 0 auto (OpenCL if a device works), 1 OpenCL, 2 CPU.
Backend backendFromProperty(int value);

// 0 cut, 1 poisson, 2 shepard, 3 new.
MergeMode mergeModeFromProperty(int value);

// 0 best-first, 1 concentric.
FillOrder fillOrderFromProperty(int value);

// 0 fill, 1 breach, 2 hybrid (Terrain Pit Removal's Method).
PitRemovalMethod pitRemovalMethodFromProperty(int value);

// 0 off, 1 fill, 2 breach, 3 hybrid (Terrain Synthesis' Drainage, Terrain Optimisation's
// PitRemoval).
std::optional<PitRemovalMethod> drainageFromProperty(int value);

} // namespace tsynth
