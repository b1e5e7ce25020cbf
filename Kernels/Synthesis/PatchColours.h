// Colours for the synthesis's PatchId map: neighbouring patches get different colours, so a
// categorical colour map (the plugin's default for the PatchColour array) shows every patch.
#pragma once

#include <cstdint>
#include <vector>

namespace tsynth
{

// A categorical map of this many colours is enough: greedy colouring of a map of patches
// (each touching about six others) needs at most a handful.
constexpr int kPatchColours = 12;

// For each cell of a width x height PatchId grid (row-major, negative: no patch), a colour in
// 0 .. kPatchColours-1 (-1 where there is no patch). Patches sharing an edge of cells get
// different colours, chosen greedily in PatchId order; a patch whose neighbours already took
// every colour gets the one fewest of them hold. Deterministic: depends on the map only.
std::vector<std::int8_t> patchColours(const std::vector<int>& patchId, int width, int height);

} // namespace tsynth
