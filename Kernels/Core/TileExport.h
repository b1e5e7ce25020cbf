// Cutting a terrain into tiles that share their edge rows and columns, so that
// neighbouring tiles meet exactly:
// - GeoTIFF tiles (float32, metres, georeferenced) under a GDAL virtual mosaic
//   (NAME.vrt), for GIS;
// - 16-bit PNG heightmaps (rows north first, tiles NAME_x<column>_y<row> counted
//   from the north-west, as Unreal's tiled landscape import reads them), or
//   16-bit little-endian RAW heightmaps (rows south first, tiles
//   NAME_<x>_<z> counted from the south-west, as Unity's terrain tools read them),
//   of 2^k + 1 samples a side, all sharing one height scale.
// Every tile has a NAME.json sidecar giving its height range, its place in the
// terrain and, for the engines, the scales that reproduce the heights in metres.
// In ParaView: vtkTerrainTileWriter (Terrain Tile Writer), in Filters/.
#pragma once

#include "Grid.h"
#include "Heightfield.h"
#include "HeightfieldIO.h"
#include "OptionTable.h"
#include "Progress.h"

#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace tsynth
{

enum class TileFormat
{
  GeoTiff, // -o NAME.vrt
  Png16,   // -o NAME.png
  Raw16    // -o NAME.raw or NAME.r16
};

// The format an output name asks for; nullopt for any other extension.
std::optional<TileFormat> tileFormatFor(const std::string& output);

// The smallest and largest tile a side: a tile needs two samples to have an
// edge to share; past 2^16 + 1 samples a 16-bit engine heightmap is no tile.
constexpr int kSmallestTile = 2;
constexpr int kLargestTile = 65537;
// The Terrain Tile Writer's default: 1025 samples, Unity's default heightmap
// resolution and one of Unreal's recommended landscape sizes.
constexpr int kDefaultTileSize = 1025;

// The tile export's options as a table: the Terrain Tile Writer's TileSize and
// tsynth convert's --tile-size (which has no default: it asks for tiles).
const std::vector<OptionRow>& tileExportOptionRows();
// At most this many tiles per export (a 16k terrain in tiles of 65 samples):
// more is almost surely a mistyped size, and would flood the folder.
constexpr std::size_t kMostTiles = 65536;

// The fixed grid of tiles over a width x height terrain: tiles of `size`
// samples a side, each starting `size - 1` samples after the one before, so
// that neighbours share their edge row or column; the last column and row of
// tiles reach or pass the terrain's edge.
struct TileGrid
{
  int size = 0;
  int columns = 0;
  int rows = 0;
  int step() const { return size - 1; }
  std::size_t count() const { return cellCount(columns, rows); }
};

// Throws tsynth::Error (one sentence, with the sizes that work) if `size` does
// not suit `format` (engine heightmaps are 2^k + 1 samples, 33 to 8193), or the
// grid would hold more than kMostTiles tiles.
TileGrid tileGridFor(int width, int height, int size, TileFormat format);

// One tile of the grid: column and row from the north-west, the samples it
// takes from the terrain (file order: column from the west, row from the north).
struct Tile
{
  int column = 0;
  int row = 0;
  int firstColumn = 0;
  int firstRow = 0;
  int validWidth = 0;  // samples taken from the terrain; a 16-bit tile repeats
  int validHeight = 0; // its last column and row beyond them, up to `size`
};

Tile tileAt(const TileGrid& grid, int column, int row, int width, int height);

// The files of one tile: the heightmap and its sidecar.
struct TileFiles
{
  std::string heights;
  std::string sidecar;
};

// Where tile (column, row) of `output` is written (beside it, named after it).
TileFiles tileFilesFor(const std::string& output, TileFormat format, const Tile& tile, int rows);

// What the tiles' files need to know of the whole terrain, which one process
// may hold only in part (a band of its rows).
struct TerrainFrame
{
  int width = 0; // samples
  int height = 0;
  double cellX = 1.0; // metres
  double cellY = 1.0;
  bool cellSizeKnown = false;
  Georeference georef; // always with the whole terrain's geotransform
  bool hasNodata = false;
  Png16Range range; // 16-bit tiles: the heights of codes 0 and 65535 (the terrain's range)
};

// The frame of a terrain held whole (for 16-bit tiles, with its range).
// Throws tsynth::Error for a 16-bit format and a terrain with nodata or none valid.
TerrainFrame terrainFrameOf(const Heightfield& hf, TileFormat format, const std::string& output);

// What a frame needs of the heights: summed over the bands of several
// processes (each counting its own rows once), it is the whole terrain's.
struct HeightSummary
{
  std::size_t holes = 0;
  std::size_t valid = 0;
  double min = 0.0; // over the valid heights
  double max = 0.0;
};

// The summary of `rows` rows of `hf` from row `first` (from the north).
HeightSummary summaryOf(const Heightfield& hf, int first, int rows);

// Two summaries as one.
HeightSummary combined(const HeightSummary& a, const HeightSummary& b);

// The frame of a width x height terrain with these heights; `like` (the whole
// or a band of it) gives its cell size and georeference. Throws as terrainFrameOf.
TerrainFrame terrainFrameFrom(const Heightfield& like,
  int width,
  int height,
  const HeightSummary& heights,
  TileFormat format,
  const std::string& output);

// Rows of a terrain held by one process: `heights` holds the rows
// [firstRow, firstRow + heights.height) counted from the north (row 0 south,
// as in every Heightfield), all its columns.
struct TerrainBand
{
  const TerrainFrame& frame;
  const Heightfield& heights;
  int firstRow = 0;
};

// The tile rows [first, last) process `rank` of `ranks` writes: a contiguous
// share, as even as the rows allow (empty for ranks beyond the rows).
std::pair<int, int> tileRowsOf(const TileGrid& grid, int rank, int ranks);

// The terrain rows, from the north, that tile rows [first, last) need:
// [firstRow, lastRow] (both included; neighbours share their edge row).
std::pair<int, int> terrainRowsOf(const TileGrid& grid, int height, int first, int last);

struct TileExportReport
{
  TileGrid grid;
  TileFormat format = TileFormat::GeoTiff;
  std::vector<TileFiles> tiles;  // in row-major order from the north-west
  std::string mosaic;            // the .vrt (GeoTIFF tiles); empty otherwise
  double zMin = 0.0;             // 16-bit tiles: the heights of codes 0 and 65535,
  double zMax = 0.0;             // the same for every tile
  std::size_t paddedSamples = 0; // 16-bit tiles: samples repeated past the terrain's edge
};

// Writes the tiles of `hf` for `output` (.vrt, .png, .raw or .r16), and the
// mosaic for GeoTIFF tiles. Each file appears complete or not at all (inside an
// open Publication, all together). Throws tsynth::Error (one sentence) for a
// size that does not suit the format, a 16-bit export of a terrain with nodata
// (engines cannot mark it), or a failed write; tsynth::Cancelled when stopped.
TileExportReport exportTiles(const Heightfield& hf,
  const std::string& output,
  int tileSize,
  const ProgressReport& progress = {});

// The same, for tile rows [firstTileRow, lastTileRow) of `grid` from a band
// that holds their rows (terrainRowsOf), without the mosaic: the part of an
// export one of several processes writes. Throws tsynth::Error when the band
// lacks a row the tiles need.
TileExportReport exportTileRows(const TerrainBand& band,
  const std::string& output,
  const TileGrid& grid,
  TileFormat format,
  int firstTileRow,
  int lastTileRow,
  const ProgressReport& progress = {});

// Writes the GDAL virtual mosaic over every GeoTIFF tile of `grid` (named as
// exportTiles names them beside `output`).
void writeTileMosaic(const TerrainFrame& frame, const TileGrid& grid, const std::string& output);

} // namespace tsynth
