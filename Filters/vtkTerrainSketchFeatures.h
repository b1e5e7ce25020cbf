/**
 * @class vtkTerrainSketchFeatures
 * @brief A user's sketch turned into a feature tree like vtkTerrainFeatureExtractor's.
 *
 * Input port 0 takes either
 * - an image: a grey sketch map (one channel, or R = G = B; brighter is higher)
 *   goes through PPA with settings derived from its stroke width; a stroke map
 *   (RGB: red R>=200 G<=80 B<=80 ridges, blue B>=200 R<=80 G<=80 valleys) is
 *   thinned to centre lines and turned into a graph directly, loops kept; or
 * - poly-lines (vtkPolyData lines, e.g. drawn with ParaView's poly-line source),
 *   with cell data FeatureType (+1 ridge, -1 valley; ridges if absent) and
 *   optional point data Elevation kept as ElevationConstraint.
 * Optional input port 1: a reference image whose grid (origin, spacing, extent)
 * the poly-lines are laid on. Outputs as vtkTerrainFeatureExtractor: the tree
 * (port 0) and its control points (port 1).
 *
 * Kernel: Kernels/Features/Sketch.h (sketchFeatures for images,
 * polylineFeatures for poly-lines).
 */
#pragma once

#include "TerrainSynthesisFiltersModule.h"

#include "Features/Sketch.h" // the options table and its limits

#include <vtkPolyDataAlgorithm.h>

class TERRAINSYNTHESISFILTERS_EXPORT vtkTerrainSketchFeatures : public vtkPolyDataAlgorithm
{
public:
  static vtkTerrainSketchFeatures* New();
  vtkTypeMacro(vtkTerrainSketchFeatures, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Patch size in cells (default 80): a multiple of 4 from 16 to 512, as the synthesis
  /// takes; another size fails the request with a sentence saying so (never clamped). A sketch
  /// image smaller than one patch is refused.
  vtkSetMacro(PatchSize, int);
  vtkGetMacro(PatchSize, int);
  ///@}

  ///@{
  /// Control-point radius in cells; 0 (default) means half the patch size.
  vtkSetClampMacro(ControlRadius, double, 0.0, tsynth::kMaxControlRadius);
  vtkGetMacro(ControlRadius, double);
  ///@}

  ///@{
  /// Metres per sketch pixel (images) or per cell (poly-lines without a
  /// reference image); 0 (default) takes the image spacing, or 1 for poly-lines.
  vtkSetClampMacro(CellSize, double, 0.0, tsynth::kMaxCellSizeMetres);
  vtkGetMacro(CellSize, double);
  ///@}

  ///@{
  /// Poly-line vertices closer than this many cells are merged (default 1).
  vtkSetClampMacro(SnapTolerance, double, 0.0, tsynth::kMaxSnapCells);
  vtkGetMacro(SnapTolerance, double);
  ///@}

  ///@{
  /// Chain smoothing passes for sketch images (default 2).
  vtkSetClampMacro(SmoothingPasses, int, 0, tsynth::kMaxSmoothingPasses);
  vtkGetMacro(SmoothingPasses, int);
  ///@}

  /// Sets the optional reference image (port 1) for poly-line input.
  void SetReferenceConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }

protected:
  vtkTerrainSketchFeatures();
  ~vtkTerrainSketchFeatures() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  // The options table's defaults (tsynth::sketchOptionRows), set in the constructor.
  int PatchSize;
  double ControlRadius;
  double CellSize;
  double SnapTolerance;
  int SmoothingPasses;

private:
  vtkTerrainSketchFeatures(const vtkTerrainSketchFeatures&) = delete;
  void operator=(const vtkTerrainSketchFeatures&) = delete;
};
