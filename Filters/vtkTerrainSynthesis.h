/**
 * @class vtkTerrainSynthesis
 * @brief The whole sketch-driven synthesis as one filter.
 *
 * Input port 0: one or more exemplar heightfields (images with "Elevation").
 * Input port 1: the sketch: an image (grey sketch map, RGB stroke map with red
 * ridges and blue valleys, or a DEM used as the target), or poly-lines in metres
 * in the output's raster frame (lower-left cell centre at (0, 0)) with a
 * FeatureType cell array and optional Elevation point array (height constraints).
 * The set-up (output grid, exemplar resampling to its cell size, features,
 * memory check, target) is tsynth::prepareSynthesis, the same as `tsynth synth`. Output port 0: the
 * terrain (2D image, "Elevation" in metres) with PatchId (the placement that wrote each cell, -1
 * for none; the placement order), SeamMask, PlacementOrder, MatchCost and PatchColour (0-11,
 * different for patches that touch: tsynth::patchColours) arrays. Output port 1: a
 * table of the placements (order, feature or fill, exemplar, variant, source position, output cell,
 * match cost, seam cost, vertical offset). Output port 2: the sketch's feature tree as the
 * synthesis follows it, in metres on the terrain's grid (DESIGN.md's feature-graph poly-data).
 * Output port 3: the seams as poly-lines along the borders between patches, with an Elevation point
 * array for Warp By Scalar. With DebugOutputs on, output port 4: the report (a Figure and a
 * Value column: the quality, landform and legibility figures of `tsynth synth --report`), and
 * output port 5: the construction image (Target, TargetConfidence, and Patches: the terrain
 * before the final corrections); off, both are empty. Output port 6: the lines the drawing implies
 * (the divides between facing valleys, shaped as ridges in the target; in metres, as port 2),
 * empty when it implies none. The stages are the other Terrain Synthesis
 * filters' kernels: feature extraction, candidate pools and matching (OpenCL or CPU), graph-cut
 * merging. Optional input port 2: style regions, an image of integer labels resized to the output;
 * label L is served by exemplar L unless AddRegionMap("L=E1,E2"). Optional input port 3: the
 * exemplars' candidate pool, the Terrain Candidate Builder's table, built from the exemplars on
 * the output's cells at the same PatchSize: the synthesis matches its feature patches from it
 * (as the Terrain Patch Matcher does) instead of the pool it would prepare. With the builder's
 * FeatureTrees from a Terrain Feature Extractor at the synthesis' PPA settings (ridges and
 * valleys, Significance 0), the terrain is the same, bit for bit
 * (Examples/states/stages.pvsm).
 *
 * On ParaView's parallel engine each rank's outputs hold its piece. While they do, the filter
 * keeps the whole outputs of its last synthesis, so that a request for another extent of the same
 * synthesis (File > Save Data's writer asking for its tile rows after the view asked for pieces)
 * is cut from them instead of synthesised again. Whatever changes the terrain (inputs' content,
 * properties) makes it synthesise anew; in one process, where the outputs hold the whole, nothing
 * is kept.
 */
#pragma once

#include "Core/Memory.h"
#include "Core/PatchSize.h"
#include "Synthesis/OptionLimits.h"
#include "TerrainSynthesisFiltersModule.h"

#include <vtkImageAlgorithm.h>

#include <memory>
#include <string>
#include <vector>

namespace tsynth
{
struct PlacementRecord;  // Synthesis/TileRecord.h
struct SynthesisResult;  // Synthesis/Synthesiser.h
struct SynthesisRequest; // Synthesis/SynthesisRequest.h
}

class vtkImageData;
class vtkPolyData;
class vtkTable;

