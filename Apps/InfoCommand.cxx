// tsynth info: size, cell size, height range, nodata share, CRS and units of a DEM.
#include "Commands.h"

#include "CliSupport.h"
#include "CommandLine.h"

#include "Core/HeightfieldIO.h"

#include <nlohmann/json.hpp>

#include <iomanip>
#include <iostream>

namespace tsynth::cli
{
namespace
{

const char* const kInfoHelp = R"(Usage: tsynth info DEM [--json] [read options]

Prints the size, cell size (metres), height range (metres), nodata share, CRS and
units of a DEM. --json prints the same as a JSON object.
)";

// What `tsynth info` reports of one DEM.
struct DemSummary
{
  std::string path;
  RasterInfo info;
  Heightfield hf;
  HeightRange range;
  std::size_t invalid = 0; // nodata cells
  std::string crs;         // "none" without one
};

DemSummary summariseDem(const std::string& path, const ReadOptions& options)
{
  DemSummary s;
  s.path = path;
  s.hf = readDem(path, options, &s.info);
  s.range = computeHeightRange(s.hf);
  s.invalid = s.hf.size() - s.range.validCells;
  s.crs = s.info.crsName.empty() ? "none" : s.info.crsName;
  return s;
}

void printInfoJson(const DemSummary& s)
{
  // nlohmann escapes quotes, backslashes and control characters in paths and
  // replaces bytes that are not UTF-8, so the output is always valid JSON.
  const nlohmann::ordered_json doc = { { "file", s.path },
    { "format", s.info.driver },
    { "data_type", s.info.dataType },
    { "width", s.hf.width },
    { "height", s.hf.height },
    { "cell_size_m", { s.hf.cellX, s.hf.cellY } },
    { "cell_size_source", s.info.cellSizeSource },
    { "z_min_m", s.range.min },
    { "z_max_m", s.range.max },
    { "z_mean_m", s.range.mean },
    { "source_z_unit", zUnitName(s.info.zUnit) },
    { "z_unit_source", s.info.zUnitSource },
    { "normalised", s.info.normalised },
    { "nodata_cells", s.invalid },
    { "crs", s.crs },
    { "geographic", s.info.georef.isGeographic },
    { "sidecar", s.info.sidecarPath } };
  std::cout << doc.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
}

void printInfoText(const DemSummary& s)
{
  const RasterInfo& info = s.info;
  const Heightfield& hf = s.hf;
  const double invalidShare =
    100.0 * static_cast<double>(s.invalid) / static_cast<double>(hf.size());
  std::cout << std::fixed;
  std::cout << "File:       " << s.path << "\n";
  std::cout << "Format:     " << info.driver << ", " << info.dataType
            << (info.bands > 1 ? ", " + std::to_string(info.bands) + " bands" : std::string())
            << "\n";
  std::cout << "Size:       " << hf.width << " x " << hf.height << " cells ("
            << std::setprecision(2) << hf.width * hf.cellX / 1000.0 << " x "
            << hf.height * hf.cellY / 1000.0 << " km)\n";
  std::cout << "Cell size:  " << std::setprecision(3) << hf.cellX << " x " << hf.cellY << " m ("
            << info.cellSizeSource << ")\n";
  std::cout << "Heights:    " << std::setprecision(2) << s.range.min << " to " << s.range.max
            << " m, mean " << s.range.mean << " m\n";
  std::cout << "Stored in:  " << (info.zUnit == ZUnit::Feet ? "feet" : "metres") << " ("
            << info.zUnitSource << ")\n";
  if (info.normalised)
  {
    std::cout << "Range:      codes map linearly onto " << std::setprecision(2) << info.zMin
              << " to " << info.zMax << " " << zUnitName(info.zUnit) << "\n";
  }
  std::cout << "Nodata:     " << s.invalid << " cells (" << std::setprecision(2) << invalidShare
            << "%)\n";
  std::cout << "CRS:        " << s.crs << (info.georef.isGeographic ? " (geographic)" : "") << "\n";
  if (!info.sidecarPath.empty())
  {
    std::cout << "Sidecar:    " << info.sidecarPath << "\n";
  }
}

} // namespace

int runInfo(std::vector<std::string> args)
{
  if (wantsHelp(args))
  {
    std::cout << kInfoHelp << kReadOptionsHelp;
    return 0;
  }
  CommandLine cl(std::move(args));
  const bool json = cl.takeFlag("--json");
  const ReadOptions options = takeReadOptions(cl);
  const std::string path = oneInput(cl, "info");
  const DemSummary summary = summariseDem(path, options);
  if (json)
  {
    printInfoJson(summary);
  }
  else
  {
    printInfoText(summary);
  }
  return 0;
}

} // namespace tsynth::cli
