// Tests of Kernels/Core/TileExport.cxx.
// Tiled export (Core/TileExport.h): neighbouring tiles share their edges
// exactly, the GeoTIFF mosaic gives back the terrain bit for bit, the 16-bit
// tiles share one height scale, and bad sizes, nodata and failed writes leave
// nothing behind. The files are read back through GDAL, not through our reader.
#include "Core/Error.h"
#include "Core/OutputFile.h"
#include "Core/TileExport.h"
#include "ErrorOf.h"
#include "TestData.h"

#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <memory>

namespace fs = std::filesystem;
using tsynth::Heightfield;

namespace
{

// A folder of its own for each test, emptied first.
fs::path freshFolder(const std::string& name)
{
  const fs::path dir = tsynth::test::scratchDir() / ("tiles-" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// A 70 x 50 terrain of distinct heights, 30 m cells, in a projected frame,
// with a hole of nodata when asked.
Heightfield terrain(bool withHole)
{
  Heightfield hf(70, 50);
  hf.cellX = hf.cellY = 30.0;
  hf.cellSizeKnown = true;
  for (int j = 0; j < hf.height; ++j)
  {
    for (int i = 0; i < hf.width; ++i)
    {
      hf.at(i, j) = 1000.0f + 3.25f * static_cast<float>(i) + 0.5f * static_cast<float>(j * j) +
        40.0f * std::sin(0.3f * static_cast<float>(i + 2 * j));
    }
  }
  hf.georef.hasGeoTransform = true;
  hf.georef.geoTransform = { 500000.0, 30.0, 0.0, 4200000.0, 0.0, -30.0 };
  if (withHole)
  {
    hf.valid.assign(hf.size(), 1);
    for (int j = 20; j < 26; ++j)
    {
      for (int i = 30; i < 37; ++i)
      {
        hf.valid[hf.index(i, j)] = 0;
        hf.at(i, j) = std::numeric_limits<float>::quiet_NaN();
      }
    }
  }
  return hf;
}

struct Raster
{
  int width = 0;
  int height = 0;
  std::vector<double> values; // file order: row 0 north
  std::array<double, 6> geoTransform{};
  double at(int column, int rowFromNorth) const
  {
    return values[static_cast<std::size_t>(rowFromNorth) * static_cast<std::size_t>(width) +
      static_cast<std::size_t>(column)];
  }
};

Raster readWithGdal(const fs::path& path)
{
  GDALAllRegister();
  std::unique_ptr<GDALDataset> ds(
    static_cast<GDALDataset*>(GDALOpen(path.string().c_str(), GA_ReadOnly)));
  if (!ds)
  {
    ADD_FAILURE() << "GDAL cannot open " << path;
    return {};
  }
  Raster r;
  r.width = ds->GetRasterXSize();
  r.height = ds->GetRasterYSize();
  r.values.resize(static_cast<std::size_t>(r.width) * static_cast<std::size_t>(r.height));
  EXPECT_EQ(ds->GetRasterBand(1)->RasterIO(GF_Read,
              0,
              0,
              r.width,
              r.height,
              r.values.data(),
              r.width,
              r.height,
              GDT_Float64,
              0,
              0,
              nullptr),
    CE_None);
  ds->GetGeoTransform(r.geoTransform.data());
  return r;
}

// The terrain's height at a file position (row from the north), NaN for nodata.
double terrainAt(const Heightfield& hf, int column, int rowFromNorth)
{
  const int j = hf.height - 1 - rowFromNorth;
  return hf.isValid(column, j) ? hf.at(column, j) : std::numeric_limits<double>::quiet_NaN();
}

bool sameHeight(double a, double b)
{
  return (std::isnan(a) && std::isnan(b)) || a == b;
}

nlohmann::json readJson(const fs::path& path)
{
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

using tsynth::test::errorOf;

} // namespace

TEST(TileExport, TheGridSharesEdgesAndCoversTheTerrain)
{
  // 70 samples in tiles of 17 (16 apart): 5 columns reach sample 80; 50 in 4 rows reach 64.
  const tsynth::TileGrid g = tsynth::tileGridFor(70, 50, 17, tsynth::TileFormat::GeoTiff);
  EXPECT_EQ(g.columns, 5);
  EXPECT_EQ(g.rows, 4);
  const tsynth::Tile last = tsynth::tileAt(g, 4, 3, 70, 50);
  EXPECT_EQ(last.firstColumn, 64);
  EXPECT_EQ(last.firstRow, 48);
  EXPECT_EQ(last.validWidth, 6);
  EXPECT_EQ(last.validHeight, 2);
  // Exactly fitting: 65 samples in tiles of 33 are two tiles, not three.
  EXPECT_EQ(tsynth::tileGridFor(65, 65, 33, tsynth::TileFormat::Png16).columns, 2);
  EXPECT_EQ(tsynth::tileGridFor(66, 65, 33, tsynth::TileFormat::Png16).columns, 3);
}

TEST(TileExport, GeoTiffTilesAndTheirMosaicGiveBackTheTerrainBitForBit)
{
  const fs::path dir = freshFolder("geotiff");
  const Heightfield hf = terrain(true);
  const tsynth::TileExportReport report = tsynth::exportTiles(hf, (dir / "t.vrt").string(), 17, {});
  ASSERT_EQ(report.tiles.size(), 20u);

  const Raster mosaic = readWithGdal(dir / "t.vrt");
  ASSERT_EQ(mosaic.width, 70);
  ASSERT_EQ(mosaic.height, 50);
  std::size_t differ = 0;
  for (int r = 0; r < 50; ++r)
  {
    for (int c = 0; c < 70; ++c)
    {
      differ += sameHeight(mosaic.at(c, r), terrainAt(hf, c, r)) ? 0 : 1;
    }
  }
  EXPECT_EQ(differ, 0u) << "samples of the mosaic differ from the terrain";
  EXPECT_DOUBLE_EQ(mosaic.geoTransform[0], 500000.0);
  EXPECT_DOUBLE_EQ(mosaic.geoTransform[3], 4200000.0);

  // Each tile on its own: its samples, its frame and its sidecar's placement.
  const tsynth::TileGrid& g = report.grid;
  for (int r = 0; r < g.rows; ++r)
  {
    for (int c = 0; c < g.columns; ++c)
    {
      const tsynth::Tile t = tsynth::tileAt(g, c, r, 70, 50);
      const fs::path name = dir / ("t_x" + std::to_string(c) + "_y" + std::to_string(r) + ".tif");
      const Raster tile = readWithGdal(name);
      ASSERT_EQ(tile.width, t.validWidth) << name;
      ASSERT_EQ(tile.height, t.validHeight) << name;
      EXPECT_DOUBLE_EQ(tile.geoTransform[0], 500000.0 + 30.0 * t.firstColumn) << name;
      EXPECT_DOUBLE_EQ(tile.geoTransform[3], 4200000.0 - 30.0 * t.firstRow) << name;
      for (int k = 0; k < tile.height; ++k)
      {
        for (int i = 0; i < tile.width; ++i)
        {
          ASSERT_TRUE(sameHeight(tile.at(i, k), terrainAt(hf, t.firstColumn + i, t.firstRow + k)))
            << name << " sample " << i << ", " << k;
        }
      }
      const nlohmann::json side = readJson(fs::path(name).replace_extension(".json"));
      EXPECT_EQ(side["tile"]["first_sample"][0], t.firstColumn);
      EXPECT_EQ(side["tile"]["first_sample"][1], t.firstRow);
      EXPECT_FALSE(side.contains("z_min")) << "a float tile's sidecar must not rescale it";
    }
  }
  // Neighbours share their edge column: tile (1, 0)'s first is tile (0, 0)'s last.
  const Raster a = readWithGdal(dir / "t_x0_y0.tif");
  const Raster b = readWithGdal(dir / "t_x1_y0.tif");
  for (int k = 0; k < a.height; ++k)
  {
    EXPECT_EQ(a.at(a.width - 1, k), b.at(0, k));
  }
}

TEST(TileExport, SixteenBitTilesShareOneScaleAndMeetExactly)
{
  const fs::path dir = freshFolder("png");
  const Heightfield hf = terrain(false);
  const tsynth::TileExportReport report = tsynth::exportTiles(hf, (dir / "e.png").string(), 33, {});
  // 70 x 50 in tiles of 33 (32 apart): 3 x 2 tiles, 99 x 66 samples with padding.
  ASSERT_EQ(report.grid.columns, 3);
  ASSERT_EQ(report.grid.rows, 2);
  // Columns from 0, 32 and 64 take 33, 33 and 6 samples; rows from 0 and 32 take 33 and 18.
  EXPECT_EQ(report.paddedSamples, 6u * 33u * 33u - (33u + 33u + 6u) * (33u + 18u));
  const double lo = report.zMin;
  const double hi = report.zMax;
  const double halfStep = 0.5 * (hi - lo) / 65535.0;
  for (int r = 0; r < 2; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      const std::string stem = "e_x" + std::to_string(c) + "_y" + std::to_string(r);
      const Raster codes = readWithGdal(dir / (stem + ".png"));
      ASSERT_EQ(codes.width, 33);
      const nlohmann::json side = readJson(dir / (stem + ".json"));
      EXPECT_DOUBLE_EQ(side["z_min"].get<double>(), lo);
      EXPECT_DOUBLE_EQ(side["z_max"].get<double>(), hi);
      const tsynth::Tile t = tsynth::tileAt(report.grid, c, r, 70, 50);
      double worst = 0.0;
      for (int k = 0; k < 33; ++k)
      {
        for (int i = 0; i < 33; ++i)
        {
          // Past the terrain's edge a tile repeats its last column and row.
          const int column = std::min(t.firstColumn + i, 69);
          const int row = std::min(t.firstRow + k, 49);
          const double metres = lo + codes.at(i, k) * (hi - lo) / 65535.0;
          worst = std::max(worst, std::abs(metres - terrainAt(hf, column, row)));
        }
      }
      EXPECT_LE(worst, halfStep * 1.001) << stem;
    }
  }
  // The codes of shared edges are the same in both tiles, across columns and rows.
  const Raster nw = readWithGdal(dir / "e_x0_y0.png");
  const Raster ne = readWithGdal(dir / "e_x1_y0.png");
  const Raster sw = readWithGdal(dir / "e_x0_y1.png");
  for (int k = 0; k < 33; ++k)
  {
    EXPECT_EQ(nw.at(32, k), ne.at(0, k));
    EXPECT_EQ(nw.at(k, 32), sw.at(k, 0));
  }
  // The terrain's lowest sample is code 0, its highest 65535.
  EXPECT_DOUBLE_EQ(lo, tsynth::computeHeightRange(hf).min);
}

TEST(TileExport, RawTilesRunSouthFirstAndAreNamedFromTheSouthWest)
{
  const fs::path dir = freshFolder("raw");
  const Heightfield hf = terrain(false);
  const tsynth::TileExportReport report = tsynth::exportTiles(hf, (dir / "u.r16").string(), 33, {});
  ASSERT_EQ(report.grid.rows, 2);
  // Unity's tile u_0_1 is the north-west one (z counts from the south).
  std::ifstream in(dir / "u_0_1.r16", std::ios::binary);
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), {});
  ASSERT_EQ(bytes.size(), 33u * 33u * 2u);
  auto code = [&](int i, int rowFromSouth)
  {
    const std::size_t at = 2u * static_cast<std::size_t>(rowFromSouth * 33 + i);
    return bytes[at] | (bytes[at + 1] << 8);
  };
  const double lo = report.zMin;
  const double scale = (report.zMax - lo) / 65535.0;
  // Its first row in the file is its south row: the terrain's row 32 from the north.
  EXPECT_NEAR(lo + code(5, 0) * scale, terrainAt(hf, 5, 32), scale);
  EXPECT_NEAR(lo + code(5, 32) * scale, terrainAt(hf, 5, 0), scale);
  const nlohmann::json side = readJson(dir / "u_0_1.json");
  EXPECT_EQ(side["row_order"], "south first");
  EXPECT_DOUBLE_EQ(side["unity"]["position_m"][2].get<double>(), 32.0 * 30.0);
}

