// tsynth: the TerrainSynthesis command line. Every command exits 0 on success,
// 1 with one sentence on bad input or failure, 2 on wrong usage.
#include "CommandLine.h"
#include "Render3D.h"
#include "TerrainFileIO.h"

#include "Analysis/Hillshade.h"
#include "Analysis/ReliefImage.h"
#include "Core/Error.h"
#include "Core/HeightfieldIO.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace
{

using tsynth::cli::CommandLine;
using tsynth::cli::UsageError;

const char* const kMainHelp = R"(tsynth: example-based terrain synthesis from real DEMs.

Usage: tsynth COMMAND [options]

Commands:
  info DEM               size, cell size, height range, CRS and units of a DEM
  render DEM -o PNG      hillshade picture with a colour ramp; --3d for an oblique 3D view
  convert DEM -o OUT     write a DEM as GeoTIFF float32 (.tif), 16-bit PNG + sidecar (.png) or .vti

Run "tsynth COMMAND --help" for a command's options.
)";

const char* const kReadOptionsHelp = R"(
Options for reading DEMs (override the NAME.json sidecar and the file):
  --z-unit m|ft          unit of the stored heights (feet are converted to metres)
  --cell M | MX,MY       cell size in metres
  --z-range MIN,MAX      8/16-bit image storing a normalised range: value 0 is MIN, the largest MAX
  --no-sidecar           ignore NAME.json beside the file
)";

const char* const kInfoHelp = R"(Usage: tsynth info DEM [--json] [read options]

Prints the size, cell size (metres), height range (metres), nodata share, CRS and
units of a DEM. --json prints the same as a JSON object.
)";

const char* const kRenderHelp = R"(Usage: tsynth render DEM -o OUT.png [--3d] [options]

Writes a picture of the terrain: a multi-directional hillshade tinted by height,
one pixel per cell. With --3d, an oblique lit 3D view instead (needs an X display;
without one tsynth re-runs itself under xvfb-run).

  -o, --output PNG       the picture to write (.png)
  --3d                   oblique 3D view
  --exaggeration F       vertical exaggeration (default 1 for the map, 2 for --3d)
  --altitude DEG         sun elevation for the map (default 45)
  --azimuth DEG          single light from this direction, clockwise from north
  --size WxH             3D picture size in pixels (default 1600x1000)
)";

const char* const kConvertHelp = R"(Usage: tsynth convert DEM -o OUT [read options]

Reads a DEM (units, sidecar, nodata as for every command) and writes heights in
metres: .tif GeoTIFF float32 (georeference kept), .png 16-bit with a NAME.json
sidecar recording the range and cell size, or .vti (opens in ParaView).
)";

tsynth::ReadOptions takeReadOptions(CommandLine& cl)
{
  tsynth::ReadOptions o;
  if (auto unit = cl.take("--z-unit"))
  {
    const auto parsed = tsynth::parseZUnit(*unit);
    if (!parsed)
    {
      throw UsageError("--z-unit must be m or ft, not \"" + *unit + "\".");
    }
    o.zUnit = *parsed;
  }
  if (auto cell = cl.take("--cell"))
  {
    const std::size_t comma = cell->find(',');
    const auto x = tsynth::cli::parseNumber(cell->substr(0, comma));
    const auto y =
      comma == std::string::npos ? x : tsynth::cli::parseNumber(cell->substr(comma + 1));
    if (!x || !y || !(*x > 0.0) || !(*y > 0.0))
    {
      throw UsageError("--cell expects a positive number of metres or X,Y, not \"" + *cell + "\".");
    }
    o.cellX = *x;
    o.cellY = *y;
  }
  if (auto range = cl.take("--z-range"))
  {
    const std::size_t comma = range->find(',');
    const auto lo = tsynth::cli::parseNumber(range->substr(0, comma));
    const auto hi = comma == std::string::npos ? std::nullopt
                                               : tsynth::cli::parseNumber(range->substr(comma + 1));
    if (!lo || !hi || !(*hi > *lo))
    {
      throw UsageError("--z-range expects MIN,MAX with MAX > MIN, not \"" + *range + "\".");
    }
    o.zMin = lo;
    o.zMax = hi;
  }
  o.useSidecar = !cl.takeFlag("--no-sidecar");
  return o;
}

// Reads a DEM and passes on the reader's warnings, one line each.
tsynth::Heightfield readDem(const std::string& path,
  const tsynth::ReadOptions& options,
  tsynth::RasterInfo* info = nullptr)
{
  tsynth::RasterInfo local;
  tsynth::RasterInfo& used = info != nullptr ? *info : local;
  tsynth::Heightfield hf = tsynth::readTerrainFile(path, options, &used);
  for (const std::string& warning : used.warnings)
  {
    std::cerr << "tsynth: warning: " << warning << "\n";
  }
  return hf;
}

std::string oneInput(const CommandLine& cl, const char* command)
{
  const std::vector<std::string> rest = cl.positionals();
  if (rest.empty())
  {
    throw UsageError(std::string("tsynth ") + command + " needs a DEM file.");
  }
  if (rest.size() > 1)
  {
    throw UsageError("Unexpected argument \"" + rest[1] + "\".");
  }
  return rest[0];
}

