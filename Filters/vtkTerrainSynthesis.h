/**
 * @class vtkTerrainSynthesis
 * @brief The whole sketch-driven synthesis as one filter.
 *
 * Input port 0: one or more exemplar heightfields (images with "Elevation").
 * Input port 1: the sketch: an image (grey sketch map, RGB stroke map with red
 * ridges and blue valleys, or a DEM used as the target), or poly-lines with a
 * FeatureType cell array. Output port 0: the terrain (2D image, "Elevation" in
 * metres) with PatchId (the placement that wrote each cell, -1 for none; the
 * placement order), SeamMask, PlacementOrder and MatchCost arrays. Output port 1:
 * a table of the placements (order, feature or fill, exemplar, variant, source
 * position, output cell, match cost, seam cost, vertical offset).
 * The stages are the other Terrain Synthesis filters' kernels: feature
 * extraction, candidate pools and matching (OpenCL or CPU), graph-cut merging.
 * Optional input port 2: style regions, an image of integer labels resized to
 * the output; label L is served by exemplar L unless AddRegionMap("L=E1,E2").
 */
#pragma once

#include "TerrainSynthesisFiltersModule.h"

#include <vtkAlgorithm.h>

#include <string>
#include <vector>

class vtkImageData;
class vtkTable;

class TERRAINSYNTHESISFILTERS_EXPORT vtkTerrainSynthesis : public vtkAlgorithm
{
public:
  static vtkTerrainSynthesis* New();
  vtkTypeMacro(vtkTerrainSynthesis, vtkAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Patch size in cells (multiple of 4; default 80).
  vtkSetClampMacro(PatchSize, int, 16, 512);
  vtkGetMacro(PatchSize, int);
  /// 0 auto (OpenCL if usable), 1 OpenCL, 2 CPU.
  vtkSetClampMacro(Backend, int, 0, 2);
  vtkGetMacro(Backend, int);
  /// 0 cut, 1 poisson, 2 shepard, 3 new (default).
  vtkSetClampMacro(MergeMode, int, 0, 3);
  vtkGetMacro(MergeMode, int);
  /// 0 best-first (default), 1 concentric.
  vtkSetClampMacro(FillOrder, int, 0, 1);
  vtkGetMacro(FillOrder, int);
  /// Output size in cells; 0 0 (default) takes the sketch's pixels.
  vtkSetVector2Macro(OutputSize, int);
  vtkGetVector2Macro(OutputSize, int);
  /// Output cell size in metres; 0 (default) takes the first exemplar's.
  vtkSetClampMacro(CellSize, double, 0.0, 1.0e6);
  vtkGetMacro(CellSize, double);

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
  const char* GetBackendUsed() { return this->BackendUsed.c_str(); }

  vtkImageData* GetTerrain();
  vtkTable* GetPlacements();
  vtkTypeBool ProcessRequest(vtkInformation*,
    vtkInformationVector**,
    vtkInformationVector*) override;

protected:
  vtkTerrainSynthesis();
  ~vtkTerrainSynthesis() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformationVector** inputVector, vtkInformationVector* outputVector);
  int RequestData(vtkInformationVector** inputVector, vtkInformationVector* outputVector);

  int PatchSize = 80;
  int Backend = 0;
  int MergeMode = 3;
  int FillOrder = 0;
  int OutputSize[2] = { 0, 0 };
  double CellSize = 0.0;
  std::string BackendUsed;
  std::vector<std::string> RegionMaps;

private:
  vtkTerrainSynthesis(const vtkTerrainSynthesis&) = delete;
  void operator=(const vtkTerrainSynthesis&) = delete;
};