class TERRAINSYNTHESISFILTERS_EXPORT vtkTerrainSynthesis : public vtkImageAlgorithm
{
public:
  static vtkTerrainSynthesis* New();
  vtkTypeMacro(vtkTerrainSynthesis, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Backends
  {
    AUTO = 0, // OpenCL if a device works, else the CPU
    OPENCL = 1,
    CPU = 2
  };
  enum MergeModes
  {
    CUT = 0,
    POISSON = 1,
    SHEPARD = 2,
    NEW = 3
  };
  enum FillOrders
  {
    BEST_FIRST = 0,
    CONCENTRIC = 1
  };
  enum Drainages
  {
    NO_DRAINAGE = 0,
    DRAIN_BY_FILLING = 1,
    DRAIN_BY_BREACHING = 2,
    DRAIN_BY_HYBRID = 3
  };

  /// Patch size in cells: 0 (the default) chooses it for the sketch, 80 cells
  /// or 32 for a DEM target (tsynth::patchSizeFor); else a multiple of 4 from
  /// 16 to 512, checked when the filter runs: another size fails the request,
  /// never clamped.
  vtkSetMacro(PatchSize, int);
  vtkGetMacro(PatchSize, int);
  /// Where the matcher runs (default AUTO); every backend gives the same terrain.
  vtkSetClampMacro(Backend, int, AUTO, CPU);
  vtkGetMacro(Backend, int);
  /// Seam removal after each cut (default NEW).
  vtkSetClampMacro(MergeMode, int, CUT, NEW);
  vtkGetMacro(MergeMode, int);
  /// Order of the non-feature filling (default BEST_FIRST).
  vtkSetClampMacro(FillOrder, int, BEST_FIRST, CONCENTRIC);
  vtkGetMacro(FillOrder, int);
  /// Makes every cell drain at the end (default NO_DRAINAGE): depressions
  /// filled, breached or either, from blocks of a quarter patch down to cells.
  vtkSetClampMacro(Drainage, int, NO_DRAINAGE, DRAIN_BY_HYBRID);
  vtkGetMacro(Drainage, int);
  /// Shift each patch to fit what it overlaps (default on; off: patches keep
  /// their own heights).
  vtkSetMacro(VerticalOffset, bool);
  vtkGetMacro(VerticalOffset, bool);
  vtkBooleanMacro(VerticalOffset, bool);
  /// Seam-cost penalty for taking a source within half a patch of an earlier
  /// placement's (default 0.5; 0 off): discourages visible repeats.
  vtkSetClampMacro(Repetition, double, 0.0, tsynth::kMaxRepetitionPenalty);
  vtkGetMacro(Repetition, double);
  /// Tiled synthesis (Kernels/Synthesis/Tiling.h): square tiles of this many
  /// cells, at least two patches (smaller is refused), each synthesised with a
  /// halo of one patch in an order fixed by the tile grid, then the whole
  /// terrain finished at once (default 0: one piece). In one process the filter keeps each
  /// tiled synthesis' record, and the next takes over the tiles it finds unchanged
  /// (GetTilesTakenOver).
  vtkSetClampMacro(TileSize, int, 0, VTK_INT_MAX);
  vtkGetMacro(TileSize, int);
  /// Stop after this many placements and show the terrain as those patches made it, unfinished
  /// (NaN where no patch is yet), so a user steps through the synthesis one patch at a time (the
  /// Placements output lists them; the first N are the whole synthesis' first N). -1 (the
  /// default): every placement, then the finishing. One piece only (TileSize 0); no preview.
  vtkSetClampMacro(PlacementLimit, int, tsynth::kAllPlacementsNumber, VTK_INT_MAX);
  vtkGetMacro(PlacementLimit, int);
  /// Output size in cells; 0 0 (default) takes the sketch image's pixels, or
  /// the poly-lines' frame (their GridSize x CellSize field data) or extent and half a patch.
  vtkSetVector2Macro(OutputSize, int);
  vtkGetVector2Macro(OutputSize, int);
  /// Output cell size in metres; 0 (default) takes the first exemplar's.
  vtkSetClampMacro(CellSize, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(CellSize, double);
  /// Seeds every arbitrary choice: another seed gives another terrain, the same
  /// seed the same terrain (default 0).
  vtkSetClampMacro(Seed, vtkIdType, 0, VTK_ID_MAX);
  vtkGetMacro(Seed, vtkIdType);
  /// Sketched ridges and valleys get this times the relief of the exemplars'
  /// own major ones (1: like them; above 1 for bolder landforms).
  vtkSetClampMacro(LandformRelief, double, tsynth::kMinLandformRelief, tsynth::kMaxLandformRelief);
  vtkGetMacro(LandformRelief, double);
  /// A synthesis estimated to need more memory than this (GB) is refused before
  /// it starts; 0 (default) allows 80% of the machine's physical memory.
  vtkSetClampMacro(MemoryBudget, double, 0.0, tsynth::kMaxMemoryBudgetGB);
  vtkGetMacro(MemoryBudget, double);
  /// Keep what is computed from the exemplars alone (their ridges and valleys,
  /// landform statistics and candidate pool) on disk, keyed by their content, so
  /// that re-running with the same exemplars (a redrawn sketch) skips it
  /// (default on; tsynth::prepareExemplarsCached).
  vtkSetMacro(UseExemplarCache, bool);
  vtkGetMacro(UseExemplarCache, bool);
  vtkBooleanMacro(UseExemplarCache, bool);
  /// Where that cache lives; empty (default): $TSYNTH_CACHE_DIR, else
  /// $XDG_CACHE_HOME/terrainsynthesis, else ~/.cache/terrainsynthesis.
  vtkSetMacro(ExemplarCacheDirectory, std::string);
  vtkGetMacro(ExemplarCacheDirectory, std::string);
  /// Fills the Report table and the Construction image (default off: together they added
  /// 0.1-0.6 s to a 9.5 s synthesis of 1024 x 1024 cells, and the image holds 12 bytes a cell).
  vtkSetMacro(DebugOutputs, bool);
  vtkGetMacro(DebugOutputs, bool);
  vtkBooleanMacro(DebugOutputs, bool);
  /// Show a quick preview first, then the whole synthesis (default off: one update gives the
  /// whole synthesis, as scripts expect). On, an update produces the preview of
  /// tsynth::synthesisePreview (cells 4 times coarser, patches 4 times smaller: the same
  /// landforms in the same places, less detail; about a tenth of the time), upsampled onto the
  /// terrain's grid, and starts the whole synthesis in the background. GetNeedsUpdate() says
  /// when it is done, and the next update shows it, bit for bit what the filter gives with
  /// this off. A change to an input or a property stops the refinement under way and starts
  /// again from a preview; until a refinement lands the output keeps the last preview. In the
  /// preview only the terrain (Elevation; no diagnostic arrays) and the sketch's and implied lines
  /// hold data. Patches under 32 cells have no coarser level: the whole synthesis is then done at
  /// once.
  vtkSetMacro(PreviewFirst, bool);
  vtkGetMacro(PreviewFirst, bool);
  vtkBooleanMacro(PreviewFirst, bool);
  /// True, once, when a background refinement has finished: the filter is then marked modified
  /// so that the next update shows it. ParaView's GUI asks every 100 ms (the LiveSource hint)
  /// and re-renders; a script calls WaitForRefinement() and then this.
  bool GetNeedsUpdate();
  /// Blocks until the background refinement (if any) has finished or stopped.
  void WaitForRefinement();
  /// What the outputs hold: "none", "preview", "final", or "placements" (stopped after
  /// PlacementLimit patches, unfinished).
  const char* GetOutputLevel() { return this->OutputLevel.c_str(); }

  void RemoveAllExemplars() { this->RemoveAllInputConnections(0); }
  /// Optional style regions (port 2): an image of integer labels over the
  /// output; label L is served by exemplar L unless a map "L=E1,E2" says otherwise.
  void SetRegionsConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(2, output); }
  void AddRegionMap(const char* map)
  {
    this->RegionMaps.emplace_back(map != nullptr ? map : "");
    this->Modified();
  }
  void RemoveAllRegionMaps()
  {
    this->RegionMaps.clear();
    this->Modified();
  }
  void SetSketchConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }
  /// Optional candidate pool (port 3): the Terrain Candidate Builder's table.
  void SetCandidatePoolConnection(vtkAlgorithmOutput* output)
  {
    this->SetInputConnection(3, output);
  }
  const char* GetBackendUsed() { return this->BackendUsed.c_str(); }
  /// With a TileSize, in one process: how many tile passes the last synthesis took over from
  /// the one before it instead of placing them (Kernels/Synthesis/TileRecord.h). The filter
  /// keeps each tiled synthesis' record, so after an edit of the sketch only the tiles the
  /// edit reaches are placed again; the terrain is the same bits as a fresh filter's.
  vtkGetMacro(TilesTakenOver, vtkIdType);

