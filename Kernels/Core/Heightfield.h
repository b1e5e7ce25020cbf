// A regular grid of heights in metres: the data every stage reads and writes.
#pragma once

#include <array>

#include "Grid.h"
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace tsynth
{

// Where a grid sits on the Earth, when it came from a georeferenced file.
// Carried through unchanged so outputs can be written with the same frame.
struct Georeference
{
  std::string crsWkt;                   // empty when the source had no CRS
  std::array<double, 6> geoTransform{}; // GDAL order: x0, dx, rx, y0, ry, dy
  bool hasGeoTransform = false;
  bool isGeographic = false; // CRS in degrees (cell size was converted to metres)
};

// Heights are stored row-major with row 0 at the south (y = 0), so that
// index (i, j) is the point x = i * cellX, y = j * cellY, the same layout
// as vtkImageData. File readers flip rows (files keep row 0 at the north).
struct Heightfield
{
  int width = 0;
  int height = 0;
  double cellX = 1.0; // metres
  double cellY = 1.0; // metres
  bool cellSizeKnown = false;
  std::vector<float> z;            // metres; NaN where invalid
  std::vector<std::uint8_t> valid; // empty means every cell is valid
  Georeference georef;
  std::string sourceZUnit = "m"; // unit of the source file ("m" or "ft")

  Heightfield() = default;
  Heightfield(int w, int h, float value = 0.0f);

  std::size_t size() const { return z.size(); }
  std::size_t index(int i, int j) const { return rowMajor(i, j, width); }
  float at(int i, int j) const { return z[index(i, j)]; }
  float& at(int i, int j) { return z[index(i, j)]; }
  bool isValid(std::size_t k) const { return valid.empty() || valid[k] != 0; }
  bool isValid(int i, int j) const { return isValid(index(i, j)); }
  bool hasMask() const { return !valid.empty(); }

  // Number of valid cells.
  std::size_t validCount() const;
};

class ContentHasher;

// Feeds a heightfield's grid, cell size, heights and nodata mask to a content
// hash (ContentHash.h): a key for what was computed from it.
void hashHeightfield(ContentHasher& h, const Heightfield& f);

struct HeightRange
{
  float min = 0.0f;
  float max = 0.0f;
  double mean = 0.0;
  std::size_t validCells = 0;
};

// Range and mean over valid cells only (nodata never enters the figures).
HeightRange computeHeightRange(const Heightfield& hf);

// The value at quantile p (0..1) of `values` (nearest rank below; 0 if empty).
double percentile(std::vector<float> values, double p);

// Marks NaN and infinite heights invalid; drops the mask if every cell is valid.
void normaliseMask(Heightfield& hf);

// Heights no terrain has in any unit (the Earth's radius is 6.4e9 mm), and far
// enough below float's range that squared differences summed over a million
// million cells stay finite. Values beyond are an undeclared nodata value
// (float rasters often use -3.4e38).
constexpr double kMaxPlausibleHeight = 1.0e12;

// Throws tsynth::Error naming `name` (a file, an input) if a valid height lies
// beyond +-kMaxPlausibleHeight, saying how many and how to declare the nodata.
void checkPlausibleHeights(const Heightfield& hf, const std::string& name);

// True if some side x side window of `hf` holds no nodata cell (a patch can be cut there).
bool hasValidWindow(const Heightfield& hf, int side);

// Throws tsynth::Error naming `path` before a terrain whose valid heights are not finite or lie
// beyond kMaxPlausibleHeight is written: tsynth would refuse to read it back.
void checkWritableHeights(const Heightfield& hf, const std::string& path);

} // namespace tsynth
