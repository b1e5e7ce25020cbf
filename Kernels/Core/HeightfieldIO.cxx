#include "HeightfieldIO.h"

#include "Cancellation.h"
#include "Error.h"
#include "Geodesy.h"
#include "Grid.h"
#include "Memory.h"
#include "OutputFile.h"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <memory>
#include <mutex>
#include <system_error>
#include <unistd.h>

namespace fs = std::filesystem;

namespace tsynth
{
namespace
{

void initialiseGdal()
{
  static std::once_flag once;
  std::call_once(once,
    []
    {
      // No .aux.xml files beside the user's rasters.
      CPLSetConfigOption("GDAL_PAM_ENABLED", "NO");
      GDALAllRegister();
    });
}

// Silences GDAL's own printing while in scope; errors reach the user through
// tsynth::Error with GDAL's last message appended. It also keeps the errno of GDAL's first
// failure in scope: a write that hit a full disk says ENOSPC there, while the message GDAL
// posts last may be about reading back what it could not write.
class QuietGdal
{
public:
  QuietGdal()
  {
    firstFailureErrno() = 0;
    CPLPushErrorHandler(record);
    CPLErrorReset();
  }
  ~QuietGdal() { CPLPopErrorHandler(); }
  QuietGdal(const QuietGdal&) = delete;
  QuietGdal& operator=(const QuietGdal&) = delete;
  static std::string lastMessage()
  {
    const char* msg = CPLGetLastErrorMsg();
    return (msg != nullptr && *msg != '\0') ? std::string(" (GDAL: ") + msg + ")" : std::string();
  }
  // errno when GDAL first reported a failure in this scope (0 if none, or none was set).
  static int& firstFailureErrno()
  {
    thread_local int error = 0;
    return error;
  }

  // GDAL's warnings while a GdalWarnings scope is open on this thread (nullptr if none).
  static std::vector<std::string>*& warningSink()
  {
    thread_local std::vector<std::string>* sink = nullptr;
    return sink;
  }

