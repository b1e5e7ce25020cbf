/**
 * @class vtkTerrainOptimisation
 * @brief Terrain optimisation (Scott & Dodgson 2021): a terrain rebuilt from
 * patches of one source DEM so that it follows a guide.
 *
 * Input 0: the source DEM (a 2D image with heights in metres, spacing = cell
 * size). Input 1: the guide, as the synthesis reads its sketch: a DEM or a grey
 * sketch image (brought onto the source's heights), a stroke map, or ridge and
 * valley poly-lines. Output: the terrain ("Elevation") on the guide's grid (or
 * OutputSize) at the source's cell size. The algorithm and its defaults are in
 * Kernels/Optimisation/TerrainOptimisation.h; this filter only maps properties.
 */
#pragma once

#include "Core/Memory.h"
#include "Optimisation/OptimisationLimits.h"
#include "TerrainSynthesisFiltersModule.h"

#include <vtkImageAlgorithm.h>

class TERRAINSYNTHESISFILTERS_EXPORT vtkTerrainOptimisation : public vtkImageAlgorithm
{
public:
  static vtkTerrainOptimisation* New();
  vtkTypeMacro(vtkTerrainOptimisation, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum PitRemovals
  {
    NO_PIT_REMOVAL = 0,
    FILL = 1,
    BREACH = 2,
    HYBRID = 3
  };

  ///@{
  /// Patch size N in cells, odd, 3 to 15: checked when the filter runs, where another size
  /// fails the request with a sentence saying so (never clamped).
  vtkSetMacro(PatchSize, int);
  vtkGetMacro(PatchSize, int);
  ///@}

  ///@{
  /// Pyramid levels above the output; 0: as many as the source allows.
  vtkSetClampMacro(Levels, int, 0, tsynth::kMaxOptimisationLevels);
  vtkGetMacro(Levels, int);
  ///@}

  ///@{
  /// Guide weight at the coarsest level; it halves level by level to 0 at the finest.
  vtkSetClampMacro(Alpha, double, 0.0, 1.0);
  vtkGetMacro(Alpha, double);
  ///@}

  ///@{
  /// E/M iterations per level (the paper's mu).
  vtkSetClampMacro(IterationsPerLevel, int, 1, tsynth::kMaxOptimisationIterations);
  vtkGetMacro(IterationsPerLevel, int);
  ///@}

  ///@{
  /// PatchMatch passes (propagation and random search) per M-step.
  vtkSetClampMacro(SearchIterations, int, 1, tsynth::kMaxOptimisationIterations);
  vtkGetMacro(SearchIterations, int);
  ///@}

  ///@{
  /// Also use source patches turned by 90, 180 and 270 degrees / mirrored.
  vtkSetMacro(Rotations, bool);
  vtkGetMacro(Rotations, bool);
  vtkBooleanMacro(Rotations, bool);
  vtkSetMacro(Reflections, bool);
  vtkGetMacro(Reflections, bool);
  vtkBooleanMacro(Reflections, bool);
  ///@}

  ///@{
  /// Pit removal after each E-step on every level but the finest (default BREACH).
  vtkSetClampMacro(PitRemoval, int, NO_PIT_REMOVAL, HYBRID);
  vtkGetMacro(PitRemoval, int);
  ///@}

  ///@{
  /// Also make the output itself drain (beyond the paper; default off).
  vtkSetMacro(DrainOutput, bool);
  vtkGetMacro(DrainOutput, bool);
  vtkBooleanMacro(DrainOutput, bool);
  ///@}

  ///@{
  /// Output size in cells; 0 0 (default): the guide's pixels (or the poly-lines' frame).
  vtkSetVector2Macro(OutputSize, int);
  vtkGetVector2Macro(OutputSize, int);
  ///@}

  ///@{
  /// Seeds PatchMatch's random choices: the same seed gives the same terrain.
  vtkSetClampMacro(Seed, vtkIdType, 0, VTK_ID_MAX);
  vtkGetMacro(Seed, vtkIdType);
  ///@}

  ///@{
  /// An optimisation estimated to need more memory than this (GB) is refused
  /// before it starts, with the estimate; 0 (default) allows 80% of the
  /// machine's physical memory (tsynth::optimisationMemoryEstimate).
  vtkSetClampMacro(MemoryBudget, double, 0.0, tsynth::kMaxMemoryBudgetGB);
  vtkGetMacro(MemoryBudget, double);
  ///@}

  void SetSourceConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(0, output); }
  void SetGuideConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }

protected:
  vtkTerrainOptimisation();
  ~vtkTerrainOptimisation() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  // The options table's defaults (tsynth::optimisationOptionRows), set in the constructor.
  int PatchSize;
  int Levels;
  double Alpha;
  int IterationsPerLevel;
  int SearchIterations;
  bool Rotations;
  bool Reflections;
  int PitRemoval;
  bool DrainOutput;
  int OutputSize[2];
  vtkIdType Seed;
  double MemoryBudget; // GB

private:
  vtkTerrainOptimisation(const vtkTerrainOptimisation&) = delete;
  void operator=(const vtkTerrainOptimisation&) = delete;
};
