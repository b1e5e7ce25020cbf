#include "TerrainImageConversion.h"

#include "Core/Cancellation.h"
#include "Core/Error.h"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDataSetAttributes.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkStringArray.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

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

namespace
{

// A single-band image read by a reader other than ours (ParaView's GDAL Raster Reader) holds its
// heights on cells, one per pixel: the active cell scalars or a cell array "Elevation".
vtkDataArray* cellHeights(vtkImageData* image)
{
  vtkCellData* cells = image->GetCellData();
  vtkDataArray* heights = cells->GetArray(kElevationArray);
  if (heights == nullptr)
  {
    heights = cells->GetScalars();
  }
  const bool usable = heights != nullptr && heights->GetNumberOfComponents() == 1 &&
    heights->GetNumberOfTuples() == image->GetNumberOfCells() && image->GetNumberOfCells() > 0;
  return usable ? heights : nullptr;
}

vtkDataArray* pointHeights(vtkImageData* image)
{
  vtkDataArray* heights = image->GetPointData()->GetArray(kElevationArray);
  return heights != nullptr ? heights : image->GetPointData()->GetScalars();
}

// Cells the reader marked as nodata: hidden by its ghost array, or holding the NO_DATA_VALUE
// it records in the field data (GDAL's).
void maskReaderNodata(vtkImageData* image, Heightfield& hf)
{
  const auto* ghosts = vtkUnsignedCharArray::SafeDownCast(
    image->GetCellData()->GetArray(vtkDataSetAttributes::GhostArrayName()));
  vtkDataArray* nodata = image->GetFieldData()->GetArray("NO_DATA_VALUE");
  const bool hasNodata = nodata != nullptr && nodata->GetNumberOfTuples() > 0;
  const double nodataValue = hasNodata ? nodata->GetComponent(0, 0) : 0.0;
  for (std::size_t k = 0; k < hf.size(); ++k)
  {
    const bool hidden = ghosts != nullptr &&
      (ghosts->GetValue(static_cast<vtkIdType>(k)) & vtkDataSetAttributes::HIDDENCELL) != 0;
    if (hidden || (hasNodata && static_cast<double>(hf.z[k]) == nodataValue))
    {
      hf.z[k] = std::numeric_limits<float>::quiet_NaN();
    }
  }
}

} // namespace

vtkDataArray* pixelValues(vtkImageData* image)
{
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  if (scalars == nullptr)
  {
    scalars = image->GetPointData()->GetArray(0);
  }
  if (scalars == nullptr && image->GetNumberOfCells() > 0)
  {
    vtkDataArray* cells = image->GetCellData()->GetScalars();
    scalars =
      cells != nullptr && cells->GetNumberOfTuples() == image->GetNumberOfCells() ? cells : nullptr;
  }
  return scalars;
}

bool pixelsOnCells(vtkImageData* image)
{
  vtkDataArray* pixels = image != nullptr ? pixelValues(image) : nullptr;
  return pixels != nullptr && pixels == image->GetCellData()->GetScalars();
}

bool heightsOnCells(vtkImageData* image)
{
  return image != nullptr && pointHeights(image) == nullptr && cellHeights(image) != nullptr;
}

namespace
{

// A grid another reader left in degrees (ParaView's GDAL Raster Reader: a
// geographic MAP_PROJECTION and the spacing in degrees) gets its cell size in
// metres at its centre latitude, as the Terrain Reader gives it; taken as
// metres, a 3-arc-second DEM had cells of a millimetre and slopes of
// thousands. hf's width and height and the image's spacing are read.
void inMetres(vtkImageData* image, Heightfield& hf)
{
  auto* projection =
    vtkStringArray::SafeDownCast(image->GetFieldData()->GetAbstractArray("MAP_PROJECTION"));
  if (projection == nullptr || projection->GetNumberOfValues() == 0)
  {
    return;
  }
  int ext[6];
  double origin[3];
  double spacing[3];
  image->GetExtent(ext);
  image->GetOrigin(origin);
  image->GetSpacing(spacing);
  const double centreLatitude = origin[1] + (ext[2] + 0.5 * hf.height) * spacing[1];
  if (const auto degree = geographicDegree(projection->GetValue(0), centreLatitude))
  {
    hf.cellX *= degree->east;
    hf.cellY *= degree->north;
    hf.georef.isGeographic = true;
  }
}

} // namespace

