// Reading and writing heightfields through GDAL (GeoTIFF, PNG, SRTM .hgt, ESRI ASCII, ...).
// In ParaView: vtkTerrainReader and vtkTerrainSketchReader (Terrain Reader, Terrain Sketch
// Reader), in Filters/.
#pragma once

#include "Geodesy.h"
#include "Grid.h"
#include "Heightfield.h"
#include "OptionTable.h"
#include "Sidecar.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace tsynth
{

// Cell sizes and normalised heights beyond anything on Earth are refused: 1e7 m
// is a quarter of the equator, 1e6 m (or ft) a hundred times Everest.
constexpr double kMaxCellSizeMetres = 1.0e7;
constexpr double kMaxNormalisedHeight = 1.0e6;

// The words of ZUnit in its order, as --z-unit takes them (parseZUnit also
// takes metres, feet and their other spellings).
inline constexpr const char* kZUnitWords[] = { "auto", "m", "ft" };

// Options that override what the file and its sidecar say.
struct ReadOptions
{
  ZUnit zUnit = ZUnit::Auto;
  double cellX = 0.0;         // > 0 overrides the cell size (metres)
  double cellY = 0.0;         // > 0 overrides; if only cellX is set it is used for both
  std::optional<double> zMin; // normalised-range integer images: value 0 maps here
  std::optional<double> zMax; // ... and the type's maximum (255 or 65535) here
  bool useSidecar = true;
};

// The read options as a table: the Terrain Reader's properties (ZUnit,
// CellSize, UseSidecar, UseNormalisedRange, ZMin, ZMax) and tsynth's --z-unit,
// --cell, --no-sidecar and --z-range (MIN,MAX). CellSize 0 means "from the
// sidecar or the georeference"; ZMin and ZMax apply only with UseNormalisedRange.
const std::vector<OptionRow>& readOptionRows();

// What a raster is, read from its header and sidecar without reading the heights.
struct RasterInfo
{
  std::string path;
  std::string driver;   // GDAL short name, e.g. "GTiff", "PNG", "SRTMHGT", "AAIGrid"
  std::string dataType; // GDAL type name of the height band, e.g. "Int16"
  int width = 0;
  int height = 0;
  int bands = 0;
  double cellX = 1.0; // metres
  double cellY = 1.0;
  bool cellSizeKnown = false;
  std::string cellSizeSource;  // "options", "sidecar", "projected CRS", "geographic CRS", ...
  ZUnit zUnit = ZUnit::Metres; // unit the stored values are in
  std::string zUnitSource;
  bool normalised = false; // integer values mapped through [zMin, zMax]
  double zMin = 0.0;
  double zMax = 0.0;
  std::optional<double> nodata;
  std::string sidecarPath; // empty when no sidecar was used
  Georeference georef;
  std::string crsName;               // human-readable CRS name, empty if none
  std::vector<std::string> warnings; // things the user should know that did not stop the read
};

// The metric size of a degree at `centreLatitude` when `crs` (WKT, PROJ string or
// any definition GDAL reads) is geographic, on that CRS's ellipsoid; nothing when
// it is projected, local or not understood. For grids another reader left in
// degrees (ParaView's GDAL Raster Reader gives its MAP_PROJECTION as a PROJ
// string and its spacing in degrees).
std::optional<MetresPerDegree> geographicDegree(const std::string& crs, double centreLatitude);

// Reads the header. Throws tsynth::Error with one clear sentence on any problem
// (missing file, not a raster, several colour bands, bad sidecar, ...).
RasterInfo readRasterInfo(const std::string& path, const ReadOptions& options = {});

// Reads heights in metres, rows flipped so row 0 is the south edge; nodata,
// NaN and masked cells become invalid. Throws tsynth::Error if the raster has
// no valid cell, would need more memory to read than the machine allows (checkReadFits), or
// cannot be read.
Heightfield readHeightfield(const std::string& path,
  const ReadOptions& options = {},
  RasterInfo* info = nullptr);

// Writes by extension: ".tif"/".tiff" GeoTIFF float32 (georeference kept, NaN
// nodata), ".png" 16-bit PNG plus a NAME.json sidecar with the range and cell
// size. The file appears complete or not at all (written aside, then renamed).
void writeHeightfield(const std::string& path, const Heightfield& hf);

// The largest code of a 16-bit image.
constexpr double kLargestPng16Code = 65535.0;

// The heights 16-bit codes 0 and 65535 stand for (a PNG sidecar's z_min and z_max).
struct Png16Range
{
  double zMin = 0.0;
  double zMax = 1.0;
};

// Writes a 16-bit PNG (no sidecar) whose codes span `range` rather than the
// heightfield's own range, so that the tiles of one terrain share one scale and
// their shared edges get the same codes. Invalid cells are written as code 0.
// The file appears complete or not at all. Throws tsynth::Error naming `path`.
void writePng16InRange(const std::string& path, const Heightfield& hf, const Png16Range& range);

// The GDAL geotransform of a heightfield's file (x0, dx, rx, y0, ry, dy; row 0
// north): its own, or a local frame in metres with the south-west cell centre at (0, 0).
std::array<double, 6> geoTransformOf(const Heightfield& hf);

// Writes an 8-bit RGB PNG; rgb holds width*height*3 bytes, first row at the top.
void writeRgbPng(const std::string& path,
  int width,
  int height,
  const std::vector<std::uint8_t>& rgb);

// An 8-bit image of 1 to 4 channels (grey, grey+alpha, RGB, RGBA), interleaved,
// first row at the top (north) as in the file: sketches are read this way.
struct ColourImage
{
  int width = 0;
  int height = 0;
  int channels = 0;
  std::vector<std::uint8_t> data;
  const std::uint8_t* pixel(int column, int rowFromTop) const
  {
    return data.data() + rowMajor(column, rowFromTop, width) * static_cast<std::size_t>(channels);
  }
};

// Reads an image GDAL understands; 16-bit channels are scaled to 8 bits.
// Throws tsynth::Error with one clear sentence (also when reading would not fit in memory).
ColourImage readColourImage(const std::string& path);

// True if the extension names a format writeHeightfield writes.
bool isHeightfieldWriteExtension(const std::string& path);

// The file name's extension in lower case, with its dot (".tif"), or "".
std::string lowerExtension(const std::string& path);

// True if the file name ends in `wanted` (lower case, with its dot: ".vtp"),
// in any case ("A.VTP" too).
bool hasExtension(const std::string& path, const char* wanted);

} // namespace tsynth
