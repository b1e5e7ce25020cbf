#include "SketchInputs.h"

#include "FeatureGraphConversion.h"
#include "TerrainImageConversion.h"

#include "Core/Error.h"

#include <vtkAlgorithm.h>
#include <vtkAlgorithmOutput.h>
#include <vtkDataArray.h>
#include <vtkDataObject.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkStreamingDemandDrivenPipeline.h>

namespace tsynth
{
namespace
{

bool isDemImage(vtkImageData* image)
{
  vtkDataArray* scalars = pixelValues(image);
  return scalars != nullptr &&
    rasterIsDemTarget(
      scalars->GetNumberOfComponents(), scalars->GetDataType() == VTK_UNSIGNED_CHAR);
}

} // namespace

SketchInput sketchInput(vtkDataObject* data, std::vector<std::string>& warnings)
{
  if (auto* image = vtkImageData::SafeDownCast(data))
  {
    if (isDemImage(image))
    {
      return imageToHeightfield(image);
    }
    return imageToColourImage(image);
  }
  if (auto* lines = vtkPolyData::SafeDownCast(data))
  {
    std::string warning;
    PolylineSketch sketch = polyDataToPolylineSketch(lines, &warning);
    if (!warning.empty())
    {
      warnings.push_back(warning);
    }
    return sketch;
  }
  throw Error("The sketch must be an image or poly-lines.");
}

SketchExtent announcedSketchExtent(vtkAlgorithm* filter, int port, vtkInformationVector* portInfo)
{
  vtkInformation* info = portInfo->GetInformationObject(0);
  if (info == nullptr)
  {
    return {};
  }
  if (vtkPolyData::SafeDownCast(info->Get(vtkDataObject::DATA_OBJECT())) != nullptr)
  {
    // A poly-data producer announces no extent: the lines themselves say how far
    // the output reaches, so they are brought up to date before it is announced.
    vtkAlgorithmOutput* connection = filter->GetInputConnection(port, 0);
    connection->GetProducer()->Update(connection->GetIndex());
    auto* lines = vtkPolyData::SafeDownCast(info->Get(vtkDataObject::DATA_OBJECT()));
    return polylineExtent(polyDataToPolylineSketch(lines));
  }
  if (info->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    int e[6];
    info->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), e);
    return rasterExtent(e[1] - e[0] + 1, e[3] - e[2] + 1);
  }
  return {};
}

} // namespace tsynth
