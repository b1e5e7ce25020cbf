// tsynth convert: a DEM rewritten in metres as one file (GeoTIFF, 16-bit PNG,
// VTK image) or cut into tiles that share their edges (Core/TileExport.h).
#pragma once

#include <string>
#include <vector>

namespace tsynth::cli
{

int runConvert(std::vector<std::string> args);

} // namespace tsynth::cli
