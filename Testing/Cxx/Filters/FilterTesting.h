// What the filters' C++ tests share: heightfields as ParaView images, a
// filter's error sentences, point arrays as vectors, and a small rough DEM
// with pits and nodata. The filters run here as a pvpython script runs them,
// but inside the sanitized build (which skips pvpython).
#pragma once

#include "TerrainImageConversion.h"

#include "Core/Heightfield.h"

#include <vtkAlgorithm.h>
#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace tsynth::test
{

// `hf` as the Terrain Reader gives it: "Elevation", "Valid" where some cells are nodata.
inline vtkSmartPointer<vtkImageData> imageOf(const Heightfield& hf)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  heightfieldToImage(hf, image);
  return image;
}

// Every error sentence a filter reports, in order (empty: none).
struct FilterErrors
{
  std::string text;
  vtkNew<vtkCallbackCommand> callback;
  explicit FilterErrors(vtkAlgorithm* filter)
  {
    callback->SetClientData(this);
    callback->SetCallback([](vtkObject*, unsigned long, void* self, void* message)
      { static_cast<FilterErrors*>(self)->text += static_cast<const char*>(message); });
    filter->AddObserver(vtkCommand::ErrorEvent, callback);
  }
};

// A point array's first components as doubles (empty if there is no such array).
inline std::vector<double> pointValues(vtkImageData* image, const char* name)
{
  std::vector<double> values;
  vtkDataArray* a = image->GetPointData()->GetArray(name);
  if (a == nullptr)
  {
    return values;
  }
  values.resize(static_cast<std::size_t>(a->GetNumberOfTuples()));
  for (vtkIdType k = 0; k < a->GetNumberOfTuples(); ++k)
  {
    values[static_cast<std::size_t>(k)] = a->GetComponent(k, 0);
  }
  return values;
}

// The same values as doubles, for comparing a kernel's result with a filter's array.
template<class T>
std::vector<double> asDoubles(const std::vector<T>& values)
{
  return std::vector<double>(values.begin(), values.end());
}

// A rough width x height DEM of 30 m cells, 1000-1400 m: ridges and hollows
// from a few sines, cut with closed hollows (pits) every few cells, and a
// block of nodata when `withNodata`. The same every time.
inline Heightfield roughDem(int width, int height, bool withNodata)
{
  Heightfield dem(width, height);
  dem.cellX = dem.cellY = 30.0;
  dem.cellSizeKnown = true;
  for (int j = 0; j < height; ++j)
  {
    for (int i = 0; i < width; ++i)
    {
      const double x = i * 0.21, y = j * 0.17;
      const double hollows = ((i * 7 + j * 13) % 11 == 0) ? -25.0 : 0.0;
      dem.at(i, j) = static_cast<float>(1200.0 + 120.0 * std::sin(x) * std::cos(y) +
        60.0 * std::sin(0.5 * x + 1.3 * y) + 8.0 * std::sin(3.1 * x - 2.3 * y) + hollows);
    }
  }
  if (withNodata)
  {
    dem.valid.assign(dem.size(), 1);
    for (int j = height / 3; j < height / 3 + 5; ++j)
    {
      for (int i = width / 2; i < width / 2 + 6; ++i)
      {
        dem.valid[dem.index(i, j)] = 0;
        dem.at(i, j) = std::nanf("");
      }
    }
  }
  return dem;
}

} // namespace tsynth::test
