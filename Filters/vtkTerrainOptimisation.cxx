#include "vtkTerrainOptimisation.h"

#include "PipelineRequests.h"
#include "PropertyEnums.h"
#include "SketchInputs.h"
#include "TerrainImageConversion.h"

#include "Core/Error.h"
#include "Core/Memory.h"
#include "Optimisation/OptimisationGuide.h"
#include "Optimisation/TerrainOptimisation.h"

#include <vtkDataObject.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <new>

vtkStandardNewMacro(vtkTerrainOptimisation);

namespace
{

constexpr int kSourcePort = 0;
constexpr int kGuidePort = 1;
// Share of the progress bar taken by the guide (the source's features for a sketch).
constexpr double kGuideProgress = 0.05;

tsynth::SetupOptionNames propertyNames()
{
  tsynth::SetupOptionNames names;
  names.size = "OutputSize";
  names.patch = "the guide's landform scale";
  return names;
}

tsynth::GridRequest gridRequest(const int* size)
{
  tsynth::GridRequest request;
  if (size[0] > 0 || size[1] > 0)
  {
    request.width = size[0];
    request.height = size[1];
  }
  return request;
}

// The properties as the kernel's options (progress and confidence come later).
tsynth::OptimisationOptions optimisationOptions(vtkTerrainOptimisation* f)
{
  tsynth::OptimisationOptions o;
  o.patchSize = f->GetPatchSize();
  o.levels = f->GetLevels();
  o.alpha = f->GetAlpha();
  o.iterationsPerLevel = f->GetIterationsPerLevel();
  o.patchMatchIterations = f->GetSearchIterations();
  o.rotations = f->GetRotations();
  o.reflections = f->GetReflections();
  const std::optional<tsynth::PitRemovalMethod> pits =
    tsynth::drainageFromProperty(f->GetPitRemoval());
  o.removePits = pits.has_value();
  o.pitRemoval.method = pits.value_or(tsynth::PitRemovalMethod::Breach);
  o.drainOutput = f->GetDrainOutput();
  o.seed = static_cast<std::uint64_t>(f->GetSeed());
  o.memoryBudget = f->GetMemoryBudget() * tsynth::kBytesPerGB;
  o.memoryOption = "MemoryBudget";
  o.sizeOption = "OutputSize";
  return o;
}

} // namespace

vtkTerrainOptimisation::vtkTerrainOptimisation()
{
  this->SetNumberOfInputPorts(2);
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, tsynth::kElevationArray);
  // The defaults of the options table (tsynth::optimisationOptionRows).
  const auto initial = [](const char* property)
  { return tsynth::optionRow(tsynth::optimisationOptionRows(), property).defaultValue; };
  this->PatchSize = static_cast<int>(initial("PatchSize"));
  this->Levels = static_cast<int>(initial("Levels"));
  this->Alpha = initial("Alpha");
  this->IterationsPerLevel = static_cast<int>(initial("IterationsPerLevel"));
  this->SearchIterations = static_cast<int>(initial("SearchIterations"));
  this->Rotations = initial("Rotations") != 0.0;
  this->Reflections = initial("Reflections") != 0.0;
  this->PitRemoval = static_cast<int>(initial("PitRemoval"));
  this->DrainOutput = initial("DrainOutput") != 0.0;
  this->OutputSize[0] = this->OutputSize[1] = static_cast<int>(initial("OutputSize"));
  this->Seed = static_cast<vtkIdType>(initial("Seed"));
  this->MemoryBudget = initial("MemoryBudget");
}

int vtkTerrainOptimisation::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == kSourcePort)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
    return 1;
  }
  info->Remove(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE());
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

