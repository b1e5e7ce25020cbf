/**
 * @class vtkTerrainPitRemoval
 * @brief Removes depressions so that every cell drains, and computes D8 flow.
 *
 * The standard GIS depression tools (Kernels/Hydrology/PitRemoval.h): filling
 * (Priority-Flood+epsilon, Barnes, Lehman & Mulla 2014), complete breaching
 * (Soille 2004, as chosen by Scott & Dodgson 2021) or the hybrid (Lindsay 2016:
 * breach within MaxBreachDepth and MaxBreachLength, fill the rest).
 *
 * Input 0: a 2D heightfield image (any single-component point array; cells 0 in
 * "Valid" are nodata and act as outlets). Input 1 (optional): an image of the
 * same dimensions whose selected array is non-zero at sinks to keep (lakes).
 * Output: the input with the selected heights replaced by the corrected ones
 * (as "Elevation") and point arrays "Changed" (0 unchanged, 1 raised, 2
 * lowered), "FlowDirection" (D8 code 0..7 counter-clockwise from east, -1 none)
 * and "FlowAccumulation" (cells draining through each cell), plus "Streams"
 * (1 where the accumulation reaches StreamThreshold) when the threshold is set.
 */
#pragma once

#include "Core/Memory.h"
#include "Hydrology/BreachLimits.h"
#include "TerrainSynthesisFiltersModule.h"

#include <vtkImageAlgorithm.h>

class TERRAINSYNTHESISFILTERS_EXPORT vtkTerrainPitRemoval : public vtkImageAlgorithm
{
public:
  static vtkTerrainPitRemoval* New();
  vtkTypeMacro(vtkTerrainPitRemoval, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Methods
  {
    FILL = 0,
    BREACH = 1,
    HYBRID = 2
  };

  ///@{
  /// FILL, BREACH (default) or HYBRID.
  vtkSetClampMacro(Method, int, FILL, HYBRID);
  vtkGetMacro(Method, int);
  ///@}

  ///@{
  /// Hybrid only: deepest cut in metres a breach may make (beyond it the pit is filled).
  vtkSetClampMacro(MaxBreachDepth,
    double,
    tsynth::kMinBreachDepthLimit,
    tsynth::kMaxBreachDepthLimit);
  vtkGetMacro(MaxBreachDepth, double);
  ///@}

  ///@{
  /// Hybrid only: longest channel in cells a breach may cut.
  vtkSetClampMacro(MaxBreachLength, int, 1, tsynth::kMaxBreachLengthLimit);
  vtkGetMacro(MaxBreachLength, int);
  ///@}

  ///@{
  /// Cells of flow accumulation from which a cell is a stream (0: no "Streams" array).
  vtkSetClampMacro(StreamThreshold, int, 0, VTK_INT_MAX);
  vtkGetMacro(StreamThreshold, int);
  ///@}

  ///@{
  /// A removal (with its flow routing) estimated to need more memory than this
  /// (GB) is refused before it starts, with the estimate; 0 (default) allows 80%
  /// of the machine's physical memory (tsynth::pitRemovalMemoryEstimate).
  vtkSetClampMacro(MemoryBudget, double, 0.0, tsynth::kMaxMemoryBudgetGB);
  vtkGetMacro(MemoryBudget, double);
  ///@}

  /// The optional sink mask (same dimensions as the DEM).
  void SetSinksConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }

protected:
  vtkTerrainPitRemoval();
  ~vtkTerrainPitRemoval() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  // The options table's defaults (tsynth::pitRemovalOptionRows), set in the constructor.
  int Method;
  double MaxBreachDepth;
  int MaxBreachLength;
  int StreamThreshold = 0;
  double MemoryBudget; // GB

private:
  vtkTerrainPitRemoval(const vtkTerrainPitRemoval&) = delete;
  void operator=(const vtkTerrainPitRemoval&) = delete;
};
