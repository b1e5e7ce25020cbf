/**
 * @class vtkTerrainGraphCutMerger
 * @brief Merges a new patch into terrain along the graph-cut seam, then removes
 * what is left of the seam in the gradient domain.
 *
 * Input port 0: the terrain so far (2D image, "Elevation"; an optional uint8
 * point array "Filled" marks cells that hold terrain, else every valid cell
 * does; an optional int array "PatchId" is carried on). Input port 1: the patch
 * (2D image with "Elevation", same cell size; an optional uint8 "Core" array
 * marks cells that must come from the patch, e.g. around its feature). The patch
 * is placed where its origin lies in the terrain's frame, or at PatchCell when
 * UsePatchOrigin is off, and clipped to the terrain.
 *
 * The seam is the minimum cut through the overlap with Kwatra's cost
 * (|A(s)-B(s)| + |A(t)-B(t)|) / (gradient norms + eps) (Tasse's thesis;
 * Zhou et al. 2007). Modes: Cut (labels only), Poisson (Zhou: gradients across
 * the seam removed, Poisson solve), Shepard (height mismatch spread from the
 * seam with a smooth fall-off), New (default: gradient mismatch spread by
 * Shepard interpolation, then a Poisson solve, as in Tasse's thesis). Old
 * terrain is never changed. Output: the terrain with the merged heights and
 * point arrays Filled, SeamMask (1 on seam cells), PatchId (PatchIdValue where
 * the patch was taken); field data CutCost, CutEdges, NormalisedCutCost.
 *
 * Kernel: Kernels/Merging/PatchMerger.h (PatchMerger::merge).
 */
#pragma once

#include "Merging/MergeLimits.h"
#include "TerrainSynthesisFiltersModule.h"

#include <vtkImageAlgorithm.h>

class TERRAINSYNTHESISFILTERS_EXPORT vtkTerrainGraphCutMerger : public vtkImageAlgorithm
{
public:
  static vtkTerrainGraphCutMerger* New();
  vtkTypeMacro(vtkTerrainGraphCutMerger, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Modes
  {
    CUT = 0,
    POISSON = 1,
    SHEPARD = 2,
    NEW = 3
  };

  /// Seam removal after the cut (default NEW).
  vtkSetClampMacro(Mode, int, CUT, NEW);
  vtkGetMacro(Mode, int);
  /// Place the patch where its origin lies (default on), else at PatchCell.
  vtkSetMacro(UsePatchOrigin, bool);
  vtkGetMacro(UsePatchOrigin, bool);
  vtkBooleanMacro(UsePatchOrigin, bool);
  /// Terrain cell of the patch's lower-left cell when UsePatchOrigin is off.
  vtkSetVector2Macro(PatchCell, int);
  vtkGetVector2Macro(PatchCell, int);
  /// Shepard radius of influence in cells (default 20).
  vtkSetClampMacro(ShepardRadius, double, tsynth::kMinShepardRadius, tsynth::kMaxShepardRadius);
  vtkGetMacro(ShepardRadius, double);
  /// Value written to PatchId where the patch is taken (default 1); at least 1, since
  /// 0 marks cells no merge has taken.
  vtkSetClampMacro(PatchIdValue, int, 1, VTK_INT_MAX);
  vtkGetMacro(PatchIdValue, int);

  /// Sets the patch (port 1).
  void SetPatchConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }

protected:
  vtkTerrainGraphCutMerger();
  ~vtkTerrainGraphCutMerger() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  // Mode and ShepardRadius: the options table's defaults (tsynth::mergeOptionRows), set in the
  // constructor.
  int Mode;
  bool UsePatchOrigin = true;
  int PatchCell[2] = { 0, 0 };
  double ShepardRadius;
  int PatchIdValue = 1;

private:
  vtkTerrainGraphCutMerger(const vtkTerrainGraphCutMerger&) = delete;
  void operator=(const vtkTerrainGraphCutMerger&) = delete;
};