int vtkTerrainOptimisation::RequestInformation(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkInformation* out = outputVector->GetInformationObject(0);
  vtkInformation* source = inputVector[kSourcePort]->GetInformationObject(0);
  if (tsynth::anyImageProducerFailed(inputVector, this->GetNumberOfInputPorts()))
  {
    out->Remove(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT());
    return 0; // the reader that failed said why
  }
  try
  {
    double spacing[3] = { 0.0, 0.0, 0.0 };
    if (source != nullptr && source->Has(vtkDataObject::SPACING()))
    {
      source->Get(vtkDataObject::SPACING(), spacing);
    }
    const tsynth::SketchExtent extent =
      tsynth::announcedSketchExtent(this, kGuidePort, inputVector[kGuidePort]);
    const tsynth::OutputGrid grid = tsynth::outputGrid(extent,
      gridRequest(this->OutputSize),
      spacing[0],
      spacing[1],
      tsynth::kGuideLandformScale,
      propertyNames());
    const int wholeExtent[6] = { 0, grid.width - 1, 0, grid.height - 1, 0, 0 };
    const double origin[3] = { 0.0, 0.0, 0.0 };
    out->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), wholeExtent, 6);
    out->Set(vtkDataObject::SPACING(), grid.cellX, grid.cellY, 1.0);
    out->Set(vtkDataObject::ORIGIN(), origin, 3);
  }
  catch (const std::exception& e)
  {
    out->Remove(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT());
    tsynth::reportRefusal(this, e.what()); // once, not again in RequestData or the next update
    return 0;
  }
  return 1;
}

int vtkTerrainOptimisation::RequestUpdateExtent(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector*)
{
  tsynth::requestWholeExtents(inputVector, 2); // source and guide are needed whole
  return 1;
}

int vtkTerrainOptimisation::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkImageData* source = vtkImageData::GetData(inputVector[kSourcePort], 0);
  vtkDataObject* guideData = vtkDataObject::GetData(inputVector[kGuidePort], 0);
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  if (source == nullptr || guideData == nullptr || output == nullptr)
  {
    tsynth::reportRefusal(this, "Connect a source DEM and a guide.");
    return 0;
  }
  if (tsynth::anyImageProducerFailed(inputVector, this->GetNumberOfInputPorts()))
  {
    output->Initialize();
    return 0; // ParaView asks for the data even after RequestInformation failed
  }
  return tsynth::runFilterRequest(
    this,
    "Out of memory optimising the terrain: use a smaller OutputSize.",
    [&] { output->Initialize(); },
    [&]
    {
      const tsynth::Heightfield dem =
        tsynth::imageToHeightfield(source, this->GetInputArrayToProcess(0, inputVector));
      std::vector<std::string> warnings;
      const tsynth::SketchInput sketch = tsynth::sketchInput(guideData, warnings);
      tsynth::OptimisationOptions o = optimisationOptions(this);
      const tsynth::OptimisationGuide guide = tsynth::buildOptimisationGuide(
        dem, sketch, gridRequest(this->OutputSize), o, propertyNames());
      for (const std::string& w : guide.warnings)
      {
        vtkWarningMacro(<< w);
      }
      this->UpdateProgress(kGuideProgress);
      o.guideConfidence = guide.confidence;
      o.progress = [this](double f, const std::string&)
      { this->UpdateProgress(kGuideProgress + (1.0 - kGuideProgress) * f); };
      const tsynth::OptimisationResult r = tsynth::optimiseTerrain(dem, guide.field, o);
      tsynth::heightfieldToImage(r.terrain, output);
    });
}

void vtkTerrainOptimisation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "PatchSize: " << this->PatchSize << "\n";
  os << indent << "Levels: " << this->Levels << "\n";
  os << indent << "Alpha: " << this->Alpha << "\n";
  os << indent << "IterationsPerLevel: " << this->IterationsPerLevel << "\n";
  os << indent << "SearchIterations: " << this->SearchIterations << "\n";
  os << indent << "Rotations: " << this->Rotations << "\n";
  os << indent << "Reflections: " << this->Reflections << "\n";
  os << indent << "PitRemoval: " << this->PitRemoval << "\n";
  os << indent << "DrainOutput: " << this->DrainOutput << "\n";
  os << indent << "OutputSize: " << this->OutputSize[0] << " " << this->OutputSize[1] << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "MemoryBudget: " << this->MemoryBudget << " GB\n";
}
