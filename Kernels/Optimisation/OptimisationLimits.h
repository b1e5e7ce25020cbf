// The counts a user may ask of a terrain optimisation: beyond them a run would
// take days or the pyramid would have no cells left; they catch typing errors.
// Light enough for the Terrain Optimisation filter's header, whose clamp macros
// take them; the options table (TerrainOptimisation.h) gives them to every front end.
#pragma once

namespace tsynth
{

constexpr int kMaxOptimisationLevels = 16;
constexpr int kMaxOptimisationIterations = 100; // E/M iterations per level, PatchMatch passes

} // namespace tsynth
