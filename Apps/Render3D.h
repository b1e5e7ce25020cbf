// An oblique, lit 3D view of a heightfield rendered off screen to a PNG.
#pragma once

#include "Core/Heightfield.h"

#include <string>

namespace tsynth
{

struct Render3DOptions
{
  int width = 1600;
  int height = 1000;
  double exaggeration = 2.0;     // vertical scale factor
  double viewAzimuthDeg = 200.0; // camera direction from the centre, clockwise from north
  double viewElevationDeg = 35.0;
};

// Needs an X display (DISPLAY); tsynth re-runs itself under xvfb-run when there is none.
// Throws tsynth::Error on failure; the PNG appears complete or not at all.
void render3D(const Heightfield& hf, const std::string& pngPath, const Render3DOptions& options);

} // namespace tsynth
