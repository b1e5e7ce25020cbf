#include "TerrainFileIO.h"

#include "FeatureGraphConversion.h"
#include "TerrainImageConversion.h"
#include "VtkErrorObserver.h"
#include "XmlDataFiles.h"

#include "Core/Error.h"

#include <vtkCommand.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkXMLImageDataReader.h>
#include <vtkXMLImageDataWriter.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <system_error>

namespace fs = std::filesystem;

namespace tsynth
{

void requireFileForReader(const std::string& path)
{
  std::error_code ec;
  if (fs::exists(path, ec))
  {
    return;
  }
  if (fs::path(path).is_relative())
  {
    throw Error("No such file: " + path + " (a relative name, looked for in the working folder " +
      fs::current_path(ec).string() +
      "); for a state file, use File > Load State > \"Search files under specified directory\" "
      "and choose the folder that holds it, or give the full path.");
  }
  throw Error("No such file: " + path + ".");
}

bool isVtiPath(const std::string& path)
{
  return hasExtension(path, ".vti");
}

bool isDemRaster(const std::string& path)
{
  try
  {
    const RasterInfo info = readRasterInfo(path, {});
    return rasterIsDemTarget(info.bands, info.dataType == "Byte");
  }
  catch (const Error&)
  {
    return false; // several bands: a sketch image, read as one
  }
}

SketchInput readSketchInput(const std::string& path, std::vector<std::string>& warnings)
{
  if (hasExtension(path, ".vtp"))
  {
    vtkNew<vtkPolyData> lines;
    readPolyDataFile(path, lines);
    std::string warning;
    PolylineSketch sketch = polyDataToPolylineSketch(lines, &warning);
    if (!warning.empty())
    {
      warnings.push_back(warning);
    }
    return sketch;
  }
  if (isVtiPath(path) || isDemRaster(path))
  {
    RasterInfo info;
    Heightfield dem = readTerrainFile(path, {}, &info);
    warnings.insert(warnings.end(), info.warnings.begin(), info.warnings.end());
    return dem;
  }
  return readColourImage(path);
}

Heightfield readTerrainFile(const std::string& path, const ReadOptions& options, RasterInfo* info)
{
  if (!isVtiPath(path))
  {
    return readHeightfield(path, options, info);
  }
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
  {
    throw Error("No such file: " + path + ".");
  }
  vtkNew<vtkXMLImageDataReader> reader;
  reader->SetFileName(path.c_str());
  readXmlDataFile(reader, path, "image");
  vtkImageData* image = reader->GetOutput();
  if (image == nullptr || image->GetNumberOfPoints() == 0)
  {
    throw Error(path + " is not a VTK image file that can be read.");
  }
  Heightfield hf = imageToHeightfield(image);
  if (options.cellX > 0.0)
  {
    hf.cellX = options.cellX;
    hf.cellY = options.cellY > 0.0 ? options.cellY : options.cellX;
  }
  if (options.zUnit == ZUnit::Feet)
  {
    for (float& v : hf.z)
    {
      v = static_cast<float>(v * kMetresPerFoot);
    }
    hf.sourceZUnit = "ft";
  }
  if (hf.validCount() == 0)
  {
    throw Error(path + " holds no valid heights (every cell is nodata).");
  }
  if (info != nullptr)
  {
    *info = RasterInfo{};
    info->path = path;
    info->driver = "VTK XML image";
    info->dataType = "Float32";
    info->width = hf.width;
    info->height = hf.height;
    info->bands = 1;
    info->cellX = hf.cellX;
    info->cellY = hf.cellY;
    info->cellSizeKnown = true;
    info->cellSizeSource = options.cellX > 0.0 ? "options" : "image spacing";
    info->zUnit = options.zUnit == ZUnit::Feet ? ZUnit::Feet : ZUnit::Metres;
    info->zUnitSource = options.zUnit == ZUnit::Feet ? "options" : "file";
    info->georef = hf.georef;
  }
  return hf;
}

void writeTerrainFile(const std::string& path, const Heightfield& hf)
{
  if (!isVtiPath(path))
  {
    writeHeightfield(path, hf);
    return;
  }
  checkWritableHeights(hf, path);
  vtkNew<vtkImageData> image;
  heightfieldToImage(hf, image);
  vtkNew<vtkXMLImageDataWriter> writer;
  writeXmlDataFile(writer, image, path);
}

} // namespace tsynth
