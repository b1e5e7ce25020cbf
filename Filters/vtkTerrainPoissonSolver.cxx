#include "vtkTerrainPoissonSolver.h"

#include "PipelineRequests.h"
#include "TerrainImageConversion.h"

#include "Core/Error.h"
#include "Merging/Poisson.h"

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

vtkTerrainPoissonSolver::vtkTerrainPoissonSolver()
{
  this->SetNumberOfInputPorts(2);
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, tsynth::kElevationArray);
  this->SetInputArrayToProcess(
    1, 1, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, tsynth::kElevationArray);
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

int vtkTerrainPoissonSolver::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkImageData* destination = vtkImageData::GetData(inputVector[0], 0);
  vtkImageData* source = inputVector[1]->GetNumberOfInformationObjects() > 0
    ? vtkImageData::GetData(inputVector[1], 0)
    : nullptr;
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  try
  {
    const tsynth::Heightfield dst =
      tsynth::imageToHeightfield(destination, this->GetInputArrayToProcess(0, inputVector));
    const int w = dst.width;
    const int h = dst.height;
    const std::size_t n = dst.size();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    std::vector<double> gx(n, nan);
    std::vector<double> gy(n, nan);
    std::vector<std::uint8_t> unknown(n, 0);
    auto maskOf = [&](vtkImageData* image, std::vector<std::uint8_t>& mask)
    {
      if (vtkDataArray* m = image->GetPointData()->GetArray("Mask"))
      {
        for (std::size_t k = 0; k < n; ++k)
        {
          mask[k] = m->GetComponent(static_cast<vtkIdType>(k), 0) != 0.0 ? 1 : 0;
        }
        return true;
      }
      return false;
    };
    if (this->Mode == SEAMLESS_CLONE)
    {
      if (source == nullptr)
      {
        throw tsynth::Error("Seamless cloning needs a source heightfield on the second input.");
      }
      const tsynth::Heightfield src =
        tsynth::imageToHeightfield(source, this->GetInputArrayToProcess(1, inputVector));
      if (src.width != w || src.height != h)
      {
        throw tsynth::Error("The source must lie on the destination's grid (" + std::to_string(w) +
          " x " + std::to_string(h) + " cells); resample it first.");
      }
      if (!maskOf(source, unknown))
      {
        for (std::size_t k = 0; k < n; ++k)
        {
          unknown[k] = src.isValid(k) ? 1 : 0;
        }
      }
      for (int j = 0; j < h; ++j)
      {
        for (int i = 0; i < w; ++i)
        {
          const std::size_t k = dst.index(i, j);
          if (i + 1 < w && src.isValid(i, j) && src.isValid(i + 1, j))
          {
            gx[k] = static_cast<double>(src.at(i + 1, j)) - src.at(i, j);
          }
          if (j + 1 < h && src.isValid(i, j) && src.isValid(i, j + 1))
          {
            gy[k] = static_cast<double>(src.at(i, j + 1)) - src.at(i, j);
          }
        }
      }
    }
    else
    {
      vtkDataArray* g = destination->GetPointData()->GetArray("Gradient");
      if (g == nullptr || g->GetNumberOfComponents() != 2)
      {
        throw tsynth::Error(
          "The guidance field needs a two-component point array \"Gradient\" (dz/dx, dz/dy).");
      }
      if (!maskOf(destination, unknown))
      {
        throw tsynth::Error(
          "The guidance field needs a point array \"Mask\" marking the cells to solve.");
      }
      // Slopes at cells -> differences along edges (mean of the two ends).
      for (int j = 0; j < h; ++j)
      {
        for (int i = 0; i < w; ++i)
        {
          const std::size_t k = dst.index(i, j);
          if (i + 1 < w)
          {
            gx[k] = 0.5 *
              (g->GetComponent(static_cast<vtkIdType>(k), 0) +
                g->GetComponent(static_cast<vtkIdType>(dst.index(i + 1, j)), 0)) *
              dst.cellX;
          }
          if (j + 1 < h)
          {
            gy[k] = 0.5 *
              (g->GetComponent(static_cast<vtkIdType>(k), 1) +
                g->GetComponent(static_cast<vtkIdType>(dst.index(i, j + 1)), 1)) *
              dst.cellY;
          }
        }
      }
    }
    std::vector<double> u(n);
    std::size_t count = 0;
    for (std::size_t k = 0; k < n; ++k)
    {
      u[k] = dst.isValid(k) ? static_cast<double>(dst.z[k]) : nan;
      unknown[k] = unknown[k] != 0 && dst.isValid(k) ? 1 : 0;
      count += unknown[k];
    }
    if (count == 0)
    {
      vtkWarningMacro("The mask is empty: the destination is returned unchanged.");
    }
    this->UpdateProgress(0.1);
    tsynth::PoissonOptions options;
    options.tolerance = this->Tolerance;
    options.maxIterations = 200;
    tsynth::MaskedPoissonSolver solver;
    const tsynth::PoissonStatistics stats = count == 0
      ? tsynth::PoissonStatistics{}
      : solver.solveGuided(
          w, h, dst.cellX, dst.cellY, unknown.data(), gx.data(), gy.data(), u.data(), options);
    this->UpdateProgress(0.9);

    output->ShallowCopy(destination);
    vtkNew<vtkImageData> solved;
    tsynth::Heightfield result = dst;
    for (std::size_t k = 0; k < n; ++k)
    {
      if (unknown[k] != 0)
      {
        result.z[k] = static_cast<float>(u[k]);
      }
    }
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
  }
  catch (const tsynth::Error& e)
  {
    vtkErrorMacro(<< e.what());
    return 0;
  }
  return 1;
}

void vtkTerrainPoissonSolver::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Mode: " << this->Mode << "\n";
  os << indent << "Tolerance: " << this->Tolerance << "\n";
}
