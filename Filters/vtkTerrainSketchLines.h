/**
 * @class vtkTerrainSketchLines
 * @brief Marks drawn poly-lines as sketched ridges or valleys, with optional
 * heights, so they can be the sketch of the Terrain Synthesis filter.
 *
 * Input: poly-lines in metres in the raster frame of the terrain to make (as
 * ParaView's Poly Line or Spline source draws them over a DEM read at origin 0).
 * Output: the same lines with the cell array "FeatureType" (+1 ridge, -1
 * valley; the active cell scalars, so ParaView shows ridges red and valleys blue) and the
 * point array "Elevation" (metres; NaN where the line has no
 * height): none, each point's z coordinate (then set to 0), or one constant
 * height. Several marked sources are combined with Append Geometry.
 *
 * Kernel: none: it only sets the arrays, which Filters/FeatureGraphConversion.h
 * (polyDataToPolylines) reads for the synthesis. Its options' table:
 * tsynth::sketchLineOptionRows (Kernels/Features/Sketch.h).
 */
#pragma once

#include "TerrainSynthesisFiltersModule.h"

#include "Features/Sketch.h" // LineElevation, kLowestLineElevation, kHighestLineElevation

#include <vtkPolyDataAlgorithm.h>

class TERRAINSYNTHESISFILTERS_EXPORT vtkTerrainSketchLines : public vtkPolyDataAlgorithm
{
public:
  static vtkTerrainSketchLines* New();
  vtkTypeMacro(vtkTerrainSketchLines, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum FeatureTypes
  {
    VALLEY = -1,
    RIDGE = 1
  };
  enum ElevationModes // tsynth::LineElevation's values (checked where the filter is built)
  {
    NO_ELEVATION = 0, // the synthesis chooses the heights
    ELEVATION_FROM_Z = 1,
    CONSTANT_ELEVATION = 2
  };

  ///@{
  /// RIDGE (default) or VALLEY; 0, between them, fails the request with a sentence naming both.
  vtkSetClampMacro(FeatureType, int, VALLEY, RIDGE);
  vtkGetMacro(FeatureType, int);
  ///@}

  ///@{
  /// Where the lines' heights come from (default NO_ELEVATION).
  vtkSetClampMacro(ElevationMode, int, NO_ELEVATION, CONSTANT_ELEVATION);
  vtkGetMacro(ElevationMode, int);
  ///@}

  ///@{
  /// The height in metres of CONSTANT_ELEVATION (default 0), from the deepest sea floor to
  /// above the highest summit.
  vtkSetClampMacro(Elevation, double, tsynth::kLowestLineElevation, tsynth::kHighestLineElevation);
  vtkGetMacro(Elevation, double);
  ///@}

protected:
  vtkTerrainSketchLines();
  ~vtkTerrainSketchLines() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  // The options table's defaults (tsynth::sketchLineOptionRows).
  int FeatureType;
  int ElevationMode;
  double Elevation;

private:
  vtkTerrainSketchLines(const vtkTerrainSketchLines&) = delete;
  void operator=(const vtkTerrainSketchLines&) = delete;
};
