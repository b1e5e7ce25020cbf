#include "TerrainImageConversion.h"

#include "Core/Error.h"

#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkStringArray.h>
#include <vtkUnsignedCharArray.h>

#include <cmath>
#include <limits>

namespace tsynth
{

void heightfieldToImage(const Heightfield& hf, vtkImageData* image)
{
  image->Initialize();
  image->SetExtent(0, hf.width - 1, 0, hf.height - 1, 0, 0);
  image->SetSpacing(hf.cellX, hf.cellY, 1.0);
  image->SetOrigin(0.0, 0.0, 0.0);

  vtkNew<vtkFloatArray> elevation;
  elevation->SetName(kElevationArray);
  elevation->SetNumberOfTuples(static_cast<vtkIdType>(hf.size()));
  std::copy(hf.z.begin(), hf.z.end(), elevation->GetPointer(0));
  image->GetPointData()->SetScalars(elevation);

  if (hf.hasMask())
  {
    vtkNew<vtkUnsignedCharArray> valid;
    valid->SetName(kValidArray);
    valid->SetNumberOfTuples(static_cast<vtkIdType>(hf.size()));
    std::copy(hf.valid.begin(), hf.valid.end(), valid->GetPointer(0));
    image->GetPointData()->AddArray(valid);
  }

  if (!hf.georef.crsWkt.empty())
  {
    vtkNew<vtkStringArray> crs;
    crs->SetName("CRS");
    crs->InsertNextValue(hf.georef.crsWkt);
    image->GetFieldData()->AddArray(crs);
  }
  if (hf.georef.hasGeoTransform)
  {
    vtkNew<vtkDoubleArray> gt;
    gt->SetName("GeoTransform");
    for (double v : hf.georef.geoTransform)
    {
      gt->InsertNextValue(v);
    }
    image->GetFieldData()->AddArray(gt);
  }
}

Heightfield imageToHeightfield(vtkImageData* image, vtkDataArray* heights)
{
  if (image == nullptr)
  {
    throw Error("No input image.");
  }
  int ext[6];
  image->GetExtent(ext);
  const int w = ext[1] - ext[0] + 1;
  const int h = ext[3] - ext[2] + 1;
  if (w <= 0 || h <= 0 || ext[5] != ext[4])
  {
    throw Error("The input must be a non-empty 2D image in the x-y plane.");
  }
  if (heights == nullptr)
  {
    heights = image->GetPointData()->GetArray(kElevationArray);
  }
  if (heights == nullptr)
  {
    heights = image->GetPointData()->GetScalars();
  }
  if (heights == nullptr || heights->GetNumberOfComponents() != 1)
  {
    throw Error("The input image has no single-component height array (\"Elevation\").");
  }
  if (heights->GetNumberOfTuples() != static_cast<vtkIdType>(w) * h)
  {
    throw Error("The height array does not match the image size.");
  }

  Heightfield hf(w, h);
  double spacing[3];
  image->GetSpacing(spacing);
  hf.cellX = std::abs(spacing[0]);
  hf.cellY = std::abs(spacing[1]);
  hf.cellSizeKnown = true;
  if (!(hf.cellX > 0.0) || !(hf.cellY > 0.0))
  {
    throw Error("The input image has a zero spacing; the cell size must be positive.");
  }
  for (vtkIdType k = 0; k < heights->GetNumberOfTuples(); ++k)
  {
    hf.z[static_cast<std::size_t>(k)] = static_cast<float>(heights->GetComponent(k, 0));
  }
  if (auto* valid = image->GetPointData()->GetArray(kValidArray))
  {
    if (valid->GetNumberOfTuples() == heights->GetNumberOfTuples())
    {
      hf.valid.resize(hf.size());
      for (vtkIdType k = 0; k < valid->GetNumberOfTuples(); ++k)
      {
        hf.valid[static_cast<std::size_t>(k)] = valid->GetComponent(k, 0) != 0.0 ? 1 : 0;
      }
    }
  }
  normaliseMask(hf);

  if (auto* crs = vtkStringArray::SafeDownCast(image->GetFieldData()->GetAbstractArray("CRS")))
  {
    if (crs->GetNumberOfValues() > 0)
    {
      hf.georef.crsWkt = crs->GetValue(0);
    }
  }
  if (auto* gt = image->GetFieldData()->GetArray("GeoTransform"))
  {
    if (gt->GetNumberOfTuples() * gt->GetNumberOfComponents() == 6)
    {
      for (int c = 0; c < 6; ++c)
      {
        hf.georef.geoTransform[static_cast<std::size_t>(c)] = gt->GetComponent(c, 0);
      }
      hf.georef.hasGeoTransform = true;
    }
  }
  return hf;
}

void gridOrigin(vtkImageData* image, double& x, double& y)
{
  double origin[3];
  double spacing[3];
  int extent[6];
  image->GetOrigin(origin);
  image->GetSpacing(spacing);
  image->GetExtent(extent);
  x = origin[0] + extent[0] * spacing[0];
  y = origin[1] + extent[2] * spacing[1];
}

void addPointArray(vtkImageData* image, const char* name, const float* values)
{
  vtkNew<vtkFloatArray> array;
  array->SetName(name);
  array->SetNumberOfTuples(image->GetNumberOfPoints());
  std::copy(values, values + image->GetNumberOfPoints(), array->GetPointer(0));
  image->GetPointData()->AddArray(array);
}

} // namespace tsynth
