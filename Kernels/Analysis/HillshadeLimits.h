// The values the hillshade's options may take in a front end (tsynth render, the
// Terrain Hillshade filter): light enough for the filter's header, whose clamp
// macros take them; the options table (hillshadeOptionRows, Hillshade.h) gives
// them to every front end.
#pragma once

namespace tsynth
{

constexpr double kMaxSunAltitudeDeg = 90.0; // the zenith
constexpr double kFullTurnDeg = 360.0;      // azimuths from north round to north
// Vertical exaggerations beyond a thousandth or a thousand times show nothing but flat or black.
constexpr double kMinZFactor = 0.001;
constexpr double kMaxZFactor = 1000.0;

} // namespace tsynth
