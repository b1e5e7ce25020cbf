// Heightfield files in every format the project handles: the kernels' GDAL
// formats plus VTK's .vti (which needs VTK, so it lives here).
#pragma once

#include "Core/HeightfieldIO.h"
#include "Synthesis/Setup.h"

#include <string>
#include <vector>

namespace tsynth
{

// Throws tsynth::Error, in one sentence, when `path` names no file. A relative name (as the
// project's state files hold: Data/dems/colorado.png) also gets the folder it was looked for in
// and how ParaView looks elsewhere: what a user loading a state by hand needs to know.
void requireFileForReader(const std::string& path);

// True for paths ending in ".vti" (any case).
bool isVtiPath(const std::string& path);

// Reads any raster GDAL reads (see readHeightfield) or a .vti image with an
// "Elevation" array. Throws tsynth::Error with one clear sentence.
Heightfield readTerrainFile(const std::string& path,
  const ReadOptions& options = {},
  RasterInfo* info = nullptr);

// True for a single-band raster that is not 8-bit: a DEM, used as a sketch it is the target.
// Unreadable or several bands: false (a sketch image, read as one).
bool isDemRaster(const std::string& path);

// The sketch file as the synthesis set-up takes it (tsynth synth --sketch, the Terrain Sketch
// Reader): .vtp poly-lines (metres in the raster frame), a DEM used as the target, or a sketch
// image (stroke map or grey map). Warnings about the file are appended to `warnings`.
SketchInput readSketchInput(const std::string& path, std::vector<std::string>& warnings);

// Writes .tif, .png (+ sidecar) or .vti (inline binary, which this machine's
// ParaView reads; see DESIGN.md). Complete or not at all.
void writeTerrainFile(const std::string& path, const Heightfield& hf);

} // namespace tsynth
