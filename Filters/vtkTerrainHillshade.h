/**
 * @class vtkTerrainHillshade
 * @brief Multi-directional hillshade and slope of a heightfield image.
 *
 * Input: a 2D image with a height array ("Elevation" by default; any
 * single-component point array can be chosen), spacing = cell size in metres.
 * Output: the input plus point arrays "Hillshade" (0 dark .. 1 lit; active
 * scalars) and "Slope" (degrees). Cells marked invalid in "Valid" get NaN and
 * never influence their neighbours.
 *
 * Kernel: Kernels/Analysis/Hillshade.h (computeHillshade).
 */
#pragma once

#include "Analysis/HillshadeLimits.h"
#include "TerrainSynthesisFiltersModule.h"

#include <vtkImageAlgorithm.h>

class TERRAINSYNTHESISFILTERS_EXPORT vtkTerrainHillshade : public vtkImageAlgorithm
{
public:
  static vtkTerrainHillshade* New();
  vtkTypeMacro(vtkTerrainHillshade, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Sun elevation above the horizon in degrees (default 45).
  vtkSetClampMacro(Altitude, double, 0.0, tsynth::kMaxSunAltitudeDeg);
  vtkGetMacro(Altitude, double);
  ///@}

  ///@{
  /// Direction the light comes from, degrees clockwise from north (default 315);
  /// used when Multidirectional is off.
  vtkSetClampMacro(Azimuth, double, 0.0, tsynth::kFullTurnDeg);
  vtkGetMacro(Azimuth, double);
  ///@}

  ///@{
  /// Blend four lights (225, 270, 315, 360 deg) weighted by slope aspect (default on).
  vtkSetMacro(Multidirectional, bool);
  vtkGetMacro(Multidirectional, bool);
  vtkBooleanMacro(Multidirectional, bool);
  ///@}

  ///@{
  /// Vertical exaggeration applied before shading (default 1).
  vtkSetClampMacro(ZFactor, double, tsynth::kMinZFactor, tsynth::kMaxZFactor);
  vtkGetMacro(ZFactor, double);
  ///@}

protected:
  vtkTerrainHillshade();
  ~vtkTerrainHillshade() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  // The options table's defaults (tsynth::hillshadeOptionRows), set in the constructor.
  double Altitude;
  double Azimuth;
  bool Multidirectional;
  double ZFactor;

private:
  vtkTerrainHillshade(const vtkTerrainHillshade&) = delete;
  void operator=(const vtkTerrainHillshade&) = delete;
};
