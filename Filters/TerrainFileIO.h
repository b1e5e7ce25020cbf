// Heightfield files in every format the project handles: the kernels' GDAL
// formats plus VTK's .vti (which needs VTK, so it lives here).
#pragma once

#include "Core/HeightfieldIO.h"

#include <string>

namespace tsynth
{

// True for paths ending in ".vti" (any case).
bool isVtiPath(const std::string& path);

// Reads any raster GDAL reads (see readHeightfield) or a .vti image with an
// "Elevation" array. Throws tsynth::Error with one clear sentence.
Heightfield readTerrainFile(const std::string& path,
  const ReadOptions& options = {},
  RasterInfo* info = nullptr);

// Writes .tif, .png (+ sidecar) or .vti (inline binary, which this machine's
// ParaView reads; see DESIGN.md). Complete or not at all.
void writeTerrainFile(const std::string& path, const Heightfield& hf);

} // namespace tsynth
