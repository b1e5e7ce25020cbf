#include "vtkTerrainCandidateBuilder.h"
#include "PipelineRequests.h"

#include "CandidatePoolTable.h"
#include "MatchingInputs.h"
#include "TerrainImageConversion.h"

#include "Core/Error.h"
#include "Matching/CandidatePool.h"

#include <vtkDataObject.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkTable.h>

vtkStandardNewMacro(vtkTerrainCandidateBuilder);

namespace
{
constexpr int kExemplarHeights = 0; // SetInputArrayToProcess index of the exemplars' heights
} // namespace

vtkTerrainCandidateBuilder::vtkTerrainCandidateBuilder()
{
  this->SetNumberOfInputPorts(2);
  this->SetInputArrayToProcess(
    kExemplarHeights, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, tsynth::kElevationArray);
}

int vtkTerrainCandidateBuilder::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_IS_REPEATABLE(), 1);
  if (port == 0)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
    return 1;
  }
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

int vtkTerrainCandidateBuilder::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkTable* table = vtkTable::GetData(outputVector, 0);
  return tsynth::runFilterRequest(
    this,
    "Out of memory: give a smaller input.",
    [&]
    {
      table->Initialize(); // aborted: empty outputs
    },
    [&]
    {
      tsynth::checkPatchSizeInRange(this->PatchSize, "Patch Size");
      const tsynth::ExemplarInputs in = tsynth::gatherExemplars(inputVector[0],
        inputVector[1],
        tsynth::exemplarHeightsNamed(
          this->GetInputArrayInformation(kExemplarHeights), inputVector[0]));
      this->UpdateProgress(0.3);
      tsynth::PoolOptions o;
      o.patchSize = this->PatchSize;
      const tsynth::CandidatePool pool =
        tsynth::buildCandidatePool(in.heightPointers(), in.graphPointers(), o);
      for (const auto& w : pool.warnings)
      {
        vtkWarningMacro(<< w);
      }
      this->UpdateProgress(0.9);
      tsynth::writePoolTable(pool, in, table);
    });
}

void vtkTerrainCandidateBuilder::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "PatchSize: " << this->PatchSize << "\n";
}
