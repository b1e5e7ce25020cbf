#include "TileExport.h"

#include "Error.h"
#include "Grid.h"
#include "HeightfieldIO.h"
#include "OutputFile.h"

#include <cpl_string.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <sstream>

namespace fs = std::filesystem;

namespace tsynth
{

namespace
{

// Engine heightmaps: 2^k + 1 samples a side, from Unity's smallest terrain (33)
// to the largest either engine imports as one tile (8193).
constexpr int kSmallestEngineTile = 33;
constexpr int kLargestEngineTile = 8193;

// Unreal's landscape: a 16-bit code c stands for (c - 32768) * zScale / 128
// centimetres above the landscape's z location (zScale 100: -256..256 m).
constexpr double kUnrealMidCode = 32768.0;
constexpr double kUnrealCodesPerScale = 128.0;
constexpr double kCentimetresPerMetre = 100.0;

bool isEngineSize(int size)
{
  const int quads = size - 1;
  return size >= kSmallestEngineTile && size <= kLargestEngineTile && (quads & (quads - 1)) == 0;
}

std::string engineSizesAround(int size)
{
  int below = kSmallestEngineTile;
  while (below < kLargestEngineTile && 2 * (below - 1) + 1 <= size)
  {
    below = 2 * (below - 1) + 1;
  }
  const int above = std::min(kLargestEngineTile, 2 * (below - 1) + 1);
  if (size < kSmallestEngineTile || below == above)
  {
    return std::to_string(below);
  }
  return std::to_string(below) + " or " + std::to_string(above);
}

const char* formatName(TileFormat format)
{
  switch (format)
  {
    case TileFormat::Png16:
      return "16-bit PNG";
    case TileFormat::Raw16:
      return "16-bit RAW";
    case TileFormat::GeoTiff:
      break;
  }
  return "GeoTIFF";
}

bool sixteenBit(TileFormat format)
{
  return format != TileFormat::GeoTiff;
}

int tilesAlong(int samples, int size)
{
  return std::max(1, (samples - 1 + size - 2) / (size - 1));
}

// The terrain's sample at a file position (column from the west, row from
// the north), clamped to its edge, from the band of its rows that `band` holds.
float sampleAt(const TerrainBand& band, int column, int rowFromNorth)
{
  const Heightfield& hf = band.heights;
  const int i = std::min(column, hf.width - 1);
  const int row = std::min(rowFromNorth, band.frame.height - 1) - band.firstRow;
  return hf.at(i, hf.height - 1 - row);
}

bool validAt(const TerrainBand& band, int column, int rowFromNorth)
{
  const Heightfield& hf = band.heights;
  const int i = std::min(column, hf.width - 1);
  const int row = std::min(rowFromNorth, band.frame.height - 1) - band.firstRow;
  return hf.isValid(i, hf.height - 1 - row);
}

// The tile's own heightfield (row 0 south, as every Heightfield): its valid
// samples for a GeoTIFF, `size` samples a side for a 16-bit tile.
Heightfield cutTile(const TerrainBand& band, const TileGrid& grid, const Tile& t, TileFormat format)
{
  const TerrainFrame& frame = band.frame;
  const int w = sixteenBit(format) ? grid.size : t.validWidth;
  const int h = sixteenBit(format) ? grid.size : t.validHeight;
  Heightfield tile(w, h);
  tile.cellX = frame.cellX;
  tile.cellY = frame.cellY;
  tile.cellSizeKnown = frame.cellSizeKnown;
  tile.sourceZUnit = "m";
  for (int k = 0; k < h; ++k) // rows from the tile's north edge
  {
    for (int i = 0; i < w; ++i)
    {
      const bool valid = validAt(band, t.firstColumn + i, t.firstRow + k);
      tile.at(i, h - 1 - k) = valid ? sampleAt(band, t.firstColumn + i, t.firstRow + k)
                                    : std::numeric_limits<float>::quiet_NaN();
    }
  }
  normaliseMask(tile);
  // The tile's frame: the terrain's, moved to the tile's north-west sample.
  const std::array<double, 6>& gt = frame.georef.geoTransform;
  tile.georef = frame.georef;
  tile.georef.geoTransform[0] = gt[0] + t.firstColumn * gt[1] + t.firstRow * gt[2];
  tile.georef.geoTransform[3] = gt[3] + t.firstColumn * gt[4] + t.firstRow * gt[5];
  return tile;
}

// 16-bit little-endian codes, rows south first (Unity's RAW heightmaps).
std::string rawCodes(const Heightfield& tile, const Png16Range& range)
{
  std::string bytes;
  bytes.reserve(tile.size() * 2);
  const double codesPerMetre = kLargestPng16Code / (range.zMax - range.zMin);
  for (int j = 0; j < tile.height; ++j)
  {
    for (int i = 0; i < tile.width; ++i)
    {
      const long code = std::clamp(std::lround((tile.at(i, j) - range.zMin) * codesPerMetre),
        0L,
        static_cast<long>(kLargestPng16Code));
      bytes.push_back(static_cast<char>(code & 0xff));
      bytes.push_back(static_cast<char>(code >> 8));
    }
  }
  return bytes;
}

void writeText(const std::string& path, const std::string& text)
{
  OutputFile file(path);
  file.write(text);
  file.commit();
}

nlohmann::ordered_json tilePlacement(const TerrainFrame& hf,
  const TileGrid& grid,
  const Tile& t,
  const Heightfield& tile)
{
  const HeightRange own = computeHeightRange(tile);
  const std::array<double, 6>& gt = tile.georef.geoTransform;
  nlohmann::ordered_json place = { { "column", t.column },
    { "row", t.row },
    { "columns", grid.columns },
    { "rows", grid.rows },
    { "size", grid.size },
    { "first_sample", { t.firstColumn, t.firstRow } },
    { "valid_samples", { t.validWidth, t.validHeight } },
    { "terrain_samples", { hf.width, hf.height } },
    // The north-west sample's centre in the terrain's frame (its CRS's units,
    // or metres from the terrain's south-west sample when it had none).
    { "north_west_centre",
      { gt[0] + 0.5 * gt[1] + 0.5 * gt[2], gt[3] + 0.5 * gt[4] + 0.5 * gt[5] } },
    { "height_min_m", own.validCells > 0 ? own.min : 0.0f },
    { "height_max_m", own.validCells > 0 ? own.max : 0.0f } };
  return place;
}

// The scales at which the engines reproduce the heights in metres.
nlohmann::ordered_json engineScales(const TerrainFrame& hf,
  const TileGrid& grid,
  const Tile& t,
  const Png16Range& range)
{
  const double span = range.zMax - range.zMin;
  const double zScale = span * kCentimetresPerMetre * kUnrealCodesPerScale / kLargestPng16Code;
  const double quads = grid.step();
  return {
    { "unreal",
      { { "xy_scale_cm", { kCentimetresPerMetre * hf.cellX, kCentimetresPerMetre * hf.cellY } },
        { "z_scale", zScale },
        { "z_location_cm",
          kCentimetresPerMetre * range.zMin + kUnrealMidCode * zScale / kUnrealCodesPerScale } } },
    { "unity",
      { { "heightmap_resolution", grid.size },
        { "size_m", { quads * hf.cellX, span, quads * hf.cellY } },
        { "position_m",
          { t.column * quads * hf.cellX,
            range.zMin,
            (grid.rows - 1 - t.row) * quads * hf.cellY } } } }
  };
}

std::string sidecarText(const TerrainFrame& hf,
  const TileGrid& grid,
  const Tile& t,
  const Heightfield& tile,
  TileFormat format)
{
  const Png16Range& range = hf.range;
  nlohmann::ordered_json doc = { { "z_unit", "m" }, { "cell_size_m", { hf.cellX, hf.cellY } } };
  if (sixteenBit(format))
  {
    doc["z_min"] = range.zMin; // the heights of codes 0 and 65535, for every tile
    doc["z_max"] = range.zMax;
    doc["row_order"] = format == TileFormat::Raw16 ? "south first" : "north first";
  }
  doc["tile"] = tilePlacement(hf, grid, t, tile);
  if (sixteenBit(format))
  {
    const nlohmann::ordered_json engines = engineScales(hf, grid, t, range);
    for (const auto& [engine, scales] : engines.items())
    {
      doc[engine] = scales;
    }
  }
  return doc.dump(2) + "\n";
}

std::string xmlEscaped(const std::string& text)
{
  char* escaped = CPLEscapeString(text.c_str(), static_cast<int>(text.size()), CPLES_XML);
  std::string out = escaped != nullptr ? escaped : "";
  CPLFree(escaped);
  return out;
}

// A GDAL virtual mosaic of the GeoTIFF tiles, in the terrain's frame; tile
// files are named relative to it. Shared edges hold the same values in both
// tiles, so the order of the sources does not matter.
std::string mosaicText(const TerrainFrame& hf,
  const std::vector<Tile>& tiles,
  const std::vector<TileFiles>& files)
{
  std::ostringstream x;
  x.precision(17);
  const std::array<double, 6>& gt = hf.georef.geoTransform;
  x << "<VRTDataset rasterXSize=\"" << hf.width << "\" rasterYSize=\"" << hf.height << "\">\n";
  if (!hf.georef.crsWkt.empty())
  {
    x << "  <SRS>" << xmlEscaped(hf.georef.crsWkt) << "</SRS>\n";
  }
  x << "  <GeoTransform>" << gt[0] << ", " << gt[1] << ", " << gt[2] << ", " << gt[3] << ", "
    << gt[4] << ", " << gt[5] << "</GeoTransform>\n";
  x << "  <VRTRasterBand dataType=\"Float32\" band=\"1\">\n";
  if (hf.hasNodata)
  {
    x << "    <NoDataValue>nan</NoDataValue>\n";
  }
  x << "    <UnitType>m</UnitType>\n";
  for (std::size_t n = 0; n < tiles.size(); ++n)
  {
    const Tile& t = tiles[n];
    const std::string name = fs::path(files[n].heights).filename().string();
    x << "    <SimpleSource>\n"
      << "      <SourceFilename relativeToVRT=\"1\">" << xmlEscaped(name) << "</SourceFilename>\n"
      << "      <SourceBand>1</SourceBand>\n"
      << "      <SourceProperties RasterXSize=\"" << t.validWidth << "\" RasterYSize=\""
      << t.validHeight << "\" DataType=\"Float32\" />\n"
      << "      <SrcRect xOff=\"0\" yOff=\"0\" xSize=\"" << t.validWidth << "\" ySize=\""
      << t.validHeight << "\" />\n"
      << "      <DstRect xOff=\"" << t.firstColumn << "\" yOff=\"" << t.firstRow << "\" xSize=\""
      << t.validWidth << "\" ySize=\"" << t.validHeight << "\" />\n"
      << "    </SimpleSource>\n";
  }
  x << "  </VRTRasterBand>\n</VRTDataset>\n";
  return x.str();
}

void writeTile(const Heightfield& tile,
  const TileFiles& files,
  TileFormat format,
  const Png16Range& range)
{
  switch (format)
  {
    case TileFormat::GeoTiff:
      writeHeightfield(files.heights, tile);
      break;
    case TileFormat::Png16:
      writePng16InRange(files.heights, tile, range);
      break;
    case TileFormat::Raw16:
      writeText(files.heights, rawCodes(tile, range));
      break;
  }
}

} // namespace

std::optional<TileFormat> tileFormatFor(const std::string& output)
{
  if (hasExtension(output, ".vrt"))
  {
    return TileFormat::GeoTiff;
  }
  if (hasExtension(output, ".png"))
  {
    return TileFormat::Png16;
  }
  if (hasExtension(output, ".raw") || hasExtension(output, ".r16"))
  {
    return TileFormat::Raw16;
  }
  return std::nullopt;
}

TileGrid tileGridFor(int width, int height, int size, TileFormat format)
{
  if (size < kSmallestTile || size > kLargestTile)
  {
    throw Error("A tile must be " + std::to_string(kSmallestTile) + " to " +
      std::to_string(kLargestTile) + " samples a side, not " + std::to_string(size) + ".");
  }
  if (sixteenBit(format) && !isEngineSize(size))
  {
    throw Error(std::string(formatName(format)) +
      " tiles for game engines are 2^k + 1 samples a side (" + std::to_string(kSmallestEngineTile) +
      " to " + std::to_string(kLargestEngineTile) + "), not " + std::to_string(size) + ": try " +
      engineSizesAround(size) + ".");
  }
  TileGrid g;
  g.size = size;
  g.columns = tilesAlong(width, size);
  g.rows = tilesAlong(height, size);
  if (g.count() > kMostTiles)
  {
    throw Error("Tiles of " + std::to_string(size) + " samples would cut this " +
      std::to_string(width) + " x " + std::to_string(height) + " terrain into " +
      std::to_string(g.count()) + " files, more than " + std::to_string(kMostTiles) +
      ": choose larger tiles.");
  }
  return g;
}

Tile tileAt(const TileGrid& grid, int column, int row, int width, int height)
{
  Tile t;
  t.column = column;
  t.row = row;
  t.firstColumn = column * grid.step();
  t.firstRow = row * grid.step();
  t.validWidth = std::min(grid.size, width - t.firstColumn);
  t.validHeight = std::min(grid.size, height - t.firstRow);
  return t;
}

TileFiles tileFilesFor(const std::string& output, TileFormat format, const Tile& tile, int rows)
{
  const fs::path out(output);
  const std::string stem = (out.parent_path() / out.stem()).string();
  std::string name;
  switch (format)
  {
    case TileFormat::GeoTiff:
      name = stem + "_x" + std::to_string(tile.column) + "_y" + std::to_string(tile.row) + ".tif";
      break;
    case TileFormat::Png16: // Unreal: _x<column>_y<row>, rows from the north
      name = stem + "_x" + std::to_string(tile.column) + "_y" + std::to_string(tile.row) + ".png";
      break;
    case TileFormat::Raw16: // Unity: _<x>_<z>, z from the south
      name = stem + "_" + std::to_string(tile.column) + "_" + std::to_string(rows - 1 - tile.row) +
        out.extension().string();
      break;
  }
  return { name, sidecarPathFor(name) };
}

HeightSummary summaryOf(const Heightfield& hf, int first, int rows)
{
  HeightSummary h;
  for (int row = first; row < first + rows; ++row)
  {
    const int j = hf.height - 1 - row;
    for (int i = 0; i < hf.width; ++i)
    {
      if (!hf.isValid(i, j))
      {
        ++h.holes;
        continue;
      }
      const double z = hf.at(i, j);
      h.min = h.valid == 0 ? z : std::min(h.min, z);
      h.max = h.valid == 0 ? z : std::max(h.max, z);
      ++h.valid;
    }
  }
  return h;
}

HeightSummary combined(const HeightSummary& a, const HeightSummary& b)
{
  if (a.valid == 0 || b.valid == 0)
  {
    HeightSummary h = a.valid == 0 ? b : a;
    h.holes = a.holes + b.holes;
    return h;
  }
  return { a.holes + b.holes, a.valid + b.valid, std::min(a.min, b.min), std::max(a.max, b.max) };
}

TerrainFrame terrainFrameFrom(const Heightfield& like,
  int width,
  int height,
  const HeightSummary& heights,
  TileFormat format,
  const std::string& output)
{
  TerrainFrame f;
  f.width = width;
  f.height = height;
  f.cellX = like.cellX;
  f.cellY = like.cellY;
  f.cellSizeKnown = like.cellSizeKnown;
  f.georef = like.georef;
  if (!f.georef.hasGeoTransform)
  {
    Heightfield whole;
    whole.width = width;
    whole.height = height;
    whole.cellX = like.cellX;
    whole.cellY = like.cellY;
    f.georef.geoTransform = geoTransformOf(whole);
    f.georef.hasGeoTransform = true;
  }
  f.hasNodata = heights.holes > 0;
  if (sixteenBit(format))
  {
    if (heights.holes > 0)
    {
      throw Error("The terrain has " + std::to_string(heights.holes) +
        " cells without data, which a 16-bit engine heightmap cannot mark: write GeoTIFF tiles "
        "(-o NAME.vrt) or fill the holes first.");
    }
    if (heights.valid == 0)
    {
      throw Error("Cannot write " + output + ": the terrain has no valid cell.");
    }
    // One scale for every 16-bit tile: the terrain's whole range.
    f.range = { heights.min, heights.max > heights.min ? heights.max : heights.min + 1.0 };
  }
  return f;
}

TerrainFrame terrainFrameOf(const Heightfield& hf, TileFormat format, const std::string& output)
{
  return terrainFrameFrom(hf, hf.width, hf.height, summaryOf(hf, 0, hf.height), format, output);
}

std::pair<int, int> tileRowsOf(const TileGrid& grid, int rank, int ranks)
{
  const auto share = [&](int r)
  { return static_cast<int>(static_cast<long long>(grid.rows) * r / ranks); };
  return { share(rank), share(rank + 1) };
}

std::pair<int, int> terrainRowsOf(const TileGrid& grid, int height, int first, int last)
{
  return { first * grid.step(), std::min(height - 1, (last - 1) * grid.step() + grid.size - 1) };
}

TileExportReport exportTileRows(const TerrainBand& band,
  const std::string& output,
  const TileGrid& grid,
  TileFormat format,
  int firstTileRow,
  int lastTileRow,
  const ProgressReport& progress)
{
  const TerrainFrame& frame = band.frame;
  TileExportReport report;
  report.format = format;
  report.grid = grid;
  report.zMin = frame.range.zMin;
  report.zMax = frame.range.zMax;
  if (firstTileRow >= lastTileRow)
  {
    return report;
  }
  const auto [needFirst, needLast] = terrainRowsOf(grid, frame.height, firstTileRow, lastTileRow);
  if (band.heights.width != frame.width || band.firstRow > needFirst ||
    band.firstRow + band.heights.height - 1 < needLast)
  {
    throw Error("The tiles of rows " + std::to_string(firstTileRow) + " to " +
      std::to_string(lastTileRow - 1) + " need the terrain's rows " + std::to_string(needFirst) +
      " to " + std::to_string(needLast) + ", which this part of it does not hold.");
  }
  const std::size_t count = cellCount(lastTileRow - firstTileRow, grid.columns);
  for (int r = firstTileRow; r < lastTileRow; ++r)
  {
    for (int c = 0; c < grid.columns; ++c)
    {
      const Tile t = tileAt(grid, c, r, frame.width, frame.height);
      const TileFiles files = tileFilesFor(output, format, t, grid.rows);
      const Heightfield tile = cutTile(band, grid, t, format);
      writeTile(tile, files, format, frame.range);
      writeText(files.sidecar, sidecarText(frame, grid, t, tile, format));
      if (sixteenBit(format))
      {
        report.paddedSamples += tile.size() - cellCount(t.validWidth, t.validHeight);
      }
      report.tiles.push_back(files);
      reportProgress(
        progress, static_cast<double>(report.tiles.size()) / static_cast<double>(count), "tiles");
    }
  }
  return report;
}

void writeTileMosaic(const TerrainFrame& frame, const TileGrid& grid, const std::string& output)
{
  std::vector<Tile> tiles;
  std::vector<TileFiles> files;
  for (int r = 0; r < grid.rows; ++r)
  {
    for (int c = 0; c < grid.columns; ++c)
    {
      tiles.push_back(tileAt(grid, c, r, frame.width, frame.height));
      files.push_back(tileFilesFor(output, TileFormat::GeoTiff, tiles.back(), grid.rows));
    }
  }
  writeText(output, mosaicText(frame, tiles, files));
}

TileExportReport exportTiles(const Heightfield& hf,
  const std::string& output,
  int tileSize,
  const ProgressReport& progress)
{
  const std::optional<TileFormat> format = tileFormatFor(output);
  if (!format)
  {
    throw Error("Tiles are written for an output ending in .vrt (GeoTIFF tiles), .png (16-bit "
                "PNG) or .raw/.r16 (16-bit RAW), not " +
      output + ".");
  }
  const TileGrid grid = tileGridFor(hf.width, hf.height, tileSize, *format);
  const TerrainFrame frame = terrainFrameOf(hf, *format, output);
  TileExportReport report =
    exportTileRows({ frame, hf, 0 }, output, grid, *format, 0, grid.rows, progress);
  if (*format == TileFormat::GeoTiff)
  {
    report.mosaic = output;
    writeTileMosaic(frame, grid, output);
  }
  return report;
}

const std::vector<OptionRow>& tileExportOptionRows()
{
  static const std::vector<OptionRow> rows = {
    numberRow("TileSize",
      "--tile-size",
      OptionType::Integer,
      kDefaultTileSize,
      kSmallestTile,
      kLargestTile),
  };
  return rows;
}

} // namespace tsynth
