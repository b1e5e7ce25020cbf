/**
 * @class vtkTerrainFeatureExtractor
 * @brief Ridge and valley lines of a heightfield (PPA) as a feature tree.
 *
 * Input: a 2D heightfield image ("Elevation" by default). Output port 0: the
 * feature forest as poly-lines in metres with point data NodeKind (0 path,
 * 1 end, 2 branch), Degree, Elevation, BFSRank, ComponentId, cell data
 * FeatureType (+1 ridge, -1 valley) and ChainId, field data BFSOrder. Output
 * port 1: the control points (where chains cross the circle of ControlRadius).
 * The algorithm is Chang's profile-recognition and target-connection (PPA)
 * with Kruskal's maximum spanning forest replacing polygon breaking (Zhou et
 * al. 2007; Tasse's thesis, algorithm 3.2).
 *
 * Kernel: Kernels/Features/Ppa.h (extractFeatures).
 */
#pragma once

#include "Features/PpaLimits.h"
#include "TerrainSynthesisFiltersModule.h"

#include <vtkPolyDataAlgorithm.h>

class TERRAINSYNTHESISFILTERS_EXPORT vtkTerrainFeatureExtractor : public vtkPolyDataAlgorithm
{
public:
  static vtkTerrainFeatureExtractor* New();
  vtkTypeMacro(vtkTerrainFeatureExtractor, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  // tsynth::FeatureSelection's values (checked in the .cxx).
  enum FeatureKinds
  {
    RIDGES = 0,
    VALLEYS = 1,
    RIDGES_AND_VALLEYS = 2
  };

  ///@{
  /// Which lines to extract (default ridges and valleys: a terrain's whole feature tree).
  vtkSetClampMacro(Features, int, RIDGES, RIDGES_AND_VALLEYS);
  vtkGetMacro(Features, int);
  ///@}

  ///@{
  /// Profile half-length in cells (default 3).
  vtkSetClampMacro(HalfProfileLength, int, 1, tsynth::kMaxHalfProfileLength);
  vtkGetMacro(HalfProfileLength, int);
  ///@}

  ///@{
  /// Minimum dip on both sides, in height units (default 0).
  vtkSetClampMacro(MinimumDip, double, 0.0, tsynth::kMaxMinimumDip);
  vtkGetMacro(MinimumDip, double);
  ///@}

  ///@{
  /// Minimum dip as a fraction of the local relief (default 0.1).
  vtkSetClampMacro(RelativeDip, double, 0.0, 1.0);
  vtkGetMacro(RelativeDip, double);
  ///@}

  ///@{
  /// Significance as a fraction of the heightfield's robust relief (the range
  /// between its 1st and 99th height percentiles; default 0.02, 0 = off): a
  /// target is kept only if along one axis both sides drop, each before rising
  /// as much, within SignificanceRadius cells by Significance x relief and by at
  /// least SignificanceNoise sigmas of the cell-scale noise. Removes the trees
  /// that noise grows on flat ground; unit-free.
  vtkSetClampMacro(Significance, double, 0.0, 1.0);
  vtkGetMacro(Significance, double);
  ///@}

  ///@{
  /// Floor of the significance drop in sigmas of the heightfield's cell-scale
  /// noise (default 4, 0 = no floor).
  vtkSetClampMacro(SignificanceNoise, double, 0.0, tsynth::kMaxSignificanceNoise);
  vtkGetMacro(SignificanceNoise, double);
  ///@}

  ///@{
  /// Cells searched on each side for the significance drop (default 20).
  vtkSetClampMacro(SignificanceRadius, int, 1, tsynth::kMaxSignificanceRadius);
  vtkGetMacro(SignificanceRadius, int);
  ///@}

  ///@{
  /// Gaussian pre-smoothing in cells (default 0: none).
  vtkSetClampMacro(PresmoothSigma, double, 0.0, tsynth::kMaxPresmoothSigma);
  vtkGetMacro(PresmoothSigma, double);
  ///@}

  ///@{
  /// End-segment removals (default 3).
  vtkSetClampMacro(EndReductions, int, 0, tsynth::kMaxEndReductions);
  vtkGetMacro(EndReductions, int);
  ///@}

  ///@{
  /// Dangling branches shorter than this many cells are removed (default 15).
  vtkSetClampMacro(MinimumBranchLength, int, 0, tsynth::kMaxBranchLength);
  vtkGetMacro(MinimumBranchLength, int);
  ///@}

  ///@{
  /// Trees with fewer cells are removed (default 30).
  vtkSetClampMacro(MinimumTreeSize, int, 0, tsynth::kMaxTreeSize);
  vtkGetMacro(MinimumTreeSize, int);
  ///@}

  ///@{
  /// Chain smoothing passes (default 2).
  vtkSetClampMacro(SmoothingPasses, int, 0, tsynth::kMaxSmoothingPasses);
  vtkGetMacro(SmoothingPasses, int);
  ///@}

  ///@{
  /// Control-point circle radius in cells: half the patch size (default 40).
  vtkSetClampMacro(ControlRadius, double, 1.0, tsynth::kMaxControlRadius);
  vtkGetMacro(ControlRadius, double);
  ///@}

protected:
  vtkTerrainFeatureExtractor();
  ~vtkTerrainFeatureExtractor() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  // The options table's defaults (tsynth::ppaOptionRows), set in the constructor.
  int Features;
  int HalfProfileLength;
  double MinimumDip;
  double RelativeDip;
  double Significance;
  double SignificanceNoise;
  int SignificanceRadius;
  double PresmoothSigma;
  int EndReductions;
  int MinimumBranchLength;
  int MinimumTreeSize;
  int SmoothingPasses;
  double ControlRadius;

private:
  vtkTerrainFeatureExtractor(const vtkTerrainFeatureExtractor&) = delete;
  void operator=(const vtkTerrainFeatureExtractor&) = delete;
};
