// A colour picture of terrain: hypsometric tint modulated by hillshade.
#pragma once

#include "../Core/Heightfield.h"
#include "Hillshade.h"

#include <array>
#include <cstdint>
#include <vector>

namespace tsynth
{

// The tint ramp, t in [0, 1] from lowest to highest ground; RGB in [0, 1].
std::array<double, 3> terrainColour(double t);

// RGB bytes, width*height*3, first row at the top (north), ready for writeRgbPng.
// Invalid cells are drawn in a flat blue-grey.
std::vector<std::uint8_t> renderRelief(const Heightfield& hf, const ShadedRelief& relief);

// The same picture without the tint: the hillshade alone in grey, the way
// landforms are judged by eye (height colours can read as relief that is not
// there). Invalid cells as in renderRelief.
std::vector<std::uint8_t> renderGreyRelief(const Heightfield& hf, const ShadedRelief& relief);

} // namespace tsynth
