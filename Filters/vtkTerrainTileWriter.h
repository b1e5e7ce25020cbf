/**
 * @class vtkTerrainTileWriter
 * @brief Writes a heightfield image as tiles that share their edge rows and
 * columns (kernel: Kernels/Core/TileExport.h, as `tsynth convert --tile-size`).
 *
 * The FileName's extension chooses the format:
 * - NAME.vrt: float32 GeoTIFF tiles NAME_x<column>_y<row>.tif and NAME.vrt, a
 *   GDAL virtual mosaic that gives the heights back bit for bit;
 * - NAME.png: 16-bit PNG tiles (Unreal's tiled landscape: NAME_x<column>_y<row>,
 *   rows north first);
 * - NAME.raw or NAME.r16: 16-bit little-endian RAW tiles (Unity's terrain tools:
 *   NAME_<x>_<z> from the south-west, rows south first).
 * 16-bit tiles are 2^k + 1 samples a side and share one height scale. Each tile
 * has a NAME.json sidecar with its placement, its height range and, for 16-bit
 * tiles, the engines' import scales. All files appear together or none.
 *
 * On ParaView's MPI engine (pvbatch, pvserver) every rank writes a contiguous
 * share of the tile rows: it asks its input for just the rows those tiles need
 * (a source that produces sub-extents, as the Terrain Synthesis filter does,
 * makes only them), the ranks agree on the terrain's frame (nodata, and the
 * 16-bit height scale) and rank 0 writes the mosaic. The files are those of
 * one process, byte for byte. A rank that fails makes every rank fail with its
 * sentence, and none publishes its tiles.
 */
#pragma once

#include "TerrainSynthesisFiltersModule.h"

#include "Core/TileExport.h" // the options table and its limits

#include <vtkWriter.h>

class vtkImageData;

class TERRAINSYNTHESISFILTERS_EXPORT vtkTerrainTileWriter : public vtkWriter
{
public:
  static vtkTerrainTileWriter* New();
  vtkTypeMacro(vtkTerrainTileWriter, vtkWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The mosaic or tile name: NAME.vrt, NAME.png, NAME.raw or NAME.r16.
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  ///@}

  ///@{
  /// Samples per tile side (default tsynth::kDefaultTileSize, 1025: Unity's and a common
  /// Unreal size); neighbouring tiles share one row or column. 16-bit tiles need 2^k + 1,
  /// 33 to 8193.
  vtkSetClampMacro(TileSize, int, tsynth::kSmallestTile, tsynth::kLargestTile);
  vtkGetMacro(TileSize, int);
  ///@}

  /// How many tiles the last Write() wrote (0 if it failed).
  vtkGetMacro(TilesWritten, int);

protected:
  vtkTerrainTileWriter();
  ~vtkTerrainTileWriter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  vtkTypeBool ProcessRequest(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  void WriteData() override;
  void WriteShare(vtkImageData* image);

  char* FileName = nullptr;
  int TileSize; // the options table's default (tsynth::tileExportOptionRows)
  int TilesWritten = 0;

private:
  vtkTerrainTileWriter(const vtkTerrainTileWriter&) = delete;
  void operator=(const vtkTerrainTileWriter&) = delete;
};