bool wantsHelp(const std::vector<std::string>& args)
{
  for (const auto& a : args)
  {
    if (a == "--help" || a == "-h")
    {
      return true;
    }
  }
  return false;
}

std::string jsonString(const std::string& s)
{
  std::ostringstream o;
  o << '"';
  for (char c : s)
  {
    switch (c)
    {
      case '"':
        o << "\\\"";
        break;
      case '\\':
        o << "\\\\";
        break;
      case '\n':
        o << "\\n";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20)
        {
          o << ' ';
        }
        else
        {
          o << c;
        }
    }
  }
  o << '"';
  return o.str();
}

int runInfo(std::vector<std::string> args)
{
  if (wantsHelp(args))
  {
    std::cout << kInfoHelp << kReadOptionsHelp;
    return 0;
  }
  CommandLine cl(std::move(args));
  const bool json = cl.takeFlag("--json");
  const tsynth::ReadOptions options = takeReadOptions(cl);
  const std::string path = oneInput(cl, "info");

  tsynth::RasterInfo info;
  const tsynth::Heightfield hf = readDem(path, options, &info);
  const tsynth::HeightRange range = tsynth::computeHeightRange(hf);
  const std::size_t invalid = hf.size() - range.validCells;
  const double invalidShare = 100.0 * static_cast<double>(invalid) / static_cast<double>(hf.size());
  const std::string crs = info.crsName.empty() ? "none" : info.crsName;

  if (json)
  {
    std::cout << std::setprecision(10) << "{\n"
              << "  \"file\": " << jsonString(path) << ",\n"
              << "  \"format\": " << jsonString(info.driver) << ",\n"
              << "  \"data_type\": " << jsonString(info.dataType) << ",\n"
              << "  \"width\": " << hf.width << ",\n"
              << "  \"height\": " << hf.height << ",\n"
              << "  \"cell_size_m\": [" << hf.cellX << ", " << hf.cellY << "],\n"
              << "  \"cell_size_source\": " << jsonString(info.cellSizeSource) << ",\n"
              << "  \"z_min_m\": " << range.min << ",\n"
              << "  \"z_max_m\": " << range.max << ",\n"
              << "  \"z_mean_m\": " << range.mean << ",\n"
              << "  \"source_z_unit\": " << jsonString(tsynth::zUnitName(info.zUnit)) << ",\n"
              << "  \"z_unit_source\": " << jsonString(info.zUnitSource) << ",\n"
              << "  \"normalised\": " << (info.normalised ? "true" : "false") << ",\n"
              << "  \"nodata_cells\": " << invalid << ",\n"
              << "  \"crs\": " << jsonString(crs) << ",\n"
              << "  \"geographic\": " << (info.georef.isGeographic ? "true" : "false") << ",\n"
              << "  \"sidecar\": " << jsonString(info.sidecarPath) << "\n"
              << "}\n";
    return 0;
  }
  std::cout << std::fixed;
  std::cout << "File:       " << path << "\n";
  std::cout << "Format:     " << info.driver << ", " << info.dataType
            << (info.bands > 1 ? ", " + std::to_string(info.bands) + " bands" : std::string())
            << "\n";
  std::cout << "Size:       " << hf.width << " x " << hf.height << " cells ("
            << std::setprecision(2) << hf.width * hf.cellX / 1000.0 << " x "
            << hf.height * hf.cellY / 1000.0 << " km)\n";
  std::cout << "Cell size:  " << std::setprecision(3) << hf.cellX << " x " << hf.cellY << " m ("
            << info.cellSizeSource << ")\n";
  std::cout << "Heights:    " << std::setprecision(2) << range.min << " to " << range.max
            << " m, mean " << range.mean << " m\n";
  std::cout << "Stored in:  " << (info.zUnit == tsynth::ZUnit::Feet ? "feet" : "metres") << " ("
            << info.zUnitSource << ")"
            << "\n";
  if (info.normalised)
  {
    std::cout << "Range:      codes map linearly onto " << std::setprecision(2) << info.zMin
              << " to " << info.zMax << " " << tsynth::zUnitName(info.zUnit) << "\n";
  }
  std::cout << "Nodata:     " << invalid << " cells (" << std::setprecision(2) << invalidShare
            << "%)\n";
  std::cout << "CRS:        " << crs << (info.georef.isGeographic ? " (geographic)" : "") << "\n";
  if (!info.sidecarPath.empty())
  {
    std::cout << "Sidecar:    " << info.sidecarPath << "\n";
  }
  return 0;
}

// Re-runs this command under xvfb-run when there is no X display for --3d.
void ensureDisplay(int argc, char** argv)
{
  const char* display = std::getenv("DISPLAY");
  if (display != nullptr && *display != '\0')
  {
    return;
  }
  if (std::getenv("TSYNTH_UNDER_XVFB") != nullptr)
  {
    throw tsynth::Error("--3d needs an X display and xvfb-run did not provide one.");
  }
  setenv("TSYNTH_UNDER_XVFB", "1", 1);
  std::vector<char*> command = { const_cast<char*>("xvfb-run"),
    const_cast<char*>("-a"),
    const_cast<char*>("-s"),
    const_cast<char*>("-screen 0 1920x1200x24") };
  for (int k = 0; k < argc; ++k)
  {
    command.push_back(argv[k]);
  }
  command.push_back(nullptr);
  execvp("xvfb-run", command.data());
  throw tsynth::Error("--3d needs an X display: set DISPLAY or install xvfb (xvfb-run).");
}

