/**
 * @class vtkTerrainReader
 * @brief Reads a DEM (GeoTIFF, 8/16-bit PNG, SRTM .hgt, ESRI ASCII grid, any
 * single-band raster GDAL reads, or .vti) into a 2D image in metres.
 *
 * Output: point scalars "Elevation" (float, metres), "Valid" (uint8) when the
 * file has nodata, spacing = cell size in metres, origin at the lower-left cell
 * centre, and the georeference as field data ("CRS", "GeoTransform").
 * Vertical units, cell size and normalised ranges come from a NAME.json sidecar
 * beside the file, from the file itself, or from the properties below, which
 * override both.
 *
 * Kernel: Kernels/Core/HeightfieldIO.h (readHeightfield); .vti through
 * Filters/TerrainFileIO.h.
 */
#pragma once

#include "TerrainSynthesisFiltersModule.h"

#include "Core/HeightfieldIO.h" // the read options table and its limits

#include <vtkImageAlgorithm.h>

#include <string>

class TERRAINSYNTHESISFILTERS_EXPORT vtkTerrainReader : public vtkImageAlgorithm
{
public:
  static vtkTerrainReader* New();
  vtkTypeMacro(vtkTerrainReader, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  // tsynth::ZUnit's values (checked in the .cxx).
  enum ZUnits
  {
    ZUNIT_AUTO = 0,
    ZUNIT_METRES = 1,
    ZUNIT_FEET = 2
  };

  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);

  ///@{
  /// Unit of the stored heights: 0 auto (sidecar, then file, else metres), 1 metres, 2 feet.
  vtkSetClampMacro(ZUnit, int, ZUNIT_AUTO, ZUNIT_FEET);
  vtkGetMacro(ZUnit, int);
  ///@}

  ///@{
  /// Cell size in metres; 0 (default) takes it from the sidecar or the georeference.
  vtkSetClampMacro(CellSize, double, 0.0, tsynth::kMaxCellSizeMetres);
  vtkGetMacro(CellSize, double);
  ///@}

  ///@{
  /// Read NAME.json beside the file (default on).
  vtkSetMacro(UseSidecar, bool);
  vtkGetMacro(UseSidecar, bool);
  vtkBooleanMacro(UseSidecar, bool);
  ///@}

  ///@{
  /// For 8/16-bit images that store a normalised range: value 0 maps to ZMin and
  /// the type's maximum to ZMax. Used only when UseNormalisedRange is on.
  vtkSetMacro(UseNormalisedRange, bool);
  vtkGetMacro(UseNormalisedRange, bool);
  vtkBooleanMacro(UseNormalisedRange, bool);
  /// Both within +-1e6 (metres or feet): beyond any height on Earth.
  vtkSetClampMacro(ZMin, double, -tsynth::kMaxNormalisedHeight, tsynth::kMaxNormalisedHeight);
  vtkGetMacro(ZMin, double);
  vtkSetClampMacro(ZMax, double, -tsynth::kMaxNormalisedHeight, tsynth::kMaxNormalisedHeight);
  vtkGetMacro(ZMax, double);
  ///@}

  /// 1 if the file exists and is a raster this reader understands.
  int CanReadFile(const char* fileName);

protected:
  vtkTerrainReader();
  ~vtkTerrainReader() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  char* FileName = nullptr;
  // The read options table's defaults (tsynth::readOptionRows), set in the constructor.
  int ZUnit;
  double CellSize;
  bool UseSidecar;
  bool UseNormalisedRange;
  double ZMin;
  double ZMax;

private:
  vtkTerrainReader(const vtkTerrainReader&) = delete;
  void operator=(const vtkTerrainReader&) = delete;
};