TEST(TileExport, BadSizesAndNodataAreRefusedBeforeAnyFile)
{
  const fs::path dir = freshFolder("refused");
  EXPECT_NE(errorOf([&] { tsynth::exportTiles(terrain(false), (dir / "e.png").string(), 100, {}); })
              .find("not 100: try 65 or 129"),
    std::string::npos);
  EXPECT_NE(errorOf([&] { tsynth::exportTiles(terrain(true), (dir / "e.png").string(), 33, {}); })
              .find("42 cells without data"),
    std::string::npos);
  EXPECT_NE(errorOf([&] { tsynth::exportTiles(terrain(false), (dir / "e.tif").string(), 33, {}); })
              .find("not " + (dir / "e.tif").string()),
    std::string::npos);
  EXPECT_TRUE(fs::is_empty(dir));
}

TEST(TileExport, AFailedTileLeavesNoTileOfThatExportBehind)
{
  const fs::path dir = freshFolder("failed");
  // A folder where the last tile's sidecar should go: that write fails.
  fs::create_directory(dir / "t_x4_y3.json");
  {
    tsynth::Publication outputs;
    EXPECT_NE(
      errorOf([&] { tsynth::exportTiles(terrain(false), (dir / "t.vrt").string(), 17, {}); }), "");
  }
  std::vector<std::string> left;
  for (const auto& entry : fs::directory_iterator(dir))
  {
    left.push_back(entry.path().filename().string());
  }
  EXPECT_EQ(left, std::vector<std::string>{ "t_x4_y3.json" });
}