Heightfield imageToHeightfield(vtkImageData* image, vtkDataArray* heights)
{
  if (image == nullptr)
  {
    throw Error("No input image.");
  }
  int ext[6];
  image->GetExtent(ext);
  // Heights on cells: found there (no point heights), or a cell array chosen by name. A point
  // array with the name of a usable cell array is ParaView's interpolation of it (its pipeline
  // converts a cell array asked for as points): the cells are the data, and nodata among them
  // must not be averaged in.
  vtkDataArray* chosenCells = heights != nullptr && heights->GetName() != nullptr
    ? image->GetCellData()->GetArray(heights->GetName())
    : nullptr;
  if (chosenCells != nullptr && chosenCells->GetNumberOfComponents() == 1 &&
    chosenCells->GetNumberOfTuples() == image->GetNumberOfCells())
  {
    heights = chosenCells;
  }
  const bool onCells = heights == nullptr ? heightsOnCells(image) : heights == chosenCells;
  // A cell-data image has one height per pixel: one fewer than its points on each axis.
  const int cellsLess = onCells ? 1 : 0;
  const int w = ext[1] - ext[0] + 1 - cellsLess;
  const int h = ext[3] - ext[2] + 1 - cellsLess;
  if (w <= 0 || h <= 0 || ext[5] != ext[4])
  {
    throw Error("The input must be a non-empty 2D image in the x-y plane.");
  }
  if (heights == nullptr)
  {
    heights = onCells ? cellHeights(image) : pointHeights(image);
  }
  if (heights == nullptr || heights->GetNumberOfComponents() != 1)
  {
    throw Error("The input image has no single-component height array: give a single-band "
                "DEM, best opened with the Terrain Reader (File > Open, then Terrain Reader), "
                "which reads its units, cell size and nodata.");
  }
  const vtkIdType points = static_cast<vtkIdType>(w) * h;
  if (heights->GetNumberOfTuples() != points)
  {
    throw Error(std::string("The height array \"") +
      (heights->GetName() != nullptr ? heights->GetName() : "") + "\" has " +
      std::to_string(heights->GetNumberOfTuples()) + " values for " + std::to_string(points) +
      " points: give one per point.");
  }

  Heightfield hf(w, h);
  double spacing[3];
  image->GetSpacing(spacing);
  hf.cellX = std::abs(spacing[0]);
  hf.cellY = std::abs(spacing[1]);
  hf.cellSizeKnown = true;
  if (!(hf.cellX > 0.0) || !(hf.cellY > 0.0) || !std::isfinite(hf.cellX) ||
    !std::isfinite(hf.cellY))
  {
    throw Error("The input image's spacing must be finite and positive (the cell size in metres).");
  }
  inMetres(image, hf);
  for (vtkIdType k = 0; k < heights->GetNumberOfTuples(); ++k)
  {
    pollCancellation(); // a whole DEM's copy is a good part of a second under a filter's abort
    hf.z[static_cast<std::size_t>(k)] = static_cast<float>(heights->GetComponent(k, 0));
  }
  if (onCells)
  {
    maskReaderNodata(image, hf);
  }
  else if (image->GetPointData()->GetArray(kValidArray) != nullptr)
  {
    hf.valid = pointFlags(image, kValidArray, 1);
  }
  normaliseMask(hf);
  checkPlausibleHeights(hf, "The input image");

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

// VTK images keep row 0 at the bottom; sketches are read top row first.
ColourImage imageToColourImage(vtkImageData* image)
{
  vtkDataArray* scalars = pixelValues(image);
  int dims[3];
  image->GetDimensions(dims);
  if (scalars == nullptr || dims[2] != 1)
  {
    throw Error("The sketch must be a 2D image with pixel values.");
  }
  // Pixels on cells (ParaView's GDAL Raster Reader): one fewer than the points on each axis.
  const int cellsLess = pixelsOnCells(image) ? 1 : 0;
  ColourImage out;
  out.width = dims[0] - cellsLess;
  out.height = dims[1] - cellsLess;
  const bool bytes = scalars->GetDataType() == VTK_UNSIGNED_CHAR;
  out.channels = bytes ? std::min(4, scalars->GetNumberOfComponents()) : 1;
  out.data.resize(static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height) *
    static_cast<std::size_t>(out.channels));
  double range[2] = { 0.0, 255.0 };
  if (!bytes)
  {
    scalars->GetRange(range, 0); // other types: one channel scaled onto 0..255
  }
  const double scale = range[1] > range[0] ? 255.0 / (range[1] - range[0]) : 0.0;
  for (int j = 0; j < out.height; ++j)
  {
    for (int i = 0; i < out.width; ++i)
    {
      const vtkIdType src = static_cast<vtkIdType>(j) * out.width + i;
      const std::size_t dst =
        (static_cast<std::size_t>(out.height - 1 - j) * static_cast<std::size_t>(out.width) +
          static_cast<std::size_t>(i)) *
        static_cast<std::size_t>(out.channels);
      for (int c = 0; c < out.channels; ++c)
      {
        const double v = scalars->GetComponent(src, c);
        out.data[dst + static_cast<std::size_t>(c)] = static_cast<std::uint8_t>(
          bytes ? v : std::clamp(std::lround((v - range[0]) * scale), 0L, 255L));
      }
    }
  }
  return out;
}

