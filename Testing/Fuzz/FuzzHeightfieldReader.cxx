// Fuzz target: the raster readers (readRasterInfo, readHeightfield,
// readColourImage) on any bytes, through GDAL. The first byte picks the file
// name (and so the extension GDAL and the readers see); with its top bit set
// the second byte gives the length of a NAME.json sidecar cut off the end.
#include "Core/Error.h"
#include "Core/HeightfieldIO.h"
#include "FuzzSupport.h"

#include <cpl_conv.h>
#include <cpl_error.h>

#include <array>
#include <string>

namespace
{

// GeoTIFF, PNG, ESRI ASCII grid, SRTM .hgt (GDAL wants the tile name), ASCII
// XYZ, USGS DEM, JPEG, GIF, BMP, Erdas .img, ENVI-like .bil, .vrt.
const std::array<const char*, 12> kNames = { "input.tif",
  "input.png",
  "input.asc",
  "N45E006.hgt",
  "input.xyz",
  "input.dem",
  "input.jpg",
  "input.gif",
  "input.bmp",
  "input.img",
  "input.bil",
  "input.vrt" };
constexpr std::uint8_t kSidecarFlag = 0x80;

// GDAL quiet, and without its netCDF driver: libnetcdf callocs names and
// attributes of the length a header declares (up to 4 GB) before it finds the
// file too short. The pages are never touched, but under ASan their shadow is,
// and a few such files in a row pass any RSS limit. That is libnetcdf's way,
// not the project's, and would hide every other finding.
void setUpGdal()
{
  static const bool once = []
  {
    CPLSetErrorHandler(CPLQuietErrorHandler);
    CPLSetConfigOption("GDAL_SKIP", "netCDF");
    return true;
  }();
  (void)once;
}

template<typename F>
void expectOnlyTsynthErrors(F&& read)
{
  try
  {
    read();
  }
  catch (const tsynth::Error&)
  {
    // Bad input, told as it should be.
  }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  setUpGdal();
  tsynth::fuzz::Bytes in(data, size);
  const std::uint8_t selector = in.byte();
  const std::string name = kNames[(selector & ~kSidecarFlag) % kNames.size()];
  const std::string stem = name.substr(0, name.rfind('.'));
  std::size_t sidecarBytes = 0;
  if ((selector & kSidecarFlag) != 0)
  {
    sidecarBytes = std::min<std::size_t>(in.byte(), in.left());
  }
  const std::size_t rasterBytes = in.left() - sidecarBytes;
  const std::string path = tsynth::fuzz::writeScratch(name, in.rest(), rasterBytes);
  if (sidecarBytes > 0)
  {
    tsynth::fuzz::writeScratch(stem + ".json", in.rest() + rasterBytes, sidecarBytes);
  }

  expectOnlyTsynthErrors([&] { tsynth::readRasterInfo(path); });
  expectOnlyTsynthErrors([&] { tsynth::readHeightfield(path); });
  expectOnlyTsynthErrors([&] { tsynth::readColourImage(path); });

  tsynth::fuzz::removeScratch(name);
  tsynth::fuzz::removeScratch(stem + ".json");
  return 0;
}
