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

// render3D lives in a module of its own (kRender3DModule, built from Render3D.cxx), which
// tsynth-main loads only for `render --3d`: VTK's rendering and what it needs (X11, GL, GLEW:
// 32 of the 168 libraries tsynth-main loaded) took 0.05 s of every command's start. The
// module's one C symbol, kRender3DEntry, gives render3D.
using Render3DFunction = void (*)(const Heightfield&, const std::string&, const Render3DOptions&);
inline constexpr const char* kRender3DModule = "tsynth-render3d.so";
inline constexpr const char* kRender3DEntry = "tsynthRender3D";

} // namespace tsynth
