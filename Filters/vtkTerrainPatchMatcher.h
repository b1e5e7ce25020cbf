/**
 * @class vtkTerrainPatchMatcher
 * @brief The best exemplar patches for one place of a target, with a cost map.
 *
 * Input port 0: the target heightfield ("Elevation"; an optional point array,
 * KnownArray, "Known" by default, is non-zero on cells already synthesised, whose
 * heights the overlap term compares; without it every cell counts as known). Input port 1: one or
 * more exemplar heightfields; port 2 (optional): their feature trees; port 3
 * (optional): their candidate pool, the Terrain Candidate Builder's table
 * (vtkTerrainCandidateBuilder), read back exactly instead of building the pool
 * again, so the builder and the matcher chain; it must have been built from the
 * same exemplars at the same patch size, and then the feature trees are not read.
 * Feature mode takes the target's feature site (PPA ridges and valleys, end and
 * branch nodes and path points) nearest to (SiteX, SiteY) and scores every
 * candidate variant with c = a_f c_f + a_a c_a + a_n c_n + a_o c_o (Tasse's
 * thesis, 3.4.1); non-feature mode searches every offset of every exemplar in
 * every variant by masked SSD (coarse-to-fine). Both run on OpenCL (any device,
 * PoCL on a CPU) or on the CPU reference; Auto falls back to the CPU with a
 * warning. Output 0: a table of the K best per exemplar (Rank, Exemplar,
 * Variant, X, Y in the exemplar's metres, Cost, Feature, FeatureType (+1 a
 * ridge, -1 a valley, 0 a fill match), CellX, CellY: the
 * centre in the exemplar's cells, exactly; field data PatchCell, the target
 * cell the window's lower-left corner lies on, and PatchSize): what the Terrain
 * Patch Extractor cuts a patch from. Output 1: a cost map
 * over the first exemplar (MatchCost: the lowest cost of any variant centred on
 * each cell; NaN where there is no candidate), to see where good matches lie.
 *
 * Kernel: Kernels/Matching/SiteMatch.h (matchAtSite, over
 * Kernels/Matching/PatchMatcher.h).
 */
#pragma once

#include "Core/PatchSize.h"
#include "Matching/MatcherLimits.h"
#include "TerrainSynthesisFiltersModule.h"

#include <vtkImageAlgorithm.h>

class vtkImageData;
class vtkTable;

class TERRAINSYNTHESISFILTERS_EXPORT vtkTerrainPatchMatcher : public vtkImageAlgorithm
{
public:
  static vtkTerrainPatchMatcher* New();
  vtkTypeMacro(vtkTerrainPatchMatcher, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Modes
  {
    FEATURE = 0,
    NON_FEATURE = 1
  };
  enum Backends
  {
    AUTO = 0,
    OPENCL = 1,
    CPU = 2
  };

  vtkSetClampMacro(Mode, int, FEATURE, NON_FEATURE);
  vtkGetMacro(Mode, int);
  vtkSetClampMacro(Backend, int, AUTO, CPU);
  vtkGetMacro(Backend, int);
  /// Patch size in cells (default 80), 16 to 512 as the synthesis takes; another size fails
  /// the request with a sentence saying so (never clamped). A multiple of 4 gets the dense
  /// search's 4 x 4 coarse pass; other sizes are searched exhaustively (slower, same ranking).
  vtkSetMacro(PatchSize, int);
  vtkGetMacro(PatchSize, int);
  /// Candidates kept per exemplar (default 8).
  vtkSetClampMacro(K, int, 1, tsynth::kMaxCandidatesKept);
  vtkGetMacro(K, int);
  /// Where in the target to match, metres in the target's frame.
  vtkSetVector2Macro(Site, double);
  vtkGetVector2Macro(Site, double);
  ///@{
  /// Cost weights a_f, a_a, a_n, a_o (defaults: the synthesis' own, from
  /// tsynth::matcherOptionRows), 0 to 1e6: a negative weight would reward a mismatch.
  vtkSetClampMacro(FeatureWeight, double, 0.0, tsynth::kMaxMatchWeight);
  vtkGetMacro(FeatureWeight, double);
  vtkSetClampMacro(AngleWeight, double, 0.0, tsynth::kMaxMatchWeight);
  vtkGetMacro(AngleWeight, double);
  vtkSetClampMacro(NoiseWeight, double, 0.0, tsynth::kMaxMatchWeight);
  vtkGetMacro(NoiseWeight, double);
  vtkSetClampMacro(OverlapWeight, double, 0.0, tsynth::kMaxMatchWeight);
  vtkGetMacro(OverlapWeight, double);
  ///@}
  /// Compare overlaps up to a vertical offset (default: the synthesis' own).
  vtkSetMacro(VerticalOffset, bool);
  vtkGetMacro(VerticalOffset, bool);
  vtkBooleanMacro(VerticalOffset, bool);

  /// The backend actually used by the last update ("opencl (device)" or "cpu").
  const char* GetBackendUsed() { return this->BackendUsed.c_str(); }

  /// Per-port clearing, for ParaView's multiple-input properties.
  void RemoveAllExemplars() { this->RemoveAllInputConnections(1); }
  void RemoveAllFeatureTrees() { this->RemoveAllInputConnections(2); }
  /// The Candidate Builder's table for port 3 (optional; nullptr: none).
  void SetCandidatePoolConnection(vtkAlgorithmOutput* output)
  {
    this->SetInputConnection(3, output);
  }

  /// The target's point array marking known cells (default "Known"; empty: every cell is
  /// known; a name the target lacks is an error unless it is the default).
  static constexpr const char* kDefaultKnownArray = "Known";
  vtkSetStringMacro(KnownArray);
  vtkGetStringMacro(KnownArray);

  vtkTable* GetMatches();
  vtkImageData* GetCostMap();

protected:
  vtkTerrainPatchMatcher();
  ~vtkTerrainPatchMatcher() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  // Output 0 is a table, output 1 an image: vtkImageAlgorithm's request methods,
  // each overridden (its defaults would allocate an image on output 0).
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int Mode = FEATURE;
  // The options table's defaults (tsynth::matcherOptionRows), set in the constructor.
  int Backend;
  int PatchSize;
  int K;
  double Site[2] = { 0.0, 0.0 };
  double FeatureWeight;
  double AngleWeight;
  double NoiseWeight;
  double OverlapWeight;
  bool VerticalOffset;
  char* KnownArray = nullptr;
  std::string BackendUsed;

private:
  vtkTerrainPatchMatcher(const vtkTerrainPatchMatcher&) = delete;
  void operator=(const vtkTerrainPatchMatcher&) = delete;
};
