#include "vtkTerrainGraphCutMerger.h"

#include "PipelineRequests.h"
#include "PropertyEnums.h"
#include "TerrainImageConversion.h"

#include "Core/Error.h"
#include "Merging/PatchMerger.h"

#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkUnsignedCharArray.h>

#include <new>
#include <sstream>
#include <utility>
#include <vector>

#include <cmath>

vtkStandardNewMacro(vtkTerrainGraphCutMerger);

vtkTerrainGraphCutMerger::vtkTerrainGraphCutMerger()
{
  this->SetNumberOfInputPorts(2);
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, tsynth::kElevationArray);
  this->SetInputArrayToProcess(
    1, 1, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, tsynth::kElevationArray);
  const tsynth::OptionRow& mode = tsynth::optionRow(tsynth::mergeOptionRows(), "Mode");
  this->Mode = static_cast<int>(mode.defaultValue);
  this->ShepardRadius = tsynth::optionRow(tsynth::mergeOptionRows(), "ShepardRadius").defaultValue;
}

int vtkTerrainGraphCutMerger::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

int vtkTerrainGraphCutMerger::RequestInformation(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  // The output lies on the first input's grid, whatever the second input's size.
  tsynth::copyGrid(inputVector[0]->GetInformationObject(0), outputVector->GetInformationObject(0));
  return 1;
}

int vtkTerrainGraphCutMerger::RequestUpdateExtent(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector*)
{
  tsynth::requestWholeExtents(inputVector, 2);
  return 1;
}

namespace
{

// Beyond this many cells from the terrain no patch overlaps it (and the cell
// would not fit an int).
constexpr double kFarthestCell = 1.0e9;

// The terrain cell the patch's first cell lies on, from the two images'
// origins. Throws tsynth::Error for a patch too far away to overlap.
std::pair<int, int> patchCellAtOrigin(vtkImageData* terrainImage,
  vtkImageData* patchImage,
  const tsynth::Heightfield& terrain)
{
  double tx = 0.0;
  double ty = 0.0;
  double px = 0.0;
  double py = 0.0;
  tsynth::gridOrigin(terrainImage, tx, ty);
  tsynth::gridOrigin(patchImage, px, py);
  const double cx = (px - tx) / terrain.cellX;
  const double cy = (py - ty) / terrain.cellY;
  if (!(std::abs(cx) < kFarthestCell && std::abs(cy) < kFarthestCell))
  {
    std::ostringstream where;
    where << cx << ", " << cy;
    throw tsynth::Error("The patch's origin lies " + where.str() +
      " cells from the terrain's: it cannot overlap it.");
  }
  return { static_cast<int>(std::lround(cx)), static_cast<int>(std::lround(cy)) };
}

// The seam's cells (SeamMask) and which patch each cell now shows (PatchId:
// the terrain's own ids, patchIdValue where the patch was taken).
void addSeamAndPatchIds(vtkImageData* output,
  vtkImageData* terrainImage,
  const tsynth::Heightfield& terrain,
  const tsynth::MergeResult& r,
  int patchIdValue)
{
  const vtkIdType n = static_cast<vtkIdType>(terrain.size());
  vtkNew<vtkUnsignedCharArray> seam;
  seam->SetName("SeamMask");
  seam->SetNumberOfTuples(n);
  seam->Fill(0);
  vtkNew<vtkIntArray> patchId;
  patchId->SetName("PatchId");
  patchId->SetNumberOfTuples(n);
  patchId->Fill(0);
  if (vtkDataArray* previous = terrainImage->GetPointData()->GetArray("PatchId"))
  {
    for (vtkIdType k = 0; k < n && k < previous->GetNumberOfTuples(); ++k)
    {
      patchId->SetValue(k, static_cast<int>(previous->GetComponent(k, 0)));
    }
  }
  for (int j = 0; j < r.height; ++j)
  {
    for (int i = 0; i < r.width; ++i)
    {
      const std::size_t w = static_cast<std::size_t>(j * r.width + i);
      const vtkIdType k = static_cast<vtkIdType>(terrain.index(r.x0 + i, r.y0 + j));
      if (r.seam[w] != 0)
      {
        seam->SetValue(k, 1);
      }
      if (r.takeNew[w] != 0)
      {
        patchId->SetValue(k, patchIdValue);
      }
    }
  }
  output->GetPointData()->AddArray(seam);
  output->GetPointData()->AddArray(patchId);
}

// The merged terrain on the input terrain's grid: its heights and validity,
// the filled cells, the seam and patch ids, and the cut's figures as field data.
void writeMergedTerrain(vtkImageData* output,
  vtkImageData* terrainImage,
  const tsynth::Heightfield& terrain,
  const std::vector<std::uint8_t>& filled,
  const tsynth::MergeResult& r,
  int patchIdValue)
{
  output->CopyStructure(terrainImage);
  output->GetFieldData()->PassData(terrainImage->GetFieldData());
  vtkNew<vtkImageData> converted;
  tsynth::heightfieldToImage(terrain, converted);
  output->GetPointData()->AddArray(converted->GetPointData()->GetArray(tsynth::kElevationArray));
  output->GetPointData()->SetActiveScalars(tsynth::kElevationArray);
  if (vtkDataArray* valid = converted->GetPointData()->GetArray(tsynth::kValidArray))
  {
    output->GetPointData()->AddArray(valid);
  }
  vtkNew<vtkUnsignedCharArray> filledArray;
  filledArray->SetName("Filled");
  filledArray->SetNumberOfTuples(static_cast<vtkIdType>(terrain.size()));
  std::copy(filled.begin(), filled.end(), filledArray->GetPointer(0));
  output->GetPointData()->AddArray(filledArray);
  addSeamAndPatchIds(output, terrainImage, terrain, r, patchIdValue);
  auto fieldValue = [&](const char* name, double v)
  {
    vtkNew<vtkDoubleArray> a;
    a->SetName(name);
    a->InsertNextValue(v);
    output->GetFieldData()->AddArray(a);
  };
  fieldValue("CutCost", r.cutCost);
  fieldValue("CutEdges", r.cutEdges);
  fieldValue("NormalisedCutCost", r.normalisedCost);
}

} // namespace