  vtkImageData* GetTerrain();
  /// The terrain, as VTK's image filters name their output.
  vtkImageData* GetOutput() { return this->GetTerrain(); }
  vtkTable* GetPlacements();
  vtkPolyData* GetSketchFeatures();
  vtkPolyData* GetSeams();
  vtkTable* GetReport();
  vtkImageData* GetConstruction();
  vtkPolyData* GetImpliedLines();

protected:
  vtkTerrainSynthesis();
  ~vtkTerrainSynthesis() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  // The terrain (output 0) and the construction are images, the other outputs poly-lines and
  // tables: vtkImageAlgorithm's request methods, each overridden (its defaults would
  // allocate an image on every output).
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  // PreviewFirst's update: the refinement's result if it answers this request, else a preview
  // and a new refinement.
  void PreviewOrRefined(vtkInformationVector** inputVector, vtkInformationVector* outputVector);
  void StopRefinement();
  // The non-preview update: the kept whole outputs cut to this request's piece if they answer
  // it, else a synthesis (whose whole outputs are kept if the outputs hold only a piece).
  void SynthesiseOrCut(vtkInformationVector** inputVector, vtkInformationVector* outputVector);
  // The properties' request, with the tile record the synthesis would keep and the last one
  // it may take tiles from (for the memory estimate).
  tsynth::SynthesisRequest RequestWithRecord();
  // Keeps a synthesis' tile record (null if it kept none) for the next, and its count.
  void KeepRecord(const tsynth::SynthesisResult& r);

