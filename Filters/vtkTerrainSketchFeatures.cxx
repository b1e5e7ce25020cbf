#include "vtkTerrainSketchFeatures.h"
#include "PipelineRequests.h"

#include "FeatureGraphConversion.h"
#include "TerrainImageConversion.h"

#include "Core/Error.h"
#include "Features/Sketch.h"

#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <new>

#include <algorithm>
#include <cmath>

vtkStandardNewMacro(vtkTerrainSketchFeatures);

vtkTerrainSketchFeatures::vtkTerrainSketchFeatures()
{
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(2);
  const auto initial = [](const char* property)
  { return tsynth::optionRow(tsynth::sketchOptionRows(), property).defaultValue; };
  this->PatchSize = static_cast<int>(initial("PatchSize"));
  this->ControlRadius = initial("ControlRadius");
  this->CellSize = initial("CellSize");
  this->SnapTolerance = initial("SnapTolerance");
  this->SmoothingPasses = static_cast<int>(initial("SmoothingPasses"));
}

int vtkTerrainSketchFeatures::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == 0)
  {
    info->Remove(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE());
    info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
    info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
    return 1;
  }
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

int vtkTerrainSketchFeatures::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkDataObject* input = vtkDataObject::GetData(inputVector[0], 0);
  vtkImageData* reference = inputVector[1]->GetNumberOfInformationObjects() > 0
    ? vtkImageData::GetData(inputVector[1], 0)
    : nullptr;
  vtkPolyData* tree = vtkPolyData::GetData(outputVector, 0);
  vtkPolyData* controls = vtkPolyData::GetData(outputVector, 1);
  const double radius = this->ControlRadius > 0.0 ? this->ControlRadius : 0.5 * this->PatchSize;
  return tsynth::runFilterRequest(
    this,
    "Out of memory: give a smaller input.",
    [&]
    {
      tree->Initialize();
      controls->Initialize(); // aborted: empty outputs
    },
    [&]
    {
      tsynth::checkPatchSize(this->PatchSize, "Patch Size");
      tsynth::FeatureGraph graph;
      double ox = 0.0;
      double oy = 0.0;
      if (auto* image = vtkImageData::SafeDownCast(input))
      {
        double spacing[3];
        image->GetSpacing(spacing);
        tsynth::SketchOptions o;
        o.patchSize = this->PatchSize;
        o.controlRadius = radius;
        o.smoothingPasses = this->SmoothingPasses;
        o.cellSize = this->CellSize > 0.0 ? this->CellSize : spacing[0];
        tsynth::SketchFeatures s = tsynth::sketchFeatures(tsynth::imageToColourImage(image), o);
        for (const auto& w : s.warnings)
        {
          vtkWarningMacro(<< w);
        }
        graph = std::move(s.graph);
        tsynth::gridOrigin(image, ox, oy);
      }
      else if (auto* lines = vtkPolyData::SafeDownCast(input))
      {
        double cx = this->CellSize > 0.0 ? this->CellSize : 1.0;
        double cy = cx;
        int width = 0;
        int height = 0;
        if (reference != nullptr)
        {
          double spacing[3];
          int dims[3];
          reference->GetSpacing(spacing);
          reference->GetDimensions(dims);
          cx = spacing[0];
          cy = spacing[1];
          tsynth::gridOrigin(reference, ox, oy);
          width = dims[0];
          height = dims[1];
        }
        else
        {
          double bounds[6];
          lines->GetBounds(bounds);
          width = static_cast<int>(std::ceil(std::max(0.0, bounds[1]) / cx)) + 1;
          height = static_cast<int>(std::ceil(std::max(0.0, bounds[3]) / cy)) + 1;
        }
        std::string warning;
        const auto polylines = tsynth::polyDataToPolylines(lines, cx, cy, ox, oy, &warning);
        if (!warning.empty())
        {
          vtkWarningMacro(<< warning);
        }
        if (polylines.empty())
        {
          vtkWarningMacro("The input has no poly-lines: the feature tree is empty.");
        }
        graph =
          tsynth::polylineFeatures(polylines, width, height, cx, cy, this->SnapTolerance, radius);
      }
      else
      {
        throw tsynth::Error("The sketch must be an image or poly-lines.");
      }
      tsynth::featureGraphToPolyData(graph, tree, ox, oy);
      tsynth::controlPointsToPolyData(graph, controls, ox, oy);
    });
}

void vtkTerrainSketchFeatures::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "PatchSize: " << this->PatchSize << "\n";
  os << indent << "ControlRadius: " << this->ControlRadius << "\n";
  os << indent << "CellSize: " << this->CellSize << "\n";
  os << indent << "SnapTolerance: " << this->SnapTolerance << "\n";
  os << indent << "SmoothingPasses: " << this->SmoothingPasses << "\n";
}