namespace
{

// Rows [first, last] (from the north) of `hf`, as one process of several holds them.
Heightfield rowsOf(const Heightfield& hf, int first, int last)
{
  Heightfield band(hf.width, last - first + 1);
  band.cellX = hf.cellX;
  band.cellY = hf.cellY;
  for (int row = first; row <= last; ++row)
  {
    for (int i = 0; i < hf.width; ++i)
    {
      const int from = hf.height - 1 - row;
      band.at(i, last - row) = hf.at(i, from);
    }
  }
  normaliseMask(band);
  return band;
}

std::string bytesOf(const fs::path& path)
{
  std::ifstream in(path, std::ios::binary);
  return { std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>() };
}

} // namespace

TEST(TileExport, ProcessesWritingTheirBandsOfTileRowsWriteTheFilesOfOneExport)
{
  for (const char* name : { "parts.vrt", "parts.png" })
  {
    const bool sixteen = std::string(name).find(".png") != std::string::npos;
    const Heightfield hf = terrain(!sixteen);
    const fs::path whole = freshFolder(std::string("whole-") + name);
    const fs::path parts = freshFolder(std::string("parts-") + name);
    constexpr int kTile = 33;
    const tsynth::TileExportReport one = tsynth::exportTiles(hf, (whole / name).string(), kTile);
    const tsynth::TileFormat format = *tsynth::tileFormatFor(name);
    const tsynth::TileGrid grid = tsynth::tileGridFor(hf.width, hf.height, kTile, format);
    ASSERT_EQ(grid.rows, 2); // 50 rows in tiles of 33: three processes leave one with none
    const tsynth::TerrainFrame frame = tsynth::terrainFrameOf(hf, format, name);
    std::size_t written = 0;
    for (int rank = 0; rank < 3; ++rank)
    {
      const auto [first, last] = tsynth::tileRowsOf(grid, rank, 3);
      if (first == last)
      {
        continue;
      }
      const auto [top, bottom] = tsynth::terrainRowsOf(grid, hf.height, first, last);
      const Heightfield band = rowsOf(hf, top, bottom);
      written += tsynth::exportTileRows(
        { frame, band, top }, (parts / name).string(), grid, format, first, last)
                   .tiles.size();
      if (rank == 0 && top == 0 && bottom + 1 < hf.height)
      {
        // A band one row short of what its tiles need is refused.
        const Heightfield shorter = rowsOf(hf, top, bottom - 1);
        EXPECT_NE(
          errorOf(
            [&]
            {
              tsynth::exportTileRows(
                { frame, shorter, top }, (parts / "short.vrt").string(), grid, format, first, last);
            })
            .find("does not hold"),
          std::string::npos);
      }
    }
    if (!sixteen)
    {
      tsynth::writeTileMosaic(frame, grid, (parts / name).string());
    }
    EXPECT_EQ(written, one.tiles.size());
    std::size_t files = 0;
    for (const auto& entry : fs::directory_iterator(whole))
    {
      const fs::path twin = parts / entry.path().filename();
      ASSERT_TRUE(fs::exists(twin)) << twin;
      EXPECT_EQ(bytesOf(entry.path()), bytesOf(twin)) << entry.path().filename();
      ++files;
    }
    EXPECT_EQ(files, 2 * one.tiles.size() + (sixteen ? 0 : 1)) << name;
  }
}