bool hasPngExtension(const std::string& path)
{
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext)
  {
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return ext == ".png";
}

int runRender(std::vector<std::string> args, int argc, char** argv)
{
  if (wantsHelp(args))
  {
    std::cout << kRenderHelp << kReadOptionsHelp;
    return 0;
  }
  CommandLine cl(std::move(args));
  const std::optional<std::string> output = cl.take("--output", "-o");
  const bool threeD = cl.takeFlag("--3d");
  const std::optional<double> exaggeration = cl.takeNumber("--exaggeration");
  const std::optional<double> altitude = cl.takeNumber("--altitude");
  const std::optional<double> azimuth = cl.takeNumber("--azimuth");
  const std::optional<std::string> size = cl.take("--size");
  const tsynth::ReadOptions options = takeReadOptions(cl);
  const std::string path = oneInput(cl, "render");
  if (!output)
  {
    throw UsageError("tsynth render needs an output picture: -o OUT.png.");
  }
  if (!hasPngExtension(*output))
  {
    throw UsageError("The picture must be a .png file, not " + *output + ".");
  }
  if (exaggeration && !(*exaggeration > 0.0))
  {
    throw UsageError("--exaggeration must be positive.");
  }
  if (altitude && (*altitude < 0.0 || *altitude > 90.0))
  {
    throw UsageError("--altitude must be between 0 and 90 degrees.");
  }
  tsynth::Render3DOptions view;
  if (size)
  {
    int w = 0;
    int h = 0;
    char tail = 0;
    if (std::sscanf(size->c_str(), "%dx%d%c", &w, &h, &tail) != 2 || w < 16 || h < 16 || w > 8192 ||
      h > 8192)
    {
      throw UsageError("--size expects WxH between 16 and 8192 pixels, e.g. 1600x1000.");
    }
    view.width = w;
    view.height = h;
  }

  const tsynth::Heightfield hf = readDem(path, options);
  if (threeD)
  {
    ensureDisplay(argc, argv);
    view.exaggeration = exaggeration.value_or(2.0);
    tsynth::render3D(hf, *output, view);
  }
  else
  {
    tsynth::HillshadeOptions shading;
    shading.zFactor = exaggeration.value_or(1.0);
    shading.altitudeDeg = altitude.value_or(45.0);
    if (azimuth)
    {
      shading.multidirectional = false;
      shading.azimuthDeg = *azimuth;
    }
    const tsynth::ShadedRelief relief = tsynth::computeHillshade(hf, shading);
    tsynth::writeRgbPng(*output, hf.width, hf.height, tsynth::renderRelief(hf, relief));
  }
  std::cout << "Wrote " << *output << "\n";
  return 0;
}

int runConvert(std::vector<std::string> args)
{
  if (wantsHelp(args))
  {
    std::cout << kConvertHelp << kReadOptionsHelp;
    return 0;
  }
  CommandLine cl(std::move(args));
  const std::optional<std::string> output = cl.take("--output", "-o");
  const tsynth::ReadOptions options = takeReadOptions(cl);
  const std::string path = oneInput(cl, "convert");
  if (!output)
  {
    throw UsageError("tsynth convert needs an output file: -o OUT.tif|.png|.vti.");
  }
  if (!tsynth::isVtiPath(*output) && !tsynth::isHeightfieldWriteExtension(*output))
  {
    throw UsageError("The output must end in .tif, .png or .vti, not " + *output + ".");
  }
  const tsynth::Heightfield hf = readDem(path, options);
  tsynth::writeTerrainFile(*output, hf);
  std::cout << "Wrote " << *output << "\n";
  return 0;
}

} // namespace

int main(int argc, char** argv)
{
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help")
  {
    std::cout << kMainHelp;
    return args.empty() ? 2 : 0;
  }
  const std::string command = args[0];
  args.erase(args.begin());
  try
  {
    if (command == "info")
    {
      return runInfo(std::move(args));
    }
    if (command == "render")
    {
      return runRender(std::move(args), argc, argv);
    }
    if (command == "convert")
    {
      return runConvert(std::move(args));
    }
    throw UsageError("Unknown command \"" + command + "\".");
  }
  catch (const UsageError& e)
  {
    std::cerr << "tsynth: " << e.what()
              << " See \"tsynth " +
        (command.rfind('-', 0) == 0 ? std::string("--help") : command + " --help")
              << "\".\n";
    return 2;
  }
  catch (const tsynth::Error& e)
  {
    std::cerr << "tsynth: " << e.what() << "\n";
    return 1;
  }
  catch (const std::exception& e)
  {
    std::cerr << "tsynth: unexpected failure: " << e.what() << "\n";
    return 1;
  }
}
