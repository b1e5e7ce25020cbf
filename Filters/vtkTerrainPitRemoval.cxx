#include "vtkTerrainPitRemoval.h"

#include "PipelineRequests.h"
#include "PropertyEnums.h"
#include "TerrainImageConversion.h"

#include "Core/Error.h"
#include "Core/Memory.h"
#include "Hydrology/Flow.h"
#include "Hydrology/PitRemoval.h"

#include <vtkCharArray.h>
#include <vtkDataArray.h>
#include <vtkDataObject.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkTypeUInt32Array.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <cstdint>
#include <new>
#include <vector>

vtkStandardNewMacro(vtkTerrainPitRemoval);

namespace
{

constexpr int kSinksPort = 1;
constexpr int kSinksArrayIndex = 1; // SetInputArrayToProcess index of the sink array

template<typename ArrayType, typename Value>
void addArray(vtkImageData* image, const char* name, const std::vector<Value>& values)
{
  vtkNew<ArrayType> array;
  array->SetName(name);
  array->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  std::copy(values.begin(), values.end(), array->GetPointer(0));
  image->GetPointData()->AddArray(array);
}

} // namespace

vtkTerrainPitRemoval::vtkTerrainPitRemoval()
{
  this->SetNumberOfInputPorts(2);
  // The defaults of the options table (tsynth::pitRemovalOptionRows).
  const auto initial = [](const char* property)
  { return tsynth::optionRow(tsynth::pitRemovalOptionRows(), property).defaultValue; };
  this->Method = static_cast<int>(initial("Method"));
  this->MaxBreachDepth = initial("MaxBreachDepth");
  this->MaxBreachLength = static_cast<int>(initial("MaxBreachLength"));
  this->MemoryBudget = initial("MemoryBudget");
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, tsynth::kElevationArray);
  this->SetInputArrayToProcess(kSinksArrayIndex,
    kSinksPort,
    0,
    vtkDataObject::FIELD_ASSOCIATION_POINTS,
    vtkDataSetAttributes::SCALARS);
}

int vtkTerrainPitRemoval::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  if (port == kSinksPort)
  {
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  }
  return 1;
}

int vtkTerrainPitRemoval::RequestUpdateExtent(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector*)
{
  // The DEM and the sink mask are needed whole, whatever the mask's size (a
  // wrong size is then refused with its sizes in RequestData).
  tsynth::requestWholeExtents(inputVector, 2);
  return 1;
}

int vtkTerrainPitRemoval::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0], 0);
  vtkImageData* sinkImage = vtkImageData::GetData(inputVector[kSinksPort], 0);
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  if (input == nullptr || output == nullptr)
  {
    tsynth::reportRefusal(this, "Pit removal needs a heightfield image on its first input.");
    return 0;
  }
  return tsynth::runFilterRequest(
    this,
    "Out of memory removing pits: use a smaller DEM.",
    [&]
    {
      output->Initialize(); // aborted: empty outputs
    },
    [&]
    {
      const tsynth::Heightfield dem =
        tsynth::imageToHeightfield(input, this->GetInputArrayToProcess(0, inputVector));
      std::vector<std::uint8_t> sinks;
      tsynth::PitRemovalOptions options;
      options.method = tsynth::pitRemovalMethodFromProperty(this->Method);
      options.maxBreachDepth = this->MaxBreachDepth;
      options.maxBreachLength = this->MaxBreachLength;
      options.memoryBudget = this->MemoryBudget * tsynth::kBytesPerGB;
      options.memoryOption = "MemoryBudget";
      tsynth::checkDemToDrain(dem, options, true); // the flow arrays are always made
      if (sinkImage != nullptr)
      {
        const tsynth::Heightfield mask = tsynth::imageToHeightfield(sinkImage,
          tsynth::selectedArrayOn(this->GetInputArrayInformation(kSinksArrayIndex), sinkImage));
        sinks = tsynth::sinkMaskFromRaster(mask, dem.width, dem.height);
        options.sinks = &sinks;
      }
      this->UpdateProgress(0.1);
      const tsynth::PitRemovalResult result = tsynth::removePits(dem, options);
      this->UpdateProgress(0.6);
      const std::vector<std::int8_t> directions = tsynth::flowDirections(result.dem, options.sinks);
      const std::vector<std::uint32_t> accumulation = tsynth::flowAccumulation(
        directions, dem.width, dem.height, dem.hasMask() ? &dem.valid : nullptr);
      this->UpdateProgress(0.9);

      tsynth::copyAsPointGrid(input, dem, output);
      vtkPointData* points = output->GetPointData();
      points->RemoveArray(tsynth::kElevationArray);
      tsynth::addPointArray(output, tsynth::kElevationArray, result.dem.z.data());
      points->SetActiveScalars(tsynth::kElevationArray);
      addArray<vtkUnsignedCharArray>(output, "Changed", result.changed);
      addArray<vtkCharArray>(output, "FlowDirection", directions);
      addArray<vtkTypeUInt32Array>(output, "FlowAccumulation", accumulation);
      if (this->StreamThreshold > 0)
      {
        addArray<vtkUnsignedCharArray>(output,
          "Streams",
          tsynth::streamNetwork(accumulation, static_cast<std::uint32_t>(this->StreamThreshold)));
      }
    });
}

void vtkTerrainPitRemoval::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Method: "
     << tsynth::pitRemovalMethodName(tsynth::pitRemovalMethodFromProperty(this->Method)) << "\n";
  os << indent << "MaxBreachDepth: " << this->MaxBreachDepth << "\n";
  os << indent << "MaxBreachLength: " << this->MaxBreachLength << "\n";
  os << indent << "StreamThreshold: " << this->StreamThreshold << "\n";
  os << indent << "MemoryBudget: " << this->MemoryBudget << " GB\n";
}