  // The synthesis options' defaults are the options table's (tsynth::synthesisOptionRows), set
  // in the constructor.
  int PatchSize;
  int Backend;
  int MergeMode;
  int FillOrder;
  int Drainage;
  bool VerticalOffset;
  double Repetition;
  int TileSize;
  int PlacementLimit;
  int OutputSize[2];
  double CellSize;
  vtkIdType Seed;
  double MemoryBudget;
  double LandformRelief;
  bool DebugOutputs = false;
  bool PreviewFirst = false;
  std::string OutputLevel = "none";
  bool UseExemplarCache;
  std::string ExemplarCacheDirectory;
  std::string BackendUsed;
  std::vector<std::string> RegionMaps;
  // The last tiled synthesis' record, for the next (null: none), and what it took over.
  std::shared_ptr<const tsynth::PlacementRecord> TileRecord;
  vtkIdType TilesTakenOver = 0;

public:
  class vtkRefinement;   // the whole synthesis under way in the background (PreviewFirst)
  class vtkWholeOutputs; // the last synthesis' whole outputs, while the outputs hold a piece

private:
  vtkRefinement* Refinement = nullptr;
  vtkWholeOutputs* WholeOutputs = nullptr;
  void ForgetWholeOutputs();
  vtkTerrainSynthesis(const vtkTerrainSynthesis&) = delete;
  void operator=(const vtkTerrainSynthesis&) = delete;
};
