/**
 * @class vtkTerrainPatchExtractor
 * @brief The patch a match names, cut from its exemplar, with its core and
 * vertical offset: what the Terrain Graph-Cut Merger places.
 *
 * Input port 0: the terrain so far (2D image, "Elevation"; an optional uint8
 * point array "Filled" marks the cells patches wrote, else every valid cell
 * counts; an optional uint8 "Line" marks sketched line cells, and "Frozen" the
 * cells earlier tiles settled). Input port 1: the
 * exemplar heightfields, in the order the matcher had them. Input port 2: the
 * Terrain Patch Matcher's table of matches (vtkTerrainPatchMatcher output 0).
 *
 * The match of row Rank is cut from its exemplar as its variant (rotation or
 * mirror) sees it, patch size square, centred on the match's centre (the
 * table's CellX, CellY), exactly as the synthesis cuts its patches; cells off
 * the exemplar or on its nodata are invalid, and so, for a fill (non-feature)
 * match, are the filled Line and Frozen cells under it, which the synthesis'
 * fill patches leave as they are (protectKeptCells). With VerticalOffset, the
 * patch is shifted to continue what it overlaps, as the synthesis shifts it
 * (fitPatchOffset): least squares over the filled cells under it and, where
 * the terrain has the "Target" (and "TargetConfidence") point arrays the
 * Terrain Synthesis filter's construction output carries, the target's
 * low-pass on the empty part; without a target, the mean difference over the
 * filled cells (with under 5% of the patch on filled cells, none). Output: the patch as an
 * image on the terrain's cell size, with its origin on the window the matcher matched (the table's
 * PatchCell), so the merger places it there; point arrays Elevation, Valid (where cells are
 * invalid) and Core (uint8, 1 on the cells a feature patch owns whatever the
 * seam: a disc of an eighth of a patch round its centre, the Line cells within
 * a quarter patch and, when the matches give its FeatureType, a strip along its
 * own ridge or valley within a quarter patch (found in its exemplar with the
 * synthesis' PPA settings); all 0 for a non-feature match); field data
 * VerticalOffset (metres), Exemplar, Variant, Rank.
 *
 * Kernel: Kernels/Synthesis/PatchExtraction.h (extractPatch, protectKeptCells,
 * fitPatchOffset, featureCore, ownLineOffsets, addOwnLineStrip), which the
 * synthesis' placement uses for every patch.
 */
#pragma once

#include "TerrainSynthesisFiltersModule.h"

#include <vtkImageAlgorithm.h>

class TERRAINSYNTHESISFILTERS_EXPORT vtkTerrainPatchExtractor : public vtkImageAlgorithm
{
public:
  static vtkTerrainPatchExtractor* New();
  vtkTypeMacro(vtkTerrainPatchExtractor, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The row of the matches to cut (default 0: the best). A rank past the table's rows fails
  /// the request with a sentence saying how many there are.
  vtkSetClampMacro(Rank, int, 0, VTK_INT_MAX);
  vtkGetMacro(Rank, int);
  /// Shift the patch to fit what it overlaps (default on, as the synthesis does).
  vtkSetMacro(VerticalOffset, bool);
  vtkGetMacro(VerticalOffset, bool);
  vtkBooleanMacro(VerticalOffset, bool);

  /// Per-port clearing, for ParaView's multiple-input property.
  void RemoveAllExemplars() { this->RemoveAllInputConnections(1); }

protected:
  vtkTerrainPatchExtractor();
  ~vtkTerrainPatchExtractor() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  // The options table's defaults (tsynth::patchExtractionOptionRows).
  int Rank;
  bool VerticalOffset;

private:
  vtkTerrainPatchExtractor(const vtkTerrainPatchExtractor&) = delete;
  void operator=(const vtkTerrainPatchExtractor&) = delete;
};
