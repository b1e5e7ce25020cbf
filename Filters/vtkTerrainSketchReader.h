/**
 * @class vtkTerrainSketchReader
 * @brief Reads a sketch image (a stroke map, a grey sketch map, or a DEM used as the target)
 * onto the grid a Terrain Synthesis from a given exemplar makes of it.
 *
 * A synthesis gives each sketch pixel one output cell of the first exemplar's size, with the
 * lower-left cell centre at (0, 0). ParaView's PNG reader gives the same sketch 1 m pixels, so
 * it sits as a speck at the corner of a terrain tens of kilometres wide; this reader gives it
 * the exemplar's cells (ExemplarFileName), or CellSize, so it lies under the terrain made from
 * it. The file is read as `tsynth synth --sketch` reads it (tsynth::readSketchInput).
 *
 * Output: a 2D image of the sketch's pixels, origin (0, 0), spacing the cell size in metres.
 * Stroke and grey maps: point scalars "Sketch" (unsigned char, the file's 1 to 4 channels).
 * A DEM used as the target: point scalars "Elevation" (float, metres; NaN and "Valid" 0 where
 * the file has nodata), as the Terrain Reader reads it.
 *
 * Kernel: Kernels/Core/HeightfieldIO.h (readColourImage); .vti through
 * Filters/TerrainFileIO.h.
 */
#pragma once

#include "TerrainSynthesisFiltersModule.h"

#include "Core/HeightfieldIO.h" // kMaxCellSizeMetres, the sketch table's bound

#include <vtkImageAlgorithm.h>

class TERRAINSYNTHESISFILTERS_EXPORT vtkTerrainSketchReader : public vtkImageAlgorithm
{
public:
  static vtkTerrainSketchReader* New();
  vtkTypeMacro(vtkTerrainSketchReader, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The sketch image (PNG, GeoTIFF, any image GDAL reads).
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  /// The exemplar DEM the sketch will be synthesised from: the sketch takes its cell size
  /// (from its sidecar, its georeference or its .vti spacing, as the Terrain Reader reads it).
  vtkSetStringMacro(ExemplarFileName);
  vtkGetStringMacro(ExemplarFileName);
  /// Cell size in metres; 0 (default) takes the exemplar's, and without an exemplar 1 m.
  vtkSetClampMacro(CellSize, double, 0.0, tsynth::kMaxCellSizeMetres);
  vtkGetMacro(CellSize, double);

protected:
  vtkTerrainSketchReader();
  ~vtkTerrainSketchReader() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  char* FileName = nullptr;
  char* ExemplarFileName = nullptr;
  double CellSize; // tsynth::sketchOptionRows' default

private:
  vtkTerrainSketchReader(const vtkTerrainSketchReader&) = delete;
  void operator=(const vtkTerrainSketchReader&) = delete;
};
