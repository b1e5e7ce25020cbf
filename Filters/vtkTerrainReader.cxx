#include "vtkTerrainReader.h"

#include "PipelineRequests.h"
#include "TerrainFileIO.h"
#include "TerrainImageConversion.h"

#include "Core/Error.h"

#include <vtkDataObject.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <new>

vtkStandardNewMacro(vtkTerrainReader);

static_assert(vtkTerrainReader::ZUNIT_AUTO == static_cast<int>(tsynth::ZUnit::Auto) &&
    vtkTerrainReader::ZUNIT_METRES == static_cast<int>(tsynth::ZUnit::Metres) &&
    vtkTerrainReader::ZUNIT_FEET == static_cast<int>(tsynth::ZUnit::Feet),
  "the ZUnit property takes tsynth::ZUnit's values");

namespace
{

tsynth::ReadOptions optionsOf(int zUnit,
  double cellSize,
  bool useSidecar,
  bool normalised,
  double zMin,
  double zMax)
{
  tsynth::ReadOptions o;
  o.zUnit = tsynth::choiceOf<tsynth::ZUnit>(
    tsynth::optionRow(tsynth::readOptionRows(), "ZUnit").choices, zUnit, "ZUnit");
  o.cellX = cellSize;
  o.useSidecar = useSidecar;
  if (normalised)
  {
    o.zMin = zMin;
    o.zMax = zMax;
  }
  return o;
}

} // namespace

vtkTerrainReader::vtkTerrainReader()
{
  this->SetNumberOfInputPorts(0);
  this->SetNumberOfOutputPorts(1);
  const auto initial = [](const char* property)
  { return tsynth::optionRow(tsynth::readOptionRows(), property).defaultValue; };
  this->ZUnit = static_cast<int>(initial("ZUnit"));
  this->CellSize = initial("CellSize");
  this->UseSidecar = initial("UseSidecar") != 0.0;
  this->UseNormalisedRange = initial("UseNormalisedRange") != 0.0;
  this->ZMin = initial("ZMin");
  this->ZMax = initial("ZMax");
}

vtkTerrainReader::~vtkTerrainReader()
{
  this->SetFileName(nullptr);
}

int vtkTerrainReader::CanReadFile(const char* fileName)
{
  if (fileName == nullptr)
  {
    return 0;
  }
  try
  {
    if (tsynth::isVtiPath(fileName))
    {
      tsynth::readTerrainFile(fileName);
    }
    else
    {
      tsynth::readRasterInfo(fileName);
    }
    return 1;
  }
  catch (const std::exception&)
  {
    return 0;
  }
}

int vtkTerrainReader::RequestInformation(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  if (this->FileName == nullptr || *this->FileName == '\0')
  {
    tsynth::reportRefusal(this, "No file name: set FileName to a DEM file.");
    return 0;
  }
  int width = 0;
  int height = 0;
  double cell[2] = { 1.0, 1.0 };
  try
  {
    tsynth::requireFileForReader(this->FileName);
    const tsynth::ReadOptions options = optionsOf(this->ZUnit,
      this->CellSize,
      this->UseSidecar,
      this->UseNormalisedRange,
      this->ZMin,
      this->ZMax);
    tsynth::RasterInfo info;
    if (tsynth::isVtiPath(this->FileName))
    {
      tsynth::readTerrainFile(this->FileName, options, &info);
    }
    else
    {
      info = tsynth::readRasterInfo(this->FileName, options);
    }
    width = info.width;
    height = info.height;
    cell[0] = info.cellX;
    cell[1] = info.cellY;
  }
  catch (const std::bad_alloc&)
  {
    tsynth::reportRefusal(this, "Out of memory: give a smaller input.");
    return 0;
  }
  catch (const std::exception& e)
  {
    tsynth::reportRefusal(this, e.what()); // once, not per request and representation
    return 0;
  }
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  const int extent[6] = { 0, width - 1, 0, height - 1, 0, 0 };
  const double spacing[3] = { cell[0], cell[1], 1.0 };
  const double origin[3] = { 0.0, 0.0, 0.0 };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  outInfo->Set(vtkDataObject::SPACING(), spacing, 3);
  outInfo->Set(vtkDataObject::ORIGIN(), origin, 3);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_FLOAT, 1);
  return 1;
}

int vtkTerrainReader::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  try
  {
    this->UpdateProgress(0.0);
    tsynth::requireFileForReader(this->FileName);
    const tsynth::Heightfield hf = tsynth::readTerrainFile(this->FileName,
      optionsOf(this->ZUnit,
        this->CellSize,
        this->UseSidecar,
        this->UseNormalisedRange,
        this->ZMin,
        this->ZMax));
    this->UpdateProgress(0.8);
    tsynth::heightfieldToImage(hf, output);
    this->UpdateProgress(1.0);
  }
  catch (const std::bad_alloc&)
  {
    tsynth::reportRefusal(this, "Out of memory: give a smaller input.");
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

void vtkTerrainReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "ZUnit: " << this->ZUnit << "\n";
  os << indent << "CellSize: " << this->CellSize << "\n";
  os << indent << "UseSidecar: " << this->UseSidecar << "\n";
  os << indent << "UseNormalisedRange: " << this->UseNormalisedRange << "\n";
  os << indent << "ZMin: " << this->ZMin << "\n";
  os << indent << "ZMax: " << this->ZMax << "\n";
}