int vtkTerrainGraphCutMerger::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkImageData* terrainImage = vtkImageData::GetData(inputVector[0], 0);
  vtkImageData* patchImage = vtkImageData::GetData(inputVector[1], 0);
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  if (patchImage == nullptr)
  {
    tsynth::reportRefusal(this, "No patch: connect the patch image to the second input.");
    return 0;
  }
  return tsynth::runFilterRequest(
    this,
    "Out of memory: give a smaller input.",
    [&] { output->Initialize(); },
    [&]
    {
      tsynth::Heightfield terrain =
        tsynth::imageToHeightfield(terrainImage, this->GetInputArrayToProcess(0, inputVector));
      const tsynth::Heightfield patch = tsynth::imageToHeightfield(
        patchImage, tsynth::selectedArrayOn(this->GetInputArrayInformation(1), patchImage));
      std::vector<std::uint8_t> filled = tsynth::filledCells(terrainImage, terrain);
      const std::vector<std::uint8_t> core = tsynth::pointFlags(patchImage, "Core", 0);
      const auto [x0, y0] = this->UsePatchOrigin
        ? patchCellAtOrigin(terrainImage, patchImage, terrain)
        : std::pair<int, int>(this->PatchCell[0], this->PatchCell[1]);
      tsynth::MergeOptions options;
      options.mode = tsynth::mergeModeFromProperty(this->Mode);
      options.shepardRadius = this->ShepardRadius;
      this->UpdateProgress(0.2);
      tsynth::PatchMerger merger;
      const tsynth::MergeResult r = merger.merge(terrain, filled, patch, x0, y0, &core, options);
      this->UpdateProgress(0.9);

      writeMergedTerrain(output, terrainImage, terrain, filled, r, this->PatchIdValue);
    });
}

void vtkTerrainGraphCutMerger::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Mode: " << this->Mode << "\n";
  os << indent << "UsePatchOrigin: " << this->UsePatchOrigin << "\n";
  os << indent << "PatchCell: " << this->PatchCell[0] << ", " << this->PatchCell[1] << "\n";
  os << indent << "ShepardRadius: " << this->ShepardRadius << "\n";
  os << indent << "PatchIdValue: " << this->PatchIdValue << "\n";
}
