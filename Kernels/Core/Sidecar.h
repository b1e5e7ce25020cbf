// The `NAME.json` sidecar beside a raster: units, cell size and normalised range.
#pragma once

#include <optional>
#include <string>

namespace tsynth
{

enum class ZUnit
{
  Auto, // from the sidecar or the file, else metres
  Metres,
  Feet
};

constexpr double kMetresPerFoot = 0.3048;

// Parses "m", "ft" and common spellings ("metres", "meters", "feet", ...).
// Returns std::nullopt for anything else.
std::optional<ZUnit> parseZUnit(const std::string& text);
const char* zUnitName(ZUnit unit);

struct Sidecar
{
  std::optional<ZUnit> zUnit;
  std::optional<double> cellX;
  std::optional<double> cellY;
  std::optional<double> zMin;
  std::optional<double> zMax;
  std::optional<double> nodata; // raw stored value that means "no data"
};

// The sidecar path of a raster: same folder and stem, extension ".json".
std::string sidecarPathFor(const std::string& rasterPath);

// Reads and validates a sidecar. Throws tsynth::Error naming the file and the
// problem (bad JSON, wrong type, non-positive cell size, z_max <= z_min).
Sidecar readSidecar(const std::string& path);

// Writes a sidecar through an OutputFile (a temporary renamed over `path`, or staged in the
// open Publication). Throws tsynth::Error naming `path` if the file cannot be written.
void writeSidecar(const std::string& path, const Sidecar& sidecar);

} // namespace tsynth
