/**
 * @class vtkTerrainCandidateBuilder
 * @brief The matcher's pool of feature candidates, as a table a user can inspect.
 *
 * Input port 0: one or more exemplar heightfields (images with "Elevation").
 * Input port 1 (optional): their feature trees (vtkTerrainFeatureExtractor
 * output), in the same order; without them ridges and valleys are extracted
 * as the synthesis finds them (tsynth::exemplarPpaOptions: every line, Significance
 * 0), so the table is the Terrain Synthesis' own pool. Output: a vtkTable with one row per
 * candidate variant (each feature site in 8 rotations by 45 degrees and 2 mirrors): the whole pool,
 * exactly, in the columns Filters/CandidatePoolTable.h lists (Exemplar, Site, Variant, Kind,
 * FeatureType, Arms, X and Y in metres, Angle0..3 in degrees, and the descriptors the matcher
 * compares), so that the Terrain Patch Matcher can take it as its Candidate Pool instead of
 * building the pool again. Tasse's thesis, 3.4 (candidates, rotations, mirrors, noise).
 *
 * Kernel: Kernels/Matching/CandidatePool.h (buildCandidatePool).
 */
#pragma once

#include "Core/PatchSize.h"
#include "TerrainSynthesisFiltersModule.h"

#include <vtkTableAlgorithm.h>

class TERRAINSYNTHESISFILTERS_EXPORT vtkTerrainCandidateBuilder : public vtkTableAlgorithm
{
public:
  static vtkTerrainCandidateBuilder* New();
  vtkTypeMacro(vtkTerrainCandidateBuilder, vtkTableAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Patch size in cells (default 80, for 90 m data), 16 to 512 as the synthesis
  /// takes; another size fails the request with a sentence saying so (never clamped). Any
  /// size in the range works (the synthesis also asks a multiple of 4).
  vtkSetMacro(PatchSize, int);
  vtkGetMacro(PatchSize, int);
  ///@}

  /// Adds a feature tree for port 1 (one per exemplar, same order).
  void AddFeatureTreeConnection(vtkAlgorithmOutput* output) { this->AddInputConnection(1, output); }
  /// Per-port clearing, for ParaView's multiple-input properties.
  void RemoveAllExemplars() { this->RemoveAllInputConnections(0); }
  void RemoveAllFeatureTrees() { this->RemoveAllInputConnections(1); }

protected:
  vtkTerrainCandidateBuilder();
  ~vtkTerrainCandidateBuilder() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int PatchSize = tsynth::kDefaultSynthesisPatch;

private:
  vtkTerrainCandidateBuilder(const vtkTerrainCandidateBuilder&) = delete;
  void operator=(const vtkTerrainCandidateBuilder&) = delete;
};
