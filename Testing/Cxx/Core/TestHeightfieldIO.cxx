// Tests of Kernels/Core/HeightfieldIO.cxx.
#include "Core/Cancellation.h"
#include "Core/Error.h"
#include "Core/Geodesy.h"
#include "Core/HeightfieldIO.h"
#include "ErrorOf.h"
#include "TestData.h"

#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <optional>

namespace fs = std::filesystem;
using tsynth::Heightfield;
using tsynth::readHeightfield;

namespace
{

std::string scratch(const std::string& name)
{
  return (tsynth::test::scratchDir() / name).string();
}

using tsynth::test::errorOf;

// Writes a raster through GDAL directly, independent of the code under test.
void writeWithGdal(const std::string& path,
  const char* driver,
  int w,
  int h,
  GDALDataType type,
  const std::vector<double>& values,
  int bands = 1,
  const double* gt = nullptr,
  const char* epsg = nullptr,
  std::optional<double> nodata = std::nullopt)
{
  GDALAllRegister();
  GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
  GDALDataset* ds = mem->Create("", w, h, bands, type, nullptr);
  for (int b = 1; b <= bands; ++b)
  {
    std::vector<double> copy = values;
    ASSERT_EQ(ds->GetRasterBand(b)->RasterIO(
                GF_Write, 0, 0, w, h, copy.data(), w, h, GDT_Float64, 0, 0, nullptr),
      CE_None);
    if (nodata)
    {
      ds->GetRasterBand(b)->SetNoDataValue(*nodata);
    }
  }
  if (gt != nullptr)
  {
    ds->SetGeoTransform(const_cast<double*>(gt));
  }
  if (epsg != nullptr)
  {
    OGRSpatialReference srs;
    srs.SetFromUserInput(epsg);
    ds->SetSpatialRef(&srs);
  }
  GDALDataset* out = GetGDALDriverManager()->GetDriverByName(driver)->CreateCopy(
    path.c_str(), ds, FALSE, nullptr, nullptr, nullptr);
  ASSERT_NE(out, nullptr);
  GDALClose(out);
  GDALClose(ds);
}

std::vector<std::string> sharedDems()
{
  std::vector<std::string> out;
  for (const auto& entry : fs::directory_iterator(tsynth::test::sharedData() / "dems"))
  {
    const std::string ext = entry.path().extension().string();
    if (ext == ".png" || ext == ".tif")
    {
      out.push_back(entry.path().string());
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

void expectSameGrid(const Heightfield& a, const Heightfield& b, float tolerance)
{
  ASSERT_EQ(a.width, b.width);
  ASSERT_EQ(a.height, b.height);
  EXPECT_NEAR(a.cellX, b.cellX, 1e-9 * a.cellX);
  EXPECT_NEAR(a.cellY, b.cellY, 1e-9 * a.cellY);
  double worst = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k)
  {
    ASSERT_EQ(a.isValid(k), b.isValid(k)) << "cell " << k;
    if (a.isValid(k))
    {
      worst = std::max(worst, std::abs(static_cast<double>(a.z[k]) - b.z[k]));
    }
  }
  EXPECT_LE(worst, tolerance);
}

} // namespace

TEST(HeightfieldIO, AlaskaInFeetPeaksNear6180Metres)
{
  TSYNTH_SKIP_WITHOUT(tsynth::test::realDem("alaska.png"));
  tsynth::RasterInfo info;
  const Heightfield hf = readHeightfield(tsynth::test::realDem("alaska.png"), {}, &info);
  EXPECT_EQ(hf.width, 648);
  EXPECT_EQ(hf.height, 648);
  EXPECT_EQ(info.zUnit, tsynth::ZUnit::Feet);
  EXPECT_DOUBLE_EQ(hf.cellX, 90.0);
  EXPECT_DOUBLE_EQ(hf.cellY, 90.0);
  const auto range = tsynth::computeHeightRange(hf);
  EXPECT_NEAR(range.max, 6180.0, 10.0);
  // The stored maximum is an integer number of feet.
  const double feet = range.max / tsynth::kMetresPerFoot;
  EXPECT_NEAR(feet, std::round(feet), 1e-2);
}

TEST(HeightfieldIO, OptionsOverrideTheSidecarUnit)
{
  TSYNTH_SKIP_WITHOUT(tsynth::test::realDem("alaska.png"));
  tsynth::ReadOptions metres;
  metres.zUnit = tsynth::ZUnit::Metres;
  const auto hf = readHeightfield(tsynth::test::realDem("alaska.png"), metres);
  EXPECT_NEAR(tsynth::computeHeightRange(hf).max, 6180.0 / 0.3048, 40.0);
  tsynth::ReadOptions cell;
  cell.cellX = 30.0;
  EXPECT_DOUBLE_EQ(readHeightfield(tsynth::test::realDem("alaska.png"), cell).cellY, 30.0);
}

TEST(HeightfieldIO, MontBlancNormalisedRangeSpans454To4810)
{
  tsynth::RasterInfo info;
  const Heightfield hf = readHeightfield(tsynth::test::realDem("alps-montblanc.png"), {}, &info);
  EXPECT_TRUE(info.normalised);
  EXPECT_EQ(hf.width, 647);
  EXPECT_DOUBLE_EQ(hf.cellX, 92.74);
  const auto range = tsynth::computeHeightRange(hf);
  EXPECT_NEAR(range.min, 454.0, 0.01);
  EXPECT_NEAR(range.max, 4810.0, 0.01);
}

TEST(HeightfieldIO, MountJacksonGeographicCellSizeDiffersInXAndY)
{
  TSYNTH_SKIP_WITHOUT(tsynth::test::realDem("mount_jackson_n39_w107_3arc.tif"));
  tsynth::RasterInfo info;
  const std::string path = tsynth::test::realDem("mount_jackson_n39_w107_3arc.tif");
  const Heightfield hf = readHeightfield(path, {}, &info);
  EXPECT_EQ(hf.width, 1201);
  EXPECT_EQ(hf.height, 1201);
  EXPECT_TRUE(info.georef.isGeographic);
  EXPECT_NEAR(hf.cellX, 71.5, 0.5);
  EXPECT_NEAR(hf.cellY, 92.5, 0.3);
  EXPECT_FALSE(hf.georef.crsWkt.empty());
  const auto range = tsynth::computeHeightRange(hf);
  EXPECT_FLOAT_EQ(range.min, 1897.0f);
  EXPECT_FLOAT_EQ(range.max, 4385.0f);

  // Row 0 of the file is the north edge: it must land in the top row (j = height - 1).
  GDALAllRegister();
  GDALDataset* ds = GDALDataset::FromHandle(GDALOpen(path.c_str(), GA_ReadOnly));
  ASSERT_NE(ds, nullptr);
  float northWest = 0.0f;
  float southEast = 0.0f;
  ASSERT_EQ(ds->GetRasterBand(1)->RasterIO(
              GF_Read, 0, 0, 1, 1, &northWest, 1, 1, GDT_Float32, 0, 0, nullptr),
    CE_None);
  ASSERT_EQ(ds->GetRasterBand(1)->RasterIO(
              GF_Read, 1200, 1200, 1, 1, &southEast, 1, 1, GDT_Float32, 0, 0, nullptr),
    CE_None);
  GDALClose(ds);
  EXPECT_EQ(hf.at(0, 1200), northWest);
  EXPECT_EQ(hf.at(1200, 0), southEast);
}

TEST(HeightfieldIO, EverySharedDemRoundTripsThroughGeoTiffAndPng)
{
  TSYNTH_SKIP_WITHOUT(tsynth::test::sharedData() / "dems");
  const auto dems = sharedDems();
  ASSERT_GE(dems.size(), 9u) << "expected the DEMs of ../shared/data/dems";
  for (const std::string& path : dems)
  {
    SCOPED_TRACE(path);
    const Heightfield original = readHeightfield(path);

    const std::string stem = fs::path(path).stem().string();
    const std::string tif = scratch("roundtrip_" + stem + ".tif");
    tsynth::writeHeightfield(tif, original);
    tsynth::RasterInfo tifInfo;
    const Heightfield fromTif = readHeightfield(tif, {}, &tifInfo);
    expectSameGrid(original, fromTif, 0.0f);
    EXPECT_EQ(fromTif.georef.hasGeoTransform, true);
    EXPECT_EQ(tifInfo.georef.isGeographic, original.georef.isGeographic);
    EXPECT_EQ(fromTif.georef.crsWkt.empty(), original.georef.crsWkt.empty());

    const std::string png = scratch("roundtrip_" + stem + "_16bit.png");
    tsynth::writeHeightfield(png, original);
    ASSERT_TRUE(fs::exists(scratch("roundtrip_" + stem + "_16bit.json")));
    const Heightfield fromPng = readHeightfield(png);
    const auto range = tsynth::computeHeightRange(original);
    const float halfStep = 0.5f * (range.max - range.min) / 65535.0f;
    expectSameGrid(original, fromPng, halfStep * 1.01f + 1e-3f);
  }
}

TEST(HeightfieldIO, NodataIsMaskedAndNeverAveraged)
{
  // Int16 GeoTIFF in UTM with SRTM's nodata value in two cells.
  const int w = 4;
  const int h = 3;
  std::vector<double> v = { 10, 20, 30, 40, 50, -32768, 70, 80, 90, 100, -32768, 120 };
  const double gt[6] = { 500000.0, 30.0, 0.0, 4000000.0, 0.0, -30.0 };
  const std::string path = scratch("nodata.tif");
  writeWithGdal(path, "GTiff", w, h, GDT_Int16, v, 1, gt, "EPSG:32613", -32768.0);

  tsynth::RasterInfo info;
  const Heightfield hf = readHeightfield(path, {}, &info);
  EXPECT_DOUBLE_EQ(hf.cellX, 30.0);
  EXPECT_DOUBLE_EQ(hf.cellY, 30.0);
  EXPECT_EQ(info.cellSizeSource, "projected CRS");
  ASSERT_TRUE(hf.hasMask());
  EXPECT_EQ(hf.validCount(), 10u);
  // File row 1, column 1 is grid (1, h - 2).
  EXPECT_FALSE(hf.isValid(1, 1));
  EXPECT_TRUE(std::isnan(hf.at(1, 1)));
  const auto range = tsynth::computeHeightRange(hf);
  EXPECT_FLOAT_EQ(range.min, 10.0f);
  EXPECT_FLOAT_EQ(range.max, 120.0f);
  EXPECT_DOUBLE_EQ(range.mean, (10 + 20 + 30 + 40 + 50 + 70 + 80 + 90 + 100 + 120) / 10.0);

  // The mask survives GeoTIFF (NaN nodata) and PNG (code 0 reserved) round trips.
  tsynth::writeHeightfield(scratch("nodata_out.tif"), hf);
  expectSameGrid(hf, readHeightfield(scratch("nodata_out.tif")), 0.0f);
  tsynth::writeHeightfield(scratch("nodata_out.png"), hf);
  expectSameGrid(hf, readHeightfield(scratch("nodata_out.png")), 110.0f / 65534.0f);
}

TEST(HeightfieldIO, EsriAsciiGridAndEightBitPng)
{
  const std::string asc = scratch("grid.asc");
  std::ofstream(asc) << "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 25\n"
                        "NODATA_value -9999\n1 2 3\n4 -9999 6\n";
  const Heightfield a = readHeightfield(asc);
  EXPECT_EQ(a.width, 3);
  EXPECT_EQ(a.height, 2);
  EXPECT_DOUBLE_EQ(a.cellX, 25.0);
  EXPECT_FLOAT_EQ(a.at(0, 1), 1.0f); // top row of the file is the north row
  EXPECT_FLOAT_EQ(a.at(2, 0), 6.0f);
  EXPECT_FALSE(a.isValid(1, 0));

  // 8-bit grey PNG with a normalised range from options: 255 maps to z_max.
  const std::string png = scratch("grey8.png");
  writeWithGdal(png, "PNG", 2, 1, GDT_Byte, { 0, 255 });
  tsynth::ReadOptions o;
  o.zMin = 100.0;
  o.zMax = 300.0;
  const Heightfield g = readHeightfield(png, o);
  EXPECT_FLOAT_EQ(g.at(0, 0), 100.0f);
  EXPECT_FLOAT_EQ(g.at(1, 0), 300.0f);
  EXPECT_FALSE(g.cellSizeKnown);
}

TEST(HeightfieldIO, SrtmHgtIsGeographic)
{
  // An SRTM-3 tile is 1201 x 1201 big-endian Int16 named after its south-west corner.
  const std::string path = scratch("N45E006.hgt");
  {
    std::ofstream out(path, std::ios::binary);
    for (int r = 0; r < 1201; ++r)
    {
      for (int c = 0; c < 1201; ++c)
      {
        const std::int16_t v = static_cast<std::int16_t>(r == 0 && c == 0 ? -32768 : 1000 + c);
        const char bytes[2] = { static_cast<char>((v >> 8) & 0xff), static_cast<char>(v & 0xff) };
        out.write(bytes, 2);
      }
    }
  }
  tsynth::RasterInfo info;
  const Heightfield hf = readHeightfield(path, {}, &info);
  EXPECT_EQ(info.driver, "SRTMHGT");
  EXPECT_TRUE(info.georef.isGeographic);
  const auto m = tsynth::metresPerDegree(45.5);
  EXPECT_NEAR(hf.cellX, m.east / 1200.0, 1e-6);
  EXPECT_NEAR(hf.cellY, m.north / 1200.0, 1e-6);
  EXPECT_FALSE(hf.isValid(0, 1200));
  EXPECT_FLOAT_EQ(hf.at(7, 3), 1007.0f);
}

TEST(HeightfieldIO, BadInputGetsOneClearSentence)
{
  EXPECT_NE(errorOf([] { readHeightfield(scratch("does-not-exist.tif")); }).find("No such file"),
    std::string::npos);
  EXPECT_NE(
    errorOf([] { readHeightfield(tsynth::test::scratchDir().string()); }).find("is a directory"),
    std::string::npos);

  const std::string text = scratch("notes.tif");
  std::ofstream(text) << "this is not a raster\n";
  EXPECT_NE(errorOf([&] { readHeightfield(text); }).find("is not a raster"), std::string::npos);

  const std::string empty = scratch("empty.png");
  std::ofstream(empty).flush();
  EXPECT_NE(errorOf([&] { readHeightfield(empty); }).find("empty"), std::string::npos);

  // A truncated GeoTIFF: the header survives, the data does not.
  const std::string whole = scratch("whole.tif");
  writeWithGdal(whole, "GTiff", 64, 64, GDT_Float32, std::vector<double>(64 * 64, 5.0));
  const std::string cut = scratch("truncated.tif");
  {
    std::ifstream in(whole, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 3);
  }
  EXPECT_FALSE(errorOf([&] { readHeightfield(cut); }).empty());

  const std::string rgb = scratch("colour.png");
  writeWithGdal(rgb, "PNG", 2, 2, GDT_Byte, { 1, 2, 3, 4 }, 3);
  EXPECT_NE(errorOf([&] { readHeightfield(rgb); }).find("3 bands"), std::string::npos);

  const std::string allNodata = scratch("allnodata.asc");
  std::ofstream(allNodata) << "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n"
                              "NODATA_value -9999\n-9999 -9999\n-9999 -9999\n";
  EXPECT_NE(
    errorOf([&] { readHeightfield(allNodata); }).find("no valid heights"), std::string::npos);

  // Found by fuzzing: a 71-byte header claiming 10^10 cells made the reader
  // allocate 40 GB, and 40 bytes claiming 10^9 kept GDAL scanning for minutes;
  // a text grid must spend two bytes a cell, checked before any allocation.
  // The header itself is still described.
  const std::string huge = scratch("huge.asc");
  std::ofstream(huge) << "ncols 100000\nnrows 100000\nxllcorner 0\nyllcorner 0\ncellsize 30\n"
                         "1 2 3 4\n";
  EXPECT_NE(errorOf([&] { readHeightfield(huge); })
              .find("claims 100000 x 100000 cells, more than its 70 bytes of text can hold"),
    std::string::npos);
  EXPECT_NE(errorOf([&] { tsynth::readColourImage(huge); }).find("bytes of text can hold"),
    std::string::npos);
  EXPECT_EQ(tsynth::readRasterInfo(huge).width, 100000);

  // A broken sidecar is reported, naming the sidecar.
  const std::string dem = scratch("sidecar_broken.png");
  writeWithGdal(dem, "PNG", 2, 2, GDT_UInt16, { 1, 2, 3, 4 });
  std::ofstream(scratch("sidecar_broken.json")) << "{ \"z_unit\": ";
  const std::string msg = errorOf([&] { readHeightfield(dem); });
  EXPECT_NE(msg.find("sidecar_broken.json"), std::string::npos) << msg;
  EXPECT_NE(msg.find("not valid JSON"), std::string::npos) << msg;
  tsynth::ReadOptions noSidecar;
  noSidecar.useSidecar = false;
  EXPECT_NO_THROW(readHeightfield(dem, noSidecar));

  // A Float32 image cannot take a normalised range.
  tsynth::ReadOptions range;
  range.zMin = 0.0;
  range.zMax = 1.0;
  EXPECT_NE(
    errorOf([&] { readHeightfield(whole, range); }).find("8- or 16-bit"), std::string::npos);
}

TEST(HeightfieldIO, FailedWritesLeaveNoFile)
{
  Heightfield hf(3, 3, 1.0f);
  const std::string unknown = scratch("out.xyz");
  EXPECT_NE(errorOf([&] { tsynth::writeHeightfield(unknown, hf); }).find("unknown extension"),
    std::string::npos);
  EXPECT_FALSE(fs::exists(unknown));
  const std::string noFolder = scratch("missing-folder/out.tif");
  EXPECT_NE(errorOf([&] { tsynth::writeHeightfield(noFolder, hf); }).find("does not exist"),
    std::string::npos);
  Heightfield empty;
  EXPECT_FALSE(errorOf([&] { tsynth::writeHeightfield(scratch("empty.tif"), empty); }).empty());
  EXPECT_FALSE(fs::exists(scratch("empty.tif")));
  // No temporary files remain in the folder after all of the above.
  for (const auto& entry : fs::directory_iterator(tsynth::test::scratchDir()))
  {
    EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos) << entry.path();
  }
}

// A stop requested while a large file is written ends the write at the next row of tiles (a
// GeoTIFF) or row (a PNG), throws Cancelled and leaves neither the file nor a temporary.
TEST(HeightfieldIO, AStopDuringAWriteLeavesNoFile)
{
  constexpr int kSide = 1024; // four rows of the GeoTIFF's 256-cell tiles
  Heightfield hf(kSide, kSide, 0.0f);
  for (std::size_t k = 0; k < hf.z.size(); ++k)
  {
    hf.z[k] = static_cast<float>(k % 977);
  }
  for (const std::string name : { "stopped.tif", "stopped.png" })
  {
    int asked = 0;
    const std::string path = scratch(name);
    {
      const tsynth::CancellationScope stopOnSecondAsk([&] { return ++asked >= 2; });
      EXPECT_THROW(tsynth::writeHeightfield(path, hf), tsynth::Cancelled) << name;
    }
    // The second ask says stop; the writer may ask once more, to tell a stop from a failure.
    EXPECT_LE(asked, 3) << name << ": the write went on after the stop";
    EXPECT_FALSE(fs::exists(path)) << name;
  }
  int asked = 0;
  {
    const tsynth::CancellationScope neverStop([&] { return ++asked < 0; });
    tsynth::writeHeightfield(scratch("completed.tif"), hf);
  }
  EXPECT_EQ(asked, kSide / 256) << "one check per row of tiles";
  expectSameGrid(tsynth::readHeightfield(scratch("completed.tif")), hf, 0.0f);
  for (const auto& entry : fs::directory_iterator(tsynth::test::scratchDir()))
  {
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
  }
}

TEST(HeightfieldIO, StaleSidecarBesideAGeoTiffIsReported)
{
  Heightfield hf(4, 4, 7.0f);
  hf.cellX = 30.0;
  hf.cellY = 30.0;
  tsynth::writeHeightfield(scratch("stale.tif"), hf);
  std::ofstream(scratch("stale.json"))
    << R"({"z_unit": "ft", "cell_size_m": 90, "z_min": 0, "z_max": 9})";
  tsynth::RasterInfo info;
  const Heightfield back = readHeightfield(scratch("stale.tif"), {}, &info);
  // The sidecar still wins (it may be deliberate), but every disagreement is said.
  EXPECT_DOUBLE_EQ(back.cellX, 90.0);
  ASSERT_EQ(info.warnings.size(), 3u);
  EXPECT_NE(info.warnings[0].find("cell size"), std::string::npos);
  EXPECT_NE(info.warnings[1].find("heights are in ft"), std::string::npos);
  EXPECT_NE(info.warnings[2].find("range is ignored"), std::string::npos);
  EXPECT_FALSE(info.normalised);
}

TEST(HeightfieldIO, LocalFrameGeoTiffKeepsAnisotropicCells)
{
  Heightfield hf(5, 4);
  hf.cellX = 12.5;
  hf.cellY = 40.0;
  for (int j = 0; j < hf.height; ++j)
  {
    for (int i = 0; i < hf.width; ++i)
    {
      hf.at(i, j) = static_cast<float>(100 * j + i);
    }
  }
  tsynth::writeHeightfield(scratch("local.tif"), hf);
  const Heightfield back = readHeightfield(scratch("local.tif"));
  expectSameGrid(hf, back, 0.0f);
  EXPECT_TRUE(back.cellSizeKnown);
  EXPECT_FLOAT_EQ(back.at(4, 3), 304.0f);
}
