#include "vtkTerrainPoissonSolver.h"

#include "PipelineRequests.h"
#include "TerrainImageConversion.h"

#include "Core/Error.h"
#include "Merging/Poisson.h"
#include "Merging/PoissonEditing.h"

#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <cmath>
#include <limits>

vtkStandardNewMacro(vtkTerrainPoissonSolver);

static_assert(vtkTerrainPoissonSolver::SEAMLESS_CLONE ==
      static_cast<int>(tsynth::PoissonEditMode::SeamlessClone) &&
    vtkTerrainPoissonSolver::GUIDANCE_FIELD ==
      static_cast<int>(tsynth::PoissonEditMode::GuidanceField),
  "the Mode property takes tsynth::PoissonEditMode's values");

vtkTerrainPoissonSolver::vtkTerrainPoissonSolver()
{
  this->SetMaskArray(kDefaultMaskArray);
  this->SetGradientArray(kDefaultGradientArray);
  this->SetNumberOfInputPorts(2);
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, tsynth::kElevationArray);
  this->SetInputArrayToProcess(
    1, 1, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, tsynth::kElevationArray);
  const auto initial = [](const char* property)
  { return tsynth::optionRow(tsynth::poissonEditOptionRows(), property).defaultValue; };
  this->Mode = static_cast<int>(initial("Mode"));
  this->Tolerance = initial("Tolerance");
}

vtkTerrainPoissonSolver::~vtkTerrainPoissonSolver()
{
  this->SetMaskArray(nullptr);
  this->SetGradientArray(nullptr);
}

int vtkTerrainPoissonSolver::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  if (port == 1)
  {
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  }
  return 1;
}

int vtkTerrainPoissonSolver::RequestInformation(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  // The output lies on the first input's grid, whatever the second input's size.
  tsynth::copyGrid(inputVector[0]->GetInformationObject(0), outputVector->GetInformationObject(0));
  return 1;
}

int vtkTerrainPoissonSolver::RequestUpdateExtent(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector*)
{
  tsynth::requestWholeExtents(inputVector, 2);
  return 1;
}

namespace
{

// The chosen mask array as one byte per point, non-zero where it is non-zero (empty if the
// image has none).
std::vector<std::uint8_t> maskArray(vtkImageData* image, const char* name)
{
  vtkDataArray* m =
    tsynth::chosenPointArray(image, name, vtkTerrainPoissonSolver::kDefaultMaskArray);
  if (m == nullptr)
  {
    return {};
  }
  std::vector<std::uint8_t> mask(static_cast<std::size_t>(m->GetNumberOfTuples()));
  for (std::size_t k = 0; k < mask.size(); ++k)
  {
    tsynth::pollCancellation(); // a whole terrain's copy takes a good part of a second
    mask[k] = m->GetComponent(static_cast<vtkIdType>(k), 0) != 0.0 ? 1 : 0;
  }
  return mask;
}

// The chosen two-component gradient array (dz/dx, dz/dy). Throws tsynth::Error if it is
// missing, has another number of components, or its length is not the image's point count.
void gradientArray(vtkImageData* image,
  const char* name,
  std::vector<double>& slopeX,
  std::vector<double>& slopeY)
{
  constexpr int kSlopeComponents = 2; // dz/dx and dz/dy
  vtkDataArray* g = tsynth::chosenPointArray(
    image, name, vtkTerrainPoissonSolver::kDefaultGradientArray, kSlopeComponents);
  if (g == nullptr)
  {
    throw tsynth::Error("The guidance field needs a two-component point array of slopes "
                        "(dz/dx, dz/dy): name it in GradientArray.");
  }
  slopeX.resize(static_cast<std::size_t>(g->GetNumberOfTuples()));
  slopeY.resize(slopeX.size());
  for (std::size_t k = 0; k < slopeX.size(); ++k)
  {
    tsynth::pollCancellation();
    slopeX[k] = g->GetComponent(static_cast<vtkIdType>(k), 0);
    slopeY[k] = g->GetComponent(static_cast<vtkIdType>(k), 1);
  }
}

} // namespace

int vtkTerrainPoissonSolver::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkImageData* destination = vtkImageData::GetData(inputVector[0], 0);
  vtkImageData* source = inputVector[1]->GetNumberOfInformationObjects() > 0
    ? vtkImageData::GetData(inputVector[1], 0)
    : nullptr;
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  return tsynth::runFilterRequest(
    this,
    "Out of memory: give a smaller input.",
    [&]
    {
      output->Initialize(); // aborted: empty outputs
    },
    [&]
    {
      const tsynth::Heightfield dst =
        tsynth::imageToHeightfield(destination, this->GetInputArrayToProcess(0, inputVector));
      this->UpdateProgress(0.1);
      tsynth::PoissonEditResult r;
      if (this->Mode == SEAMLESS_CLONE)
      {
        if (source == nullptr)
        {
          throw tsynth::Error("Seamless cloning needs a source heightfield on the second input.");
        }
        const std::vector<std::uint8_t> mask = maskArray(source, this->MaskArray);
        r = tsynth::seamlessClone(dst,
          tsynth::imageToHeightfield(
            source, tsynth::selectedArrayOn(this->GetInputArrayInformation(1), source)),
          mask.empty() ? nullptr : &mask,
          this->Tolerance);
      }
      else
      {
        const std::vector<std::uint8_t> mask = maskArray(destination, this->MaskArray);
        if (mask.empty())
        {
          throw tsynth::Error("The guidance field needs a point array marking the cells to solve: "
                              "name it in MaskArray.");
        }
        std::vector<double> slopeX;
        std::vector<double> slopeY;
        gradientArray(destination, this->GradientArray, slopeX, slopeY);
        r = tsynth::integrateSlopes(dst, slopeX, slopeY, mask, this->Tolerance);
      }
      if (r.solvedCells == 0)
      {
        vtkWarningMacro("The mask is empty: the destination is returned unchanged.");
      }
      this->UpdateProgress(0.9);
      const tsynth::PoissonStatistics stats = r.statistics;
      const tsynth::Heightfield& result = r.terrain;

      output->ShallowCopy(destination);
      vtkNew<vtkImageData> solved;
      tsynth::heightfieldToImage(result, solved);
      output->GetPointData()->AddArray(solved->GetPointData()->GetArray(tsynth::kElevationArray));
      output->GetPointData()->SetActiveScalars(tsynth::kElevationArray);
      vtkNew<vtkDoubleArray> iterations;
      iterations->SetName("Iterations");
      iterations->InsertNextValue(stats.iterations);
      output->GetFieldData()->AddArray(iterations);
      vtkNew<vtkDoubleArray> residual;
      residual->SetName("RelativeResidual");
      residual->InsertNextValue(
        stats.initialResidual > 0 ? stats.finalResidual / stats.initialResidual : 0.0);
      output->GetFieldData()->AddArray(residual);
    });
}

void vtkTerrainPoissonSolver::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Mode: " << this->Mode << "\n";
  os << indent << "Tolerance: " << this->Tolerance << "\n";
  os << indent << "MaskArray: " << (this->MaskArray ? this->MaskArray : "(none)") << "\n";
  os << indent << "GradientArray: " << (this->GradientArray ? this->GradientArray : "(none)")
     << "\n";
}
