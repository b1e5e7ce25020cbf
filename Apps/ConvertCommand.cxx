// tsynth convert: a DEM rewritten as GeoTIFF, 16-bit PNG with its sidecar or .vti, or cut
// into tiles that share their edges.
#include "Commands.h"

#include "CliSupport.h"
#include "CommandLine.h"
#include "TerrainFileIO.h"

#include "Core/FileRoles.h"
#include "Core/HeightfieldIO.h"
#include "Core/TileExport.h"

#include <iostream>
#include <optional>

namespace tsynth::cli
{

namespace
{

const char* const kConvertHelp = R"(Usage: tsynth convert DEM -o OUT [--tile-size N] [read options]

Reads a DEM (units, sidecar, nodata as for every command) and writes heights in
metres: .tif GeoTIFF float32 (georeference kept), .png 16-bit with a NAME.json
sidecar recording the range and cell size, or .vti (opens in ParaView).

With --tile-size N the DEM is cut into tiles of N x N samples in a fixed grid
from its north-west corner; neighbouring tiles share their edge row or column,
so they meet exactly. Each tile has a NAME.json sidecar with its height range,
its place in the DEM and, for 16-bit tiles, the engines' import scales.
  -o OUT.vrt   GeoTIFF tiles OUT_x<column>_y<row>.tif (float32, nodata kept,
               georeferenced) and OUT.vrt, a GDAL virtual mosaic of them
  -o OUT.png   16-bit PNG tiles OUT_x<column>_y<row>.png, rows north first,
               column and row from the north-west (Unreal's tiled landscape)
  -o OUT.raw   16-bit little-endian RAW tiles OUT_<x>_<z>.raw (or .r16), rows
               south first, x from the west and z from the south (Unity)
16-bit tiles are 2^k + 1 samples a side (33 to 8193) and share one height scale
(the DEM's range); past the DEM's east and south edges they repeat its last
column and row. A DEM with nodata can only be written as GeoTIFF tiles.
)";

void checkTiledOutputs(const std::string& input,
  const ReadOptions& options,
  const std::string& output,
  int tileSize)
{
  const RasterInfo info = readRasterInfo(input, options);
  const TileFormat format = *tileFormatFor(output);
  const TileGrid grid = tileGridFor(info.width, info.height, tileSize, format);
  FileRoles files;
  files.input(input, "the DEM", options.useSidecar);
  if (format == TileFormat::GeoTiff)
  {
    files.output(output, "-o", FileRoles::Content::Other);
  }
  for (int r = 0; r < grid.rows; ++r)
  {
    for (int c = 0; c < grid.columns; ++c)
    {
      const TileFiles tile =
        tileFilesFor(output, format, tileAt(grid, c, r, info.width, info.height), grid.rows);
      files.output(tile.heights, "a tile", FileRoles::Content::HeightsAndSidecar);
    }
  }
  files.check();
}

int runTiledConvert(const std::string& input,
  const ReadOptions& options,
  const std::string& output,
  int tileSize,
  bool progress)
{
  if (!tileFormatFor(output))
  {
    throw UsageError("Tiles are written as -o OUT.vrt (GeoTIFF tiles and their mosaic), OUT.png "
                     "or OUT.raw (16-bit engine heightmaps), not " +
      output + ".");
  }
  checkTiledOutputs(input, options, output, tileSize);
  const Heightfield hf = readDem(input, options);
  ProgressBar bar(progress);
  const TileExportReport report =
    exportTiles(hf, output, tileSize, [&](double f, const std::string& stage) { bar(f, stage); });
  std::cout << "Wrote " << report.tiles.size() << " tiles of " << report.grid.size << " x "
            << report.grid.size << " samples (" << report.grid.columns << " x " << report.grid.rows
            << "), " << report.tiles.front().heights << " to " << report.tiles.back().heights
            << ", each with its sidecar";
  if (!report.mosaic.empty())
  {
    std::cout << ", and the mosaic " << report.mosaic;
  }
  std::cout << "\n";
  if (report.format != TileFormat::GeoTiff)
  {
    std::cout << "Heights " << report.zMin << " to " << report.zMax
              << " m in codes 0 to 65535 in every tile";
    if (report.paddedSamples > 0)
    {
      std::cout << "; " << report.paddedSamples
                << " samples past the DEM's edge repeat its last column or row";
    }
    std::cout << "\n";
  }
  return 0;
}

} // namespace

int runConvert(std::vector<std::string> args)
{
  if (wantsHelp(args))
  {
    std::cout << kConvertHelp << kReadOptionsHelp;
    return 0;
  }
  CommandLine cl(std::move(args));
  const std::optional<std::string> output = cl.take("--output", "-o");
  const std::optional<double> tileSize =
    takeRowNumber(cl, optionRow(tileExportOptionRows(), "TileSize"));
  const bool progress = !cl.takeFlag("--no-progress");
  const ReadOptions options = takeReadOptions(cl);
  const std::string path = oneInput(cl, "convert");
  if (!output)
  {
    throw UsageError("tsynth convert needs an output file: -o OUT.tif|.png|.vti, or -o "
                     "OUT.vrt|.png|.raw with --tile-size N.");
  }
  if (tileSize)
  {
    return runTiledConvert(path, options, *output, static_cast<int>(*tileSize), progress);
  }
  if (hasExtension(*output, ".vrt") || hasExtension(*output, ".raw") ||
    hasExtension(*output, ".r16"))
  {
    throw UsageError(*output + " is a tiled output: give the tile size, --tile-size N.");
  }
  if (!isVtiPath(*output) && !isHeightfieldWriteExtension(*output))
  {
    throw UsageError("The output must end in .tif, .png or .vti, not " + *output + ".");
  }
  FileRoles files;
  files.input(path, "the DEM", options.useSidecar);
  files.output(*output, "-o");
  files.check();
  const Heightfield hf = readDem(path, options);
  writeTerrainFile(*output, hf);
  std::cout << "Wrote " << *output << "\n";
  return 0;
}

} // namespace tsynth::cli