void copyAsPointGrid(vtkImageData* input, const Heightfield& hf, vtkImageData* output)
{
  if (static_cast<vtkIdType>(hf.size()) == input->GetNumberOfPoints())
  {
    output->ShallowCopy(input);
    return;
  }
  // The cells' centres become the points, each with its height (NaN where nodata).
  int ext[6];
  double origin[3];
  double spacing[3];
  input->GetExtent(ext);
  input->GetOrigin(origin);
  input->GetSpacing(spacing);
  heightfieldToImage(hf, output);
  output->SetExtent(ext[0], ext[0] + hf.width - 1, ext[2], ext[2] + hf.height - 1, 0, 0);
  output->SetSpacing(spacing);
  output->SetOrigin(origin[0] + 0.5 * spacing[0], origin[1] + 0.5 * spacing[1], origin[2]);
  vtkNew<vtkFloatArray> elevation;
  elevation->SetName(kElevationArray);
  elevation->SetNumberOfTuples(static_cast<vtkIdType>(hf.size()));
  for (std::size_t k = 0; k < hf.size(); ++k)
  {
    elevation->SetValue(
      static_cast<vtkIdType>(k), hf.isValid(k) ? hf.z[k] : std::numeric_limits<float>::quiet_NaN());
  }
  output->GetPointData()->SetScalars(elevation);
  output->GetFieldData()->PassData(input->GetFieldData());
}

void gridOrigin(vtkImageData* image, double& x, double& y)
{
  double origin[3];
  double spacing[3];
  int extent[6];
  image->GetOrigin(origin);
  image->GetSpacing(spacing);
  image->GetExtent(extent);
  // Heights on cells sit at the cells' centres, half a cell in from the first point.
  const double centre = heightsOnCells(image) ? 0.5 : 0.0;
  x = origin[0] + (extent[0] + centre) * spacing[0];
  y = origin[1] + (extent[2] + centre) * spacing[1];
}

void addPointArray(vtkImageData* image, const char* name, const float* values)
{
  vtkNew<vtkFloatArray> array;
  array->SetName(name);
  array->SetNumberOfTuples(image->GetNumberOfPoints());
  std::copy(values, values + image->GetNumberOfPoints(), array->GetPointer(0));
  image->GetPointData()->AddArray(array);
}

vtkDataArray* selectedArrayOn(vtkInformation* chosen, vtkImageData* image)
{
  if (chosen == nullptr || image == nullptr || !chosen->Has(vtkDataObject::FIELD_NAME()))
  {
    return nullptr;
  }
  const bool onCells = chosen->Has(vtkDataObject::FIELD_ASSOCIATION()) &&
    chosen->Get(vtkDataObject::FIELD_ASSOCIATION()) == vtkDataObject::FIELD_ASSOCIATION_CELLS;
  vtkDataSetAttributes* data = onCells ? static_cast<vtkDataSetAttributes*>(image->GetCellData())
                                       : static_cast<vtkDataSetAttributes*>(image->GetPointData());
  return data->GetArray(chosen->Get(vtkDataObject::FIELD_NAME()));
}

vtkDataArray* chosenPointArray(vtkImageData* image,
  const char* name,
  const char* defaultName,
  int components)
{
  if (name == nullptr || *name == '\0')
  {
    return nullptr;
  }
  vtkDataArray* array = image->GetPointData()->GetArray(name);
  if (array == nullptr)
  {
    if (defaultName != nullptr && std::string(name) == defaultName)
    {
      return nullptr;
    }
    throw Error(std::string("The input has no point array named \"") + name +
      "\": choose one of its arrays, or leave the name empty for none.");
  }
  if (array->GetNumberOfTuples() != image->GetNumberOfPoints())
  {
    throw Error(std::string("The ") + name + " array has " +
      std::to_string(array->GetNumberOfTuples()) + " values for " +
      std::to_string(image->GetNumberOfPoints()) + " points: give one per point.");
  }
  if (components > 0 && array->GetNumberOfComponents() != components)
  {
    throw Error(std::string("The ") + name + " array has " +
      std::to_string(array->GetNumberOfComponents()) + " components; it needs " +
      std::to_string(components) + ".");
  }
  return array;
}

void requireValidHeights(const Heightfield& hf)
{
  if (hf.validCount() == 0)
  {
    throw Error("The input image holds no valid heights (every cell is nodata).");
  }
}

std::vector<std::uint8_t> filledCells(vtkImageData* image, const Heightfield& heights)
{
  std::vector<std::uint8_t> filled = pointFlags(image, "Filled", 1);
  for (std::size_t k = 0; k < filled.size(); ++k)
  {
    filled[k] = filled[k] != 0 && heights.isValid(k) ? 1 : 0;
  }
  return filled;
}

std::vector<std::uint8_t> pointFlags(vtkImageData* image, const char* name, std::uint8_t fallback)
{
  const auto n = static_cast<std::size_t>(image->GetNumberOfPoints());
  std::vector<std::uint8_t> out(n, fallback);
  vtkDataArray* a = image->GetPointData()->GetArray(name);
  if (a == nullptr)
  {
    return out;
  }
  if (static_cast<std::size_t>(a->GetNumberOfTuples()) != n)
  {
    throw Error(std::string("The ") + name + " array has " +
      std::to_string(a->GetNumberOfTuples()) + " values for " + std::to_string(n) +
      " points: give one per point.");
  }
  for (std::size_t k = 0; k < n; ++k)
  {
    out[k] = a->GetComponent(static_cast<vtkIdType>(k), 0) != 0.0 ? 1 : 0;
  }
  return out;
}

} // namespace tsynth
