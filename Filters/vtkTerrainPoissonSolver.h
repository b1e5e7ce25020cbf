/**
 * @class vtkTerrainPoissonSolver
 * @brief Gradient-domain editing of heightfields: solves for heights whose
 * differences follow a guidance field inside a mask, with the surrounding
 * terrain as the boundary (Perez et al. 2003; Zhou et al. 2007).
 *
 * SeamlessClone (default): input port 1 is a source heightfield on the same
 * grid as the destination (port 0); inside the source's uint8 "Mask" array
 * (or, without one, wherever the source is valid) the result takes the
 * source's slopes while meeting the destination at the mask's edge: one DEM
 * cloned into another without a step. GuidanceField: the destination's own
 * two-component point array "Gradient" (dz/dx, dz/dy in m/m) is followed
 * inside its "Mask". The solver is conjugate gradients preconditioned by a
 * multigrid V-cycle, on any mask shape; nodata cells are left out. Output: the
 * destination with the solved "Elevation" and field data Iterations,
 * RelativeResidual.
 *
 * Kernel: Kernels/Merging/PoissonEditing.h (seamlessClone, over the solver of
 * Kernels/Merging/Poisson.h).
 */
#pragma once

#include "TerrainSynthesisFiltersModule.h"

#include "Merging/PoissonEditing.h" // the options table and its limits

#include <vtkImageAlgorithm.h>

class TERRAINSYNTHESISFILTERS_EXPORT vtkTerrainPoissonSolver : public vtkImageAlgorithm
{
public:
  static vtkTerrainPoissonSolver* New();
  vtkTypeMacro(vtkTerrainPoissonSolver, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  // tsynth::PoissonEditMode's values (checked in the .cxx).
  enum Modes
  {
    SEAMLESS_CLONE = 0,
    GUIDANCE_FIELD = 1
  };
  vtkSetClampMacro(Mode, int, SEAMLESS_CLONE, GUIDANCE_FIELD);
  vtkGetMacro(Mode, int);
  /// Relative residual at which the solver stops (default the solver's own, 1e-10).
  vtkSetClampMacro(Tolerance, double, tsynth::kMinEditTolerance, tsynth::kMaxEditTolerance);
  vtkGetMacro(Tolerance, double);

  /// The point array, non-zero on the cells to solve: on the source for SeamlessClone (none:
  /// the whole source), on the input for GuidanceField (required). Default "Mask"; an empty
  /// name means none, and a name the input lacks is an error unless it is the default.
  static constexpr const char* kDefaultMaskArray = "Mask";
  vtkSetStringMacro(MaskArray);
  vtkGetStringMacro(MaskArray);
  /// The input's two-component point array of slopes (dz/dx, dz/dy) for GuidanceField.
  static constexpr const char* kDefaultGradientArray = "Gradient";
  vtkSetStringMacro(GradientArray);
  vtkGetStringMacro(GradientArray);

  /// Sets the source heightfield (port 1) for SeamlessClone.
  void SetSourceConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }

protected:
  vtkTerrainPoissonSolver();
  ~vtkTerrainPoissonSolver() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  // The options table's defaults (tsynth::poissonEditOptionRows), set in the constructor.
  int Mode;
  double Tolerance;
  char* MaskArray = nullptr;
  char* GradientArray = nullptr;

private:
  vtkTerrainPoissonSolver(const vtkTerrainPoissonSolver&) = delete;
  void operator=(const vtkTerrainPoissonSolver&) = delete;
};
