/**
 * @class vtkTerrainDistanceSynthesis
 * @brief Distance-based terrain synthesis (Rusnell 2009): terrain from ridge
 * strokes or poly-lines and cross-section profiles, with no exemplar.
 *
 * Input 0: the generators, a stroke map (vtkImageData with RGB colours: red
 * ridge strokes, each 8-connected stroke a feature) or poly-lines and vertices
 * in metres (vtkPolyData; point array Cost and cell array Profile optional).
 * Input 1 (optional): the profiles, a vtkTable with columns Distance (cells),
 * Height (falling) and optionally Profile (id); or ProfileFileName, a CSV of
 * the same rows or a drawn profile image, when the port is not connected.
 * Output: the terrain ("Elevation", metres) on the stroke map's pixels or
 * OutputSize, spacing CellSize. The algorithm and its defaults are in
 * Kernels/Distance/DistanceSynthesis.h; this filter only maps properties.
 * Label images and image edge weights are offered by tsynth distance only.
 */
#pragma once

#include "Core/Memory.h"
#include "Distance/DistanceLimits.h"
#include "TerrainSynthesisFiltersModule.h"

#include <vtkImageAlgorithm.h>

#include <string>

class TERRAINSYNTHESISFILTERS_EXPORT vtkTerrainDistanceSynthesis : public vtkImageAlgorithm
{
public:
  static vtkTerrainDistanceSynthesis* New();
  vtkTypeMacro(vtkTerrainDistanceSynthesis, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum RidgeCosts
  {
    SCALED_RISE = 0, // c_g + f (C_a - c_g)
    SCALED_COST = 1  // f C_a (the thesis read literally)
  };
  enum ProfileAssignments
  {
    BY_COLOUR = 0,
    BY_FEATURE = 1
  };

  ///@{
  /// Grid of poly-line generators in cells (a stroke map's grid is its pixels).
  vtkSetVector2Macro(OutputSize, int);
  vtkGetVector2Macro(OutputSize, int);
  ///@}
  ///@{
  /// Metres per cell, and metres per cost unit.
  vtkSetClampMacro(CellSize, double, tsynth::kLeastPositiveSetting, VTK_DOUBLE_MAX);
  vtkGetMacro(CellSize, double);
  vtkSetClampMacro(HeightScale, double, tsynth::kLeastPositiveSetting, VTK_DOUBLE_MAX);
  vtkGetMacro(HeightScale, double);
  ///@}
  ///@{
  /// Edge weights, fBm costs and ridge cells.
  vtkSetClampMacro(Seed, vtkIdType, 0, VTK_ID_MAX);
  vtkGetMacro(Seed, vtkIdType);
  ///@}
  ///@{
  /// The lattice: mean weight mu_w, deviation r (< mu_w, checked when run), sqrt(2) diagonals.
  vtkSetClampMacro(MeanWeight, double, tsynth::kLeastPositiveSetting, tsynth::kMaxMeanWeight);
  vtkGetMacro(MeanWeight, double);
  vtkSetClampMacro(Roughness, double, 0.0, tsynth::kMaxMeanWeight);
  vtkGetMacro(Roughness, double);
  vtkSetMacro(Sqrt2Diagonals, bool);
  vtkGetMacro(Sqrt2Diagonals, bool);
  vtkBooleanMacro(Sqrt2Diagonals, bool);
  ///@}
  ///@{
  /// Sea level scale s and blending bias b.
  vtkSetClampMacro(SeaLevelScale, double, 0.0, tsynth::kMaxSeaLevelScale);
  vtkGetMacro(SeaLevelScale, double);
  vtkSetClampMacro(BlendBias, double, 0.0, tsynth::kMaxBlendBias);
  vtkGetMacro(BlendBias, double);
  ///@}
  ///@{
  /// The halting thresholds eps_s and p_f, and min t_s.
  vtkSetClampMacro(SeaLevelEpsilon, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(SeaLevelEpsilon, double);
  vtkSetClampMacro(ApproximateFraction, double, 0.0, 1.0);
  vtkGetMacro(ApproximateFraction, double);
  vtkSetClampMacro(MinScaling, double, tsynth::kLeastMinScaling, VTK_DOUBLE_MAX);
  vtkGetMacro(MinScaling, double);
  ///@}
  ///@{
  /// Profiles: a CSV or image file when input 1 is not connected; scale, bins, assignment, region.
  vtkSetMacro(ProfileFileName, std::string);
  vtkGetMacro(ProfileFileName, std::string);
  vtkSetClampMacro(ProfileScale, double, tsynth::kLeastPositiveSetting, VTK_DOUBLE_MAX);
  vtkGetMacro(ProfileScale, double);
  vtkSetClampMacro(ProfileBins, int, 2, tsynth::kMaxProfileBins);
  vtkGetMacro(ProfileBins, int);
  vtkSetClampMacro(ProfileAssignment, int, BY_COLOUR, BY_FEATURE);
  vtkGetMacro(ProfileAssignment, int);
  vtkSetClampMacro(RegionProfile, int, -1, VTK_INT_MAX);
  vtkGetMacro(RegionProfile, int);
  ///@}
  ///@{
  /// fBm generator costs: H, lacunarity, octaves, domain, scale and range (eq. 4.1).
  vtkSetClampMacro(FbmH, double, 0.0, tsynth::kMaxFbmH);
  vtkGetMacro(FbmH, double);
  vtkSetClampMacro(FbmLacunarity, double, tsynth::kLeastLacunarity, VTK_DOUBLE_MAX);
  vtkGetMacro(FbmLacunarity, double);
  vtkSetClampMacro(FbmOctaves, int, 1, tsynth::kMaxFbmOctaves);
  vtkGetMacro(FbmOctaves, int);
  vtkSetClampMacro(FbmDomain, double, tsynth::kLeastPositiveSetting, VTK_DOUBLE_MAX);
  vtkGetMacro(FbmDomain, double);
  vtkSetClampMacro(FbmScale, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(FbmScale, double);
  vtkSetVector2Macro(FbmRange, double);
  vtkGetVector2Macro(FbmRange, double);
  ///@}
  ///@{
  /// Dendritic ridges: count, cost fraction and rule.
  vtkSetClampMacro(RidgeCount, int, 0, tsynth::kMaxRidgeCount);
  vtkGetMacro(RidgeCount, int);
  vtkSetClampMacro(RidgeFraction, double, tsynth::kLeastPositiveSetting, 1.0);
  vtkGetMacro(RidgeFraction, double);
  vtkSetClampMacro(RidgeCost, int, SCALED_RISE, SCALED_COST);
  vtkGetMacro(RidgeCost, int);
  ///@}
  ///@{
  /// Only the one multi-source search: a fast preview with seams.
  vtkSetMacro(ApproximateOnly, bool);
  vtkGetMacro(ApproximateOnly, bool);
  vtkBooleanMacro(ApproximateOnly, bool);
  ///@}
  ///@{
  /// A synthesis estimated to need more memory than this (GB) is refused before
  /// it starts, with the estimate; 0 (default) allows 80% of the machine's
  /// physical memory (tsynth::distanceMemoryEstimate).
  vtkSetClampMacro(MemoryBudget, double, 0.0, tsynth::kMaxMemoryBudgetGB);
  vtkGetMacro(MemoryBudget, double);
  ///@}

  void SetGeneratorsConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(0, output); }
  void SetProfilesConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }

protected:
  vtkTerrainDistanceSynthesis();
  ~vtkTerrainDistanceSynthesis() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int OutputSize[2] = { tsynth::kDefaultDistanceGrid, tsynth::kDefaultDistanceGrid };
  double CellSize;
  double HeightScale;
  vtkIdType Seed;
  double MeanWeight;
  double Roughness;
  bool Sqrt2Diagonals;
  double SeaLevelScale;
  double BlendBias;
  double SeaLevelEpsilon;
  double ApproximateFraction;
  double MinScaling;
  std::string ProfileFileName;
  double ProfileScale;
  int ProfileBins;
  int ProfileAssignment = BY_COLOUR;
  int RegionProfile = -1;
  double FbmH;
  double FbmLacunarity;
  int FbmOctaves;
  double FbmDomain;
  double FbmScale;
  double FbmRange[2];
  int RidgeCount;
  double RidgeFraction;
  int RidgeCost;
  bool ApproximateOnly;
  double MemoryBudget = 0.0; // GB

private:
  vtkTerrainDistanceSynthesis(const vtkTerrainDistanceSynthesis&) = delete;
  void operator=(const vtkTerrainDistanceSynthesis&) = delete;
};
