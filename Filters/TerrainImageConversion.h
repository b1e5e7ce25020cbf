// Moving heightfields between the kernels' type and vtkImageData (DESIGN.md data model).
#pragma once

#include "Core/Heightfield.h"
#include "Core/HeightfieldIO.h"

#include <cstdint>
#include <vector>

class vtkDataArray;
class vtkImageData;
class vtkInformation;

namespace tsynth
{

// Array names shared by every filter.
constexpr const char* kElevationArray = "Elevation";
constexpr const char* kValidArray = "Valid";

// Sets a 2D image: extent [0, w-1] x [0, h-1], spacing = cell size, origin 0,
// point scalars "Elevation" (float), "Valid" (uint8) when some cells are
// invalid, and the georeference as field data ("CRS", "GeoTransform").
void heightfieldToImage(const Heightfield& hf, vtkImageData* image);

// Reads a 2D image's heights (the given array, or "Elevation", or the active
// scalars) and its "Valid" mask and georeference. Throws tsynth::Error if the
// image is not 2D in x-y, has no usable height array, a height or Valid array
// of another length than its points, a spacing that is not finite and
// positive, or heights checkPlausibleHeights refuses.
//
// Without a given array and with no point heights, a single-component cell array
// ("Elevation" or the active cell scalars, one value per cell: what ParaView's GDAL Raster
// Reader makes) is read instead, one height per cell, with the cells the reader hid (ghost
// array) or holding its NO_DATA_VALUE as nodata.
Heightfield imageToHeightfield(vtkImageData* image, vtkDataArray* heights = nullptr);

// Whether imageToHeightfield reads this image's heights from its cells (see above).
bool heightsOnCells(vtkImageData* image);

// An image's pixel values: its point scalars (or first point array), else its cell scalars
// when they hold one value per cell (ParaView's GDAL Raster Reader); nullptr if neither.
vtkDataArray* pixelValues(vtkImageData* image);

// Whether pixelValues comes from the image's cells.
bool pixelsOnCells(vtkImageData* image);

// The image's point array chosen by name for a filter's optional input array (a mask, known
// cells, a gradient). An empty name means none: nullptr. A name the image lacks is nullptr when
// it is the filter's default name (the input simply does not carry that array), and otherwise
// a tsynth::Error naming it, so a mistyped choice is never silently ignored. A present array
// must have one tuple per point and the given number of components (0: any), else
// tsynth::Error with both counts.
vtkDataArray* chosenPointArray(vtkImageData* image,
  const char* name,
  const char* defaultName,
  int components = 0);

// The array a filter's input-array selection `chosen` (its GetInputArrayInformation) names,
// looked up on `image` itself, among its cell arrays when the selection says cells, else its
// point arrays; nullptr when the selection names none or the image lacks it (imageToHeightfield
// then reads Elevation). A selection's port is not used: ParaView 5.11 crashes in its
// vtkPVPostFilter when a selection points at port 1 while no selection of index 0 does, so the
// XMLs keep port 0 in every selection and a second input's array is found here by name.
vtkDataArray* selectedArrayOn(vtkInformation* chosen, vtkImageData* image);

// Throws tsynth::Error ("The input image holds no valid heights ...") if no cell
// of `hf` is valid: what filters that need heights refuse (a target being
// synthesised may well be all unknown, so imageToHeightfield allows it).
void requireValidHeights(const Heightfield& hf);

// The image's point array `name` as one byte per point (1 where non-zero), or
// `fallback` everywhere if it has none. Throws tsynth::Error naming both counts
// if its length is not the image's point count.
std::vector<std::uint8_t> pointFlags(vtkImageData* image, const char* name, std::uint8_t fallback);

// The cells of a terrain so far that patches wrote: its "Filled" point array where non-zero (every
// cell when it has none), and valid in `heights` (the image's, imageToHeightfield's).
std::vector<std::uint8_t> filledCells(vtkImageData* image, const Heightfield& heights);

// An image's pixels (pixelValues) as a sketch image (top row first): unsigned-char scalars
// with 1-4 components as they are, other types scaled onto 0..255 (one channel).
ColourImage imageToColourImage(vtkImageData* image);

// The output grid of a filter that adds point arrays to its input image: the input itself
// (shallow copy) when `hf` (read from it) has a height per point; when its heights were on
// cells (see imageToHeightfield), a point grid on the cells' centres holding `hf`'s heights as
// "Elevation" (NaN where invalid), so arrays of one value per height fit it.
void copyAsPointGrid(vtkImageData* input, const Heightfield& hf, vtkImageData* output);

// World position of the image's first point (origin plus the extent's offset), or of its
// first cell's centre when its heights are on cells: where cell (0, 0) of a heightfield taken
// from it lies.
void gridOrigin(vtkImageData* image, double& x, double& y);

// Adds a float point array (NaN where invalid) of the image's size.
void addPointArray(vtkImageData* image, const char* name, const float* values);

} // namespace tsynth
