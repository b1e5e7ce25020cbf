#include "vtkTerrainSketchReader.h"

#include "PipelineRequests.h"
#include "TerrainFileIO.h"
#include "TerrainImageConversion.h"

#include "Core/Error.h"
#include "Features/Sketch.h"

#include <vtkDataObject.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <cstddef>
#include <new>
#include <string>
#include <variant>

vtkStandardNewMacro(vtkTerrainSketchReader);

namespace
{

constexpr const char* kSketchArray = "Sketch";
constexpr double kNoExemplarCell = 1.0; // metres: the pixel size ParaView's own readers give

struct SketchGrid
{
  int width = 0;
  int height = 0;
  double cellX = kNoExemplarCell;
  double cellY = kNoExemplarCell;
};

// The sketch file's pixel count.
void sketchPixels(const std::string& path, SketchGrid& grid)
{
  if (tsynth::hasExtension(path, ".vtp"))
  {
    throw tsynth::Error(path +
      " holds poly-lines, which are in metres already: open it with "
      "ParaView's XML PolyData reader and give it to Sketch as it is.");
  }
  if (tsynth::isVtiPath(path) || tsynth::isDemRaster(path))
  {
    tsynth::RasterInfo info;
    if (tsynth::isVtiPath(path))
    {
      tsynth::readTerrainFile(path, {}, &info); // .vti: its size is in the file itself
    }
    else
    {
      info = tsynth::readRasterInfo(path, {});
    }
    grid.width = info.width;
    grid.height = info.height;
    return;
  }
  // A sketch image: small (a few MB), read whole, as GDAL gives no header for several bands.
  const tsynth::ColourImage image = tsynth::readColourImage(path);
  grid.width = image.width;
  grid.height = image.height;
}

// The cells the synthesis will give the sketch's pixels: CellSize, else the exemplar's.
void sketchCells(const char* exemplar, double cellSize, SketchGrid& grid)
{
  if (cellSize > 0.0)
  {
    grid.cellX = grid.cellY = cellSize;
    return;
  }
  if (exemplar == nullptr || *exemplar == '\0')
  {
    return;
  }
  tsynth::RasterInfo info;
  if (tsynth::isVtiPath(exemplar))
  {
    tsynth::readTerrainFile(exemplar, {}, &info);
  }
  else
  {
    info = tsynth::readRasterInfo(exemplar, {});
  }
  grid.cellX = info.cellX;
  grid.cellY = info.cellY;
}

SketchGrid sketchGrid(const char* fileName, const char* exemplar, double cellSize)
{
  if (fileName == nullptr || *fileName == '\0')
  {
    throw tsynth::Error("No sketch file given: set FileName.");
  }
  tsynth::requireFileForReader(fileName);
  if (exemplar != nullptr && *exemplar != '\0')
  {
    tsynth::requireFileForReader(exemplar);
  }
  SketchGrid grid;
  sketchPixels(fileName, grid);
  sketchCells(exemplar, cellSize, grid);
  return grid;
}

// A stroke or grey map's pixels as the image's "Sketch" point scalars, bottom row first.
void colourImageToImage(const tsynth::ColourImage& sketch, vtkImageData* out)
{
  vtkNew<vtkUnsignedCharArray> pixels;
  pixels->SetName(kSketchArray);
  pixels->SetNumberOfComponents(sketch.channels);
  pixels->SetNumberOfTuples(static_cast<vtkIdType>(sketch.width) * sketch.height);
  const auto rowBytes =
    static_cast<std::size_t>(sketch.width) * static_cast<std::size_t>(sketch.channels);
  for (int row = 0; row < sketch.height; ++row) // VTK's rows run north from the bottom
  {
    const std::uint8_t* from = sketch.pixel(0, sketch.height - 1 - row);
    std::copy(
      from, from + rowBytes, pixels->GetPointer(0) + static_cast<std::size_t>(row) * rowBytes);
  }
  out->SetDimensions(sketch.width, sketch.height, 1);
  out->GetPointData()->SetScalars(pixels);
}

} // namespace

vtkTerrainSketchReader::vtkTerrainSketchReader()
{
  this->SetNumberOfInputPorts(0);
  this->SetNumberOfOutputPorts(1);
  // The sketch's cell size, as the Terrain Sketch Features filter takes it
  // (tsynth::sketchOptionRows).
  this->CellSize = tsynth::optionRow(tsynth::sketchOptionRows(), "CellSize").defaultValue;
}

vtkTerrainSketchReader::~vtkTerrainSketchReader()
{
  this->SetFileName(nullptr);
  this->SetExemplarFileName(nullptr);
}

int vtkTerrainSketchReader::RequestInformation(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  SketchGrid grid;
  try
  {
    grid = sketchGrid(this->FileName, this->ExemplarFileName, this->CellSize);
  }
  catch (const std::exception& e)
  {
    tsynth::reportRefusal(this, e.what()); // once, not per request and representation
    return 0;
  }
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  const int extent[6] = { 0, grid.width - 1, 0, grid.height - 1, 0, 0 };
  const double spacing[3] = { grid.cellX, grid.cellY, 1.0 };
  const double origin[3] = { 0.0, 0.0, 0.0 };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  outInfo->Set(vtkDataObject::SPACING(), spacing, 3);
  outInfo->Set(vtkDataObject::ORIGIN(), origin, 3);
  return 1;
}

int vtkTerrainSketchReader::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  try
  {
    this->UpdateProgress(0.0);
    const SketchGrid grid = sketchGrid(this->FileName, this->ExemplarFileName, this->CellSize);
    // Said here, when the sketch is read, not in RequestInformation: File > Open asks for the
    // information before the user has had a chance to give the exemplar.
    if (this->CellSize <= 0.0 &&
      (this->ExemplarFileName == nullptr || *this->ExemplarFileName == '\0'))
    {
      vtkWarningMacro("No ExemplarFileName: the sketch's pixels are 1 m; give the exemplar DEM "
                      "(or CellSize) to lay the sketch on the grid the synthesis makes of it.");
    }
    std::vector<std::string> warnings;
    const tsynth::SketchInput sketch = tsynth::readSketchInput(this->FileName, warnings);
    for (const auto& w : warnings)
    {
      vtkWarningMacro(<< w);
    }
    this->UpdateProgress(0.8);
    if (const auto* dem = std::get_if<tsynth::Heightfield>(&sketch))
    {
      tsynth::heightfieldToImage(*dem, output);
    }
    else
    {
      colourImageToImage(std::get<tsynth::ColourImage>(sketch), output);
    }
    output->SetSpacing(grid.cellX, grid.cellY, 1.0);
    output->SetOrigin(0.0, 0.0, 0.0);
    this->UpdateProgress(1.0);
  }
  catch (const std::bad_alloc&)
  {
    tsynth::reportRefusal(this, "Out of memory: give a smaller sketch.");
    output->Initialize();
    return 0;
  }
  catch (const std::exception& e)
  {
    tsynth::reportRefusal(this, e.what()); // once, not per request and representation
    output->Initialize();
    return 0;
  }
  return 1;
}

void vtkTerrainSketchReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent
     << "ExemplarFileName: " << (this->ExemplarFileName ? this->ExemplarFileName : "(none)")
     << "\n";
  os << indent << "CellSize: " << this->CellSize << "\n";
}