  static void CPL_STDCALL record(CPLErr level, CPLErrorNum, const char* message)
  {
    if (level >= CE_Failure && firstFailureErrno() == 0)
    {
      firstFailureErrno() = errno;
    }
    if (level == CE_Warning && warningSink() != nullptr && message != nullptr)
    {
      warningSink()->emplace_back(message);
    }
  }
};

// Collects GDAL's warnings while in scope (GDAL prints nothing), so that a reader can pass
// them on as one warning line of its own.
class GdalWarnings
{
public:
  GdalWarnings()
    : outer_(QuietGdal::warningSink())
  {
    QuietGdal::warningSink() = &messages_;
  }
  ~GdalWarnings() { QuietGdal::warningSink() = outer_; }
  GdalWarnings(const GdalWarnings&) = delete;
  GdalWarnings& operator=(const GdalWarnings&) = delete;
  const std::vector<std::string>& messages() const { return messages_; }

private:
  QuietGdal quiet_;
  std::vector<std::string>* outer_;
  std::vector<std::string> messages_;
};

struct DatasetCloser
{
  void operator()(GDALDataset* ds) const { GDALClose(GDALDataset::ToHandle(ds)); }
};
using DatasetPtr = std::unique_ptr<GDALDataset, DatasetCloser>;

// What reading a DEM holds per cell at its peak: the float32 values and mask
// byte GDAL fills, and the heightfield's float and validity byte.
constexpr double kBytesPerReadCell = 2.0 * (sizeof(float) + sizeof(std::uint8_t));

void checkReadable(const std::string& path)
{
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (ec || !fs::exists(st))
  {
    throw Error("No such file: " + path + ".");
  }
  if (fs::is_directory(st))
  {
    throw Error(path + " is a directory, not a raster file.");
  }
  if (!fs::is_regular_file(st))
  {
    // GDAL would wait forever on a pipe and read a device without end.
    throw Error(path + " is not a regular file (a pipe or a device?); give a raster file.");
  }
  if (::access(path.c_str(), R_OK) != 0)
  {
    throw Error("Cannot read " + path + ": permission denied.");
  }
  if (fs::file_size(path, ec) == 0)
  {
    throw Error(path + " is empty (zero bytes), not a raster.");
  }
}

DatasetPtr openRaster(const std::string& path)
{
  initialiseGdal();
  checkReadable(path);
  QuietGdal quiet;
  DatasetPtr ds(GDALDataset::FromHandle(
    GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
  if (!ds)
  {
    throw Error(path + " is not a raster that GDAL can read" + QuietGdal::lastMessage() + ".");
  }
  if (ds->GetRasterXSize() <= 0 || ds->GetRasterYSize() <= 0 || ds->GetRasterCount() <= 0)
  {
    throw Error(path + " holds a raster of zero size.");
  }
  return ds;
}

// The band with the heights; a second band is accepted only as an alpha mask.
GDALRasterBand* heightBand(GDALDataset& ds, const std::string& path)
{
  const int n = ds.GetRasterCount();
  if (n == 2 && ds.GetRasterBand(2)->GetColorInterpretation() == GCI_AlphaBand)
  {
    return ds.GetRasterBand(1);
  }
  if (n != 1)
  {
    throw Error(path + " has " + std::to_string(n) +
      " bands; a heightfield needs a single band (is it a colour image?).");
  }
  GDALRasterBand* band = ds.GetRasterBand(1);
  if (band->GetColorTable() != nullptr)
  {
    throw Error(path + " is a palette (colour-indexed) image, not a heightfield.");
  }
  if (GDALDataTypeIsComplex(band->GetRasterDataType()) != 0)
  {
    throw Error(path + " stores complex values (" + GDALGetDataTypeName(band->GetRasterDataType()) +
      "); a heightfield stores real heights, and the imaginary part would be lost.");
  }
  return band;
}

// GDAL 3.6 reads signed 8-bit rasters as Byte, marked PIXELTYPE=SIGNEDBYTE.
bool isSignedByte(GDALRasterBand& band)
{
  const char* type = band.GetMetadataItem("PIXELTYPE", "IMAGE_STRUCTURE");
  return band.GetRasterDataType() == GDT_Byte && type != nullptr &&
    std::string(type) == "SIGNEDBYTE";
}

double integerTypeMax(GDALDataType t)
{
  switch (t)
  {
    case GDT_Byte:
      return 255.0;
    case GDT_UInt16:
      return 65535.0;
    default:
      return 0.0;
  }
}

} // namespace

std::optional<MetresPerDegree> geographicDegree(const std::string& crs, double centreLatitude)
{
  if (crs.empty() || !(std::abs(centreLatitude) <= 90.0))
  {
    return std::nullopt;
  }
  OGRSpatialReference srs;
  CPLPushErrorHandler(CPLQuietErrorHandler); // a definition GDAL cannot read is simply not one
  const OGRErr read = srs.SetFromUserInput(crs.c_str());
  CPLPopErrorHandler();
  if (read != OGRERR_NONE || !srs.IsGeographic())
  {
    return std::nullopt;
  }
  return metresPerDegree(centreLatitude, srs.GetSemiMajor(), srs.GetInvFlattening());
}

namespace
{

void fillCellSizeFromGeoreference(RasterInfo& info, const OGRSpatialReference* srs, int rows)
{
  const auto& gt = info.georef.geoTransform;
  const double px = std::hypot(gt[1], gt[4]);
  const double py = std::hypot(gt[2], gt[5]);
  if (srs != nullptr && srs->IsGeographic())
  {
    const double centreLatitude = gt[3] + gt[5] * rows * 0.5;
    const double a = srs->GetSemiMajor();
    const double invF = srs->GetInvFlattening();
    const MetresPerDegree mpd = metresPerDegree(centreLatitude, a, invF);
    info.cellX = px * mpd.east;
    info.cellY = py * mpd.north;
    info.georef.isGeographic = true;
    char text[64];
    std::snprintf(text, sizeof text, "geographic CRS at latitude %.2f deg", centreLatitude);
    info.cellSizeSource = text;
  }
  else if (srs != nullptr && srs->IsProjected())
  {
    const double unit = srs->GetLinearUnits();
    info.cellX = px * unit;
    info.cellY = py * unit;
    info.cellSizeSource = "projected CRS";
  }
  else
  {
    info.cellX = px;
    info.cellY = py;
    info.cellSizeSource = "geotransform (no CRS, taken as metres)";
  }
  info.cellSizeKnown = true;
}

// A text raster (ESRI or GRASS ASCII grid, XYZ) spends at least a digit and
// a separator on every cell: a header claiming more cells than that is
// damaged. GDAL would scan such a file for minutes (40 bytes claiming 10^9
// cells kept `tsynth info` busy past 20 s) before it failed.
void checkTextRasterSize(const std::string& driver, const std::string& path, int width, int height)
{
  constexpr double kLeastBytesPerTextCell = 2.0;
  if (driver != "AAIGrid" && driver != "GRASSASCIIGrid" && driver != "XYZ")
  {
    return;
  }
  std::error_code ec;
  const double bytes = static_cast<double>(fs::file_size(path, ec));
  const double cells = static_cast<double>(width) * static_cast<double>(height);
  if (!ec && cells * kLeastBytesPerTextCell > bytes)
  {
    throw Error(path + " claims " + std::to_string(width) + " x " + std::to_string(height) +
      " cells, more than its " + std::to_string(static_cast<long long>(bytes)) +
      " bytes of text can hold: the header is damaged or the file truncated.");
  }
}

RasterInfo describeRaster(GDALDataset& ds, const std::string& path, const ReadOptions& options);

// GDAL's longest message kept in a warning line; its longer explanations follow a first sentence.
constexpr std::size_t kLongestGdalWarning = 160;

// The raster's size, type, nodata, units and georeferencing, with GDAL's own warnings about
// them (an unknown EPSG code, damaged GeoTIFF keys, a negative pixel scale) passed on as one
// warning line instead of GDAL's "Warning 1:" lines.
RasterInfo describe(GDALDataset& ds, const std::string& path, const ReadOptions& options)
{
  GdalWarnings gdal;
  RasterInfo info = describeRaster(ds, path, options);
  if (!gdal.messages().empty())
  {
    std::string first = gdal.messages().front();
    std::replace(first.begin(), first.end(), '\n', ' ');
    const std::size_t sentence = first.find(". ");
    if (!first.empty() && first.back() == '.')
    {
      first.pop_back();
    }
    if (sentence != std::string::npos && sentence < kLongestGdalWarning)
    {
      first.resize(sentence); // the first sentence: GDAL's advice on options follows it
    }
    else if (first.size() > kLongestGdalWarning)
    {
      first = first.substr(0, kLongestGdalWarning) + "...";
    }
    info.warnings.push_back(path + ": GDAL read it with " + std::to_string(gdal.messages().size()) +
      " warning(s), the first: \"" + first +
      "\"; heights and georeferencing are as GDAL reads them.");
  }
  return info;
}

// NAME.json beside the raster, when asked for and there; its nodata stands in
// for a raster that declares none.
Sidecar sidecarFor(RasterInfo& info, const std::string& path, const ReadOptions& options)
{
  Sidecar sidecar;
  if (!options.useSidecar)
  {
    return sidecar;
  }
  const std::string sc = sidecarPathFor(path);
  if (sc != path && fs::exists(sc))
  {
    sidecar = readSidecar(sc);
    info.sidecarPath = sc;
    if (sidecar.nodata && !info.nodata)
    {
      info.nodata = sidecar.nodata;
    }
  }
  return sidecar;
}

// The CRS and the geotransform, and the cell size they give.
void readGeoreference(RasterInfo& info, GDALDataset& ds)
{
  const OGRSpatialReference* srs = ds.GetSpatialRef();
  if (srs != nullptr)
  {
    char* wkt = nullptr;
    srs->exportToWkt(&wkt);
    info.georef.crsWkt = wkt != nullptr ? wkt : "";
    CPLFree(wkt);
    const char* name = srs->GetName();
    info.crsName = name != nullptr ? name : "";
  }
  double gt[6];
  if (ds.GetGeoTransform(gt) == CE_None)
  {
    std::copy(gt, gt + 6, info.georef.geoTransform.begin());
    info.georef.hasGeoTransform = true;
    fillCellSizeFromGeoreference(info, srs, info.height);
  }
  else
  {
    info.cellSizeSource = "unknown (1 m assumed; give a sidecar or a cell size)";
  }
}

// The cell size: the options', else the sidecar's (with a warning when the
// georeference disagrees), else the georeference's. Throws for one that is
// not a positive finite size.
void settleCellSize(RasterInfo& info,
  const Sidecar& sidecar,
  const std::string& path,
  const ReadOptions& options)
{
  if (sidecar.cellX)
  {
    if (info.georef.hasGeoTransform &&
      (std::abs(*sidecar.cellX - info.cellX) > 1e-3 * info.cellX ||
        std::abs(*sidecar.cellY - info.cellY) > 1e-3 * info.cellY))
    {
      info.warnings.push_back(info.sidecarPath + " gives a cell size of " +
        std::to_string(*sidecar.cellX) + " x " + std::to_string(*sidecar.cellY) + " m but " + path +
        "'s georeference gives " + std::to_string(info.cellX) + " x " + std::to_string(info.cellY) +
        " m; using the sidecar (is it stale?).");
    }
    info.cellX = *sidecar.cellX;
    info.cellY = *sidecar.cellY;
    info.cellSizeKnown = true;
    info.cellSizeSource = "sidecar";
  }
  if (options.cellX > 0.0)
  {
    info.cellX = options.cellX;
    info.cellY = options.cellY > 0.0 ? options.cellY : options.cellX;
    info.cellSizeKnown = true;
    info.cellSizeSource = "options";
  }
  if (!(info.cellX > 0.0) || !(info.cellY > 0.0) || !std::isfinite(info.cellX) ||
    !std::isfinite(info.cellY))
  {
    throw Error(path + " has a degenerate geotransform (cell size " + std::to_string(info.cellX) +
      " x " + std::to_string(info.cellY) + "); give the cell size explicitly.");
  }
}

// The vertical unit: the options', then the sidecar's (with a warning when the
// file says otherwise), then the band's own, else metres.
void settleZUnit(RasterInfo& info,
  GDALRasterBand& band,
  const Sidecar& sidecar,
  const std::string& path,
  const ReadOptions& options)
{
  info.zUnit = ZUnit::Metres;
  info.zUnitSource = "default";
  const std::optional<ZUnit> bandUnit = parseZUnit(band.GetUnitType());
  if (bandUnit && *bandUnit != ZUnit::Auto)
  {
    info.zUnit = *bandUnit;
    info.zUnitSource = "file";
  }
  if (sidecar.zUnit)
  {
    if (info.zUnitSource == "file" && *sidecar.zUnit != info.zUnit)
    {
      info.warnings.push_back(info.sidecarPath + " says heights are in " +
        zUnitName(*sidecar.zUnit) + " but " + path + " says " + zUnitName(info.zUnit) +
        "; using the sidecar (is it stale?).");
    }
    info.zUnit = *sidecar.zUnit;
    info.zUnitSource = "sidecar";
  }
  if (options.zUnit != ZUnit::Auto)
  {
    info.zUnit = options.zUnit;
    info.zUnitSource = "options";
  }
}

// The normalised range of an integer image: the options', else the
// sidecar's. Throws for a range given by halves, empty, or for float values.
void settleNormalisedRange(RasterInfo& info,
  GDALRasterBand& band,
  const Sidecar& sidecar,
  const std::string& path,
  const ReadOptions& options)
{
  const bool integerCodes = integerTypeMax(band.GetRasterDataType()) != 0.0;
  if (options.zMin || options.zMax)
  {
    const double lo = options.zMin.value_or(0.0);
    const double hi = options.zMax.value_or(0.0);
    if (!options.zMin || !options.zMax || !(hi > lo))
    {
      throw Error("A normalised height range needs both z_min and z_max, with z_max > z_min.");
    }
    if (!integerCodes)
    {
      throw Error(path + " stores " + info.dataType +
        " values; a z_min/z_max range applies only to 8- or 16-bit unsigned images.");
    }
    info.normalised = true;
    info.zMin = lo;
    info.zMax = hi;
  }
  else if (sidecar.zMin && sidecar.zMax)
  {
    if (integerCodes)
    {
      info.normalised = true;
      info.zMin = *sidecar.zMin;
      info.zMax = *sidecar.zMax;
    }
    else
    {
      // A sidecar shared by NAME.png and NAME.tif describes the PNG's codes only.
      info.warnings.push_back("The range in " + info.sidecarPath + " applies to 8/16-bit images; " +
        path + " stores " + info.dataType + " heights, so the range is ignored.");
    }
  }
}

RasterInfo describeRaster(GDALDataset& ds, const std::string& path, const ReadOptions& options)
{
  RasterInfo info;
  info.path = path;
  info.driver = ds.GetDriver() != nullptr ? ds.GetDriver()->GetDescription() : "";
  info.width = ds.GetRasterXSize();
  info.height = ds.GetRasterYSize();
  info.bands = ds.GetRasterCount();
  GDALRasterBand* band = heightBand(ds, path);
  info.dataType = isSignedByte(*band) ? "Int8" : GDALGetDataTypeName(band->GetRasterDataType());
  int hasNodata = 0;
  const double nodata = band->GetNoDataValue(&hasNodata);
  if (hasNodata != 0)
  {
    info.nodata = nodata;
  }
  const Sidecar sidecar = sidecarFor(info, path, options);
  readGeoreference(info, ds);
  settleCellSize(info, sidecar, path, options);
  settleZUnit(info, *band, sidecar, path, options);
  settleNormalisedRange(info, *band, sidecar, path, options);
  return info;
}

GDALDriver* driverByName(const char* name)
{
  initialiseGdal();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName(name);
  if (driver == nullptr)
  {
    throw Error(std::string("This GDAL has no ") + name + " driver.");
  }
  return driver;
}

// Copies a memory dataset into a file format that only supports CreateCopy (PNG).
// Why GDAL failed to write `target` through its temporary `tmp`, as the end of a sentence: a
// full disk (the errno GDAL's writes left) in plain words, else GDAL's message with the
// temporary's name replaced by the user's.
std::string writeFailure(const std::string& target, const std::string& tmp, int error)
{
  if (QuietGdal::firstFailureErrno() != 0)
  {
    error = QuietGdal::firstFailureErrno();
  }
  if (error == ENOSPC || error == EDQUOT)
  {
    return "Cannot write " + target + ": " + std::strerror(error) + ".";
  }
  std::string message = QuietGdal::lastMessage();
  for (std::size_t at = message.find(tmp); at != std::string::npos; at = message.find(tmp))
  {
    message.replace(at, tmp.size(), target);
  }
  return "Cannot write " + target + message + ".";
}

// Closes a dataset being written and throws tsynth::Error naming `target` if GDAL reported a
// failure on the way or while flushing at the close (a full disk shows there). Call with a
// QuietGdal in scope, errno cleared before the writes began.
void closeWritten(DatasetPtr& ds, const std::string& target, const std::string& tmp)
{
  if (CPLGetLastErrorType() >= CE_Failure)
  {
    const int error = errno;
    ds.reset();
    throw Error(writeFailure(target, tmp, error));
  }
  ds.reset();
  if (CPLGetLastErrorType() >= CE_Failure)
  {
    throw Error(writeFailure(target, tmp, errno));
  }
}

// GDAL's progress function: asks GDAL to stop (FALSE) once a stop was requested.
int CPL_STDCALL goOnUnlessStopped(double /*done*/, const char* /*message*/, void* /*data*/)
{
  return cancellationRequested() ? FALSE : TRUE;
}

// Copies `source` into a new file at `tmp` (the temporary of `target`) with GDAL's driver.
void createCopyTo(const char* driverName,
  GDALDataset& source,
  const std::string& tmp,
  const std::string& target)
{
  QuietGdal quiet;
  errno = 0;
  DatasetPtr out(driverByName(driverName)
                   ->CreateCopy(tmp.c_str(), &source, FALSE, nullptr, goOnUnlessStopped, nullptr));
  if (!out && cancellationRequested())
  {
    throw Cancelled();
  }
  if (!out)
  {
    throw Error(writeFailure(target, tmp, errno));
  }
  closeWritten(out, target, tmp);
}

DatasetPtr memoryDataset(int width, int height, int bands, GDALDataType type)
{
  DatasetPtr mem(driverByName("MEM")->Create("", width, height, bands, type, nullptr));
  if (!mem)
  {
    throw Error("Out of memory creating a " + std::to_string(width) + " x " +
      std::to_string(height) + " image.");
  }
  return mem;
}

// The GeoTIFF's tiles are this many cells on a side (GDAL's default for TILED=YES, set
// explicitly because the writer flushes one row of tiles at a time).
constexpr int kGeoTiffTileSide = 256;

// Compresses and writes the completed row of tiles, then honours a stop request: deflating a
// large DEM takes seconds, and left to GDAL's cache it would all happen at close.
void flushTileRow(GDALRasterBand* band, const std::string& target, const std::string& tmp)
{
  if (band->FlushCache(false) != CE_None)
  {
    throw Error(writeFailure(target, tmp, errno));
  }
  checkCancellation();
}

void writeGeoTiff(const std::string& target, const std::string& tmp, const Heightfield& hf)
{
  QuietGdal quiet;
  char** opts = nullptr;
  opts = CSLSetNameValue(opts, "COMPRESS", "DEFLATE");
  opts = CSLSetNameValue(opts, "PREDICTOR", "3");
  opts = CSLSetNameValue(opts, "TILED", "YES");
  opts = CSLSetNameValue(opts, "BLOCKXSIZE", std::to_string(kGeoTiffTileSide).c_str());
  opts = CSLSetNameValue(opts, "BLOCKYSIZE", std::to_string(kGeoTiffTileSide).c_str());
  errno = 0;
  DatasetPtr ds(
    driverByName("GTiff")->Create(tmp.c_str(), hf.width, hf.height, 1, GDT_Float32, opts));
  CSLDestroy(opts);
  if (!ds)
  {
    throw Error(writeFailure(target, tmp, errno));
  }
  std::array<double, 6> gt = geoTransformOf(hf);
  ds->SetGeoTransform(gt.data());
  if (!hf.georef.crsWkt.empty())
  {
    ds->SetProjection(hf.georef.crsWkt.c_str());
  }
  GDALRasterBand* band = ds->GetRasterBand(1);
  band->SetUnitType("m");
  if (hf.hasMask())
  {
    band->SetNoDataValue(std::numeric_limits<double>::quiet_NaN());
  }
  std::vector<float> row(static_cast<std::size_t>(hf.width));
  for (int r = 0; r < hf.height; ++r)
  {
    const int j = hf.height - 1 - r;
    for (int i = 0; i < hf.width; ++i)
    {
      row[static_cast<std::size_t>(i)] =
        hf.isValid(i, j) ? hf.at(i, j) : std::numeric_limits<float>::quiet_NaN();
    }
    if (band->RasterIO(
          GF_Write, 0, r, hf.width, 1, row.data(), hf.width, 1, GDT_Float32, 0, 0, nullptr) !=
      CE_None)
    {
      throw Error(writeFailure(target, tmp, errno));
    }
    if ((r + 1) % kGeoTiffTileSide == 0)
    {
      flushTileRow(band, target, tmp);
    }
  }
  closeWritten(ds, target, tmp);
}

// The PNG's 16-bit codes: valid heights mapped linearly from `range` onto
// lowCode..65535, nodata as 0. Row 0 of the file is the north edge.
void writePng16Codes(const std::string& target,
  const std::string& tmp,
  const Heightfield& hf,
  const Png16Range& range,
  double lowCode)
{
  const double step = (range.zMax - range.zMin) / (kLargestPng16Code - lowCode);
  DatasetPtr mem = memoryDataset(hf.width, hf.height, 1, GDT_UInt16);
  std::vector<std::uint16_t> codes(hf.size());
  for (int r = 0; r < hf.height; ++r)
  {
    const int j = hf.height - 1 - r;
    for (int i = 0; i < hf.width; ++i)
    {
      std::uint16_t code = 0;
      if (hf.isValid(i, j))
      {
        const double c = lowCode + (hf.at(i, j) - range.zMin) / step;
        code = static_cast<std::uint16_t>(
          std::clamp(std::lround(c), 0L, static_cast<long>(kLargestPng16Code)));
      }
      codes[rowMajor(i, r, hf.width)] = code;
    }
  }
  if (mem->GetRasterBand(1)->RasterIO(GF_Write,
        0,
        0,
        hf.width,
        hf.height,
        codes.data(),
        hf.width,
        hf.height,
        GDT_UInt16,
        0,
        0,
        nullptr) != CE_None)
  {
    throw Error("Cannot write " + target + ".");
  }
  createCopyTo("PNG", *mem, tmp, target);
}

void writePng16(const std::string& target, const std::string& tmp, const Heightfield& hf)
{
  const HeightRange range = computeHeightRange(hf);
  if (range.validCells == 0)
  {
    throw Error("Cannot write " + target + ": the heightfield has no valid cell.");
  }
  // Valid heights map to 1..65535 when nodata must be kept (0 marks it), else 0..65535.
  const bool reserveZero = hf.hasMask();
  const double lowCode = reserveZero ? 1.0 : 0.0;
  double zLo = range.min;
  double zHi = range.max > range.min ? static_cast<double>(range.max) : zLo + 1.0;
  const double step = (zHi - zLo) / (kLargestPng16Code - lowCode);
  writePng16Codes(target, tmp, hf, { zLo, zHi }, lowCode);

  Sidecar sidecar;
  sidecar.zUnit = ZUnit::Metres;
  sidecar.cellX = hf.cellX;
  sidecar.cellY = hf.cellY;
  const double zMinOfCodeZero = zLo - lowCode * step;
  sidecar.zMin = zMinOfCodeZero;
  sidecar.zMax = zMinOfCodeZero + kLargestPng16Code * step;
  if (reserveZero)
  {
    sidecar.nodata = 0.0;
  }
  writeSidecar(sidecarPathFor(target), sidecar);
}

} // namespace

std::string lowerExtension(const std::string& path)
{
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(),
    ext.end(),
    ext.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

bool hasExtension(const std::string& path, const char* wanted)
{
  return lowerExtension(path) == wanted;
}

RasterInfo readRasterInfo(const std::string& path, const ReadOptions& options)
{
  DatasetPtr ds = openRaster(path);
  return describe(*ds, path, options);
}

Heightfield readHeightfield(const std::string& path, const ReadOptions& options, RasterInfo* out)
{
  DatasetPtr ds = openRaster(path);
  RasterInfo info = describe(*ds, path, options);
  GDALRasterBand* band = heightBand(*ds, path);

  const int w = info.width;
  const int h = info.height;
  checkTextRasterSize(info.driver, path, w, h);
  checkReadFits(path, w, h, kBytesPerReadCell);
  const std::size_t n = cellCount(w, h);
  std::vector<float> raw(n);
  std::vector<std::uint8_t> mask(n, 255);
  {
    QuietGdal quiet;
    if (band->RasterIO(GF_Read, 0, 0, w, h, raw.data(), w, h, GDT_Float32, 0, 0, nullptr) !=
      CE_None)
    {
      throw Error("Cannot read the heights of " + path + "; the file may be truncated or corrupt" +
        QuietGdal::lastMessage() + ".");
    }
    // GDAL's mask band covers nodata values, alpha bands and per-dataset masks.
    if ((band->GetMaskFlags() & GMF_ALL_VALID) == 0)
    {
      if (band->GetMaskBand()->RasterIO(
            GF_Read, 0, 0, w, h, mask.data(), w, h, GDT_Byte, 0, 0, nullptr) != CE_None)
      {
        throw Error("Cannot read the validity mask of " + path + QuietGdal::lastMessage() + ".");
      }
    }
  }

  const double unitScale = info.zUnit == ZUnit::Feet ? kMetresPerFoot : 1.0;
  const double typeMax = integerTypeMax(band->GetRasterDataType());
  if (isSignedByte(*band))
  {
    constexpr float kByteWrap = 256.0f; // two's complement: stored 128..255 are -128..-1
    for (float& v : raw)
    {
      v = v > 127.0f ? v - kByteWrap : v;
    }
  }
  const bool sidecarNodata = info.nodata && !info.sidecarPath.empty();
  const float nodataValue = info.nodata ? static_cast<float>(*info.nodata) : 0.0f;

  Heightfield hf(w, h);
  hf.cellX = info.cellX;
  hf.cellY = info.cellY;
  hf.cellSizeKnown = info.cellSizeKnown;
  hf.georef = info.georef;
  hf.sourceZUnit = zUnitName(info.zUnit);
  hf.valid.assign(n, 1);
  for (int r = 0; r < h; ++r)
  {
    const int j = h - 1 - r;
    for (int i = 0; i < w; ++i)
    {
      const std::size_t src = rowMajor(i, r, w);
      const std::size_t dst = hf.index(i, j);
      const float v = raw[src];
      if (mask[src] == 0 || !std::isfinite(v) || (sidecarNodata && v == nodataValue))
      {
        hf.valid[dst] = 0;
        continue;
      }
      double z = v;
      if (info.normalised)
      {
        z = info.zMin + (v / typeMax) * (info.zMax - info.zMin);
      }
      hf.z[dst] = static_cast<float>(z * unitScale);
    }
  }
  normaliseMask(hf);
  if (hf.validCount() == 0)
  {
    throw Error(path + " holds no valid heights (every cell is nodata).");
  }
  checkPlausibleHeights(hf, path);
  if (out != nullptr)
  {
    *out = std::move(info);
  }
  return hf;
}

ColourImage readColourImage(const std::string& path)
{
  DatasetPtr ds = openRaster(path);
  ColourImage img;
  img.width = ds->GetRasterXSize();
  img.height = ds->GetRasterYSize();
  // Before anything else, at the most a sketch can hold (4 channels and one 16-bit band on
  // the way): a damaged header must not make the reader allocate.
  constexpr double kMostBytesPerSketchCell = 4.0 + sizeof(std::uint16_t);
  checkTextRasterSize(ds->GetDriver() != nullptr ? ds->GetDriver()->GetDescription() : "",
    path,
    img.width,
    img.height);
  checkReadFits(path, img.width, img.height, kMostBytesPerSketchCell);
  img.channels = ds->GetRasterCount();
  if (img.channels > 4)
  {
    throw Error(path + " has " + std::to_string(img.channels) +
      " bands; a sketch image has 1 to 4 (grey, RGB, with or without alpha).");
  }
  GDALRasterBand* first = ds->GetRasterBand(1);
  const GDALDataType type = first->GetRasterDataType();
  if (type != GDT_Byte && type != GDT_UInt16)
  {
    throw Error(path + " stores " + std::string(GDALGetDataTypeName(type)) +
      " values; a sketch image must be 8- or 16-bit.");
  }
  if (img.channels == 1 && first->GetColorTable() != nullptr)
  {
    img.channels = 3; // expand a palette image to RGB
  }
  // The pixels, and one 16-bit band at a time on the way.
  checkReadFits(path, img.width, img.height, img.channels + sizeof(std::uint16_t));
  const std::size_t n = cellCount(img.width, img.height);
  img.data.assign(cellCount(n, img.channels), 0);
  QuietGdal quiet;
  if (ds->GetRasterCount() == 1 && first->GetColorTable() != nullptr)
  {
    std::vector<std::uint8_t> index(n);
    if (first->RasterIO(GF_Read,
          0,
          0,
          img.width,
          img.height,
          index.data(),
          img.width,
          img.height,
          GDT_Byte,
          0,
          0,
          nullptr) != CE_None)
    {
      throw Error("Cannot read the pixels of " + path + QuietGdal::lastMessage() + ".");
    }
    const GDALColorTable* table = first->GetColorTable();
    for (std::size_t k = 0; k < n; ++k)
    {
      const GDALColorEntry* e = table->GetColorEntry(index[k]);
      img.data[3 * k] = static_cast<std::uint8_t>(e != nullptr ? e->c1 : 0);
      img.data[3 * k + 1] = static_cast<std::uint8_t>(e != nullptr ? e->c2 : 0);
      img.data[3 * k + 2] = static_cast<std::uint8_t>(e != nullptr ? e->c3 : 0);
    }
    return img;
  }
  std::vector<std::uint16_t> values(n);
  for (int b = 0; b < img.channels; ++b)
  {
    if (ds->GetRasterBand(b + 1)->RasterIO(GF_Read,
          0,
          0,
          img.width,
          img.height,
          values.data(),
          img.width,
          img.height,
          GDT_UInt16,
          0,
          0,
          nullptr) != CE_None)
    {
      throw Error("Cannot read the pixels of " + path + "; the file may be truncated or corrupt" +
        QuietGdal::lastMessage() + ".");
    }
    const int shift = type == GDT_UInt16 ? 8 : 0;
    for (std::size_t k = 0; k < n; ++k)
    {
      img.data[rowMajor(b, k, img.channels)] = static_cast<std::uint8_t>(values[k] >> shift);
    }
  }
  return img;
}

bool isHeightfieldWriteExtension(const std::string& path)
{
  const std::string ext = lowerExtension(path);
  return ext == ".tif" || ext == ".tiff" || ext == ".png";
}

void writeHeightfield(const std::string& path, const Heightfield& hf)
{
  if (hf.width <= 0 || hf.height <= 0 || hf.size() != cellCount(hf.width, hf.height))
  {
    throw Error("Cannot write " + path + ": the heightfield is empty or inconsistent.");
  }
  checkWritableHeights(hf, path);
  const std::string ext = lowerExtension(path);
  if (!isHeightfieldWriteExtension(path))
  {
    throw Error(
      "Cannot write " + path + ": unknown extension \"" + ext + "\" (use .tif, .png or .vti).");
  }
  OutputFile file(path);
  if (ext == ".png")
  {
    writePng16(path, file.temporaryPath(), hf);
  }
  else
  {
    writeGeoTiff(path, file.temporaryPath(), hf);
  }
  file.commit();
}

std::array<double, 6> geoTransformOf(const Heightfield& hf)
{
  if (hf.georef.hasGeoTransform)
  {
    return hf.georef.geoTransform;
  }
  // Local frame in metres: lower-left cell centre at (0, 0), north up.
  return { -0.5 * hf.cellX, hf.cellX, 0.0, (hf.height - 0.5) * hf.cellY, 0.0, -hf.cellY };
}

void writePng16InRange(const std::string& path, const Heightfield& hf, const Png16Range& range)
{
  if (hf.width <= 0 || hf.height <= 0 || hf.size() != cellCount(hf.width, hf.height))
  {
    throw Error("Cannot write " + path + ": the heightfield is empty or inconsistent.");
  }
  if (!(range.zMax > range.zMin))
  {
    throw Error("Cannot write " + path + ": its height range is empty.");
  }
  OutputFile file(path);
  writePng16Codes(path, file.temporaryPath(), hf, range, 0.0);
  file.commit();
}

void writeRgbPng(const std::string& path,
  int width,
  int height,
  const std::vector<std::uint8_t>& rgb)
{
  if (width <= 0 || height <= 0 || rgb.size() != cellCount(width, height) * 3)
  {
    throw Error("Cannot write " + path + ": the image is empty or inconsistent.");
  }
  OutputFile file(path);
  DatasetPtr mem = memoryDataset(width, height, 3, GDT_Byte);
  int bandMap[3] = { 1, 2, 3 };
  if (mem->RasterIO(GF_Write,
        0,
        0,
        width,
        height,
        const_cast<std::uint8_t*>(rgb.data()),
        width,
        height,
        GDT_Byte,
        3,
        bandMap,
        3,
        3 * width,
        1,
        nullptr) != CE_None)
  {
    throw Error("Cannot write " + path + ".");
  }
  createCopyTo("PNG", *mem, file.temporaryPath(), path);
  file.commit();
}

const std::vector<OptionRow>& readOptionRows()
{
  static const std::vector<OptionRow> rows = []
  {
    const ReadOptions d;
    using T = OptionType;
    return std::vector<OptionRow>{
      choiceRow("ZUnit",
        "--z-unit",
        static_cast<int>(d.zUnit),
        choicesOf(kZUnitWords),
        { "Auto (sidecar, file, else metres)", "Metres", "Feet" }),
      numberRow("CellSize", "--cell", T::Real, d.cellX, 0.0, kMaxCellSizeMetres),
      switchRow("UseSidecar", "--no-sidecar", d.useSidecar),
      switchRow("UseNormalisedRange", "--z-range", d.zMin.has_value()),
      // Placeholders until UseNormalisedRange is on (a range must be typed then).
      numberRow("ZMin", "--z-range", T::Real, 0.0, -kMaxNormalisedHeight, kMaxNormalisedHeight),
      numberRow("ZMax", "--z-range", T::Real, 1.0, -kMaxNormalisedHeight, kMaxNormalisedHeight),
    };
  }();
  return rows;
}

} // namespace tsynth
