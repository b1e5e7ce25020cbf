// The Terrain Reader (Filters/vtkTerrainReader.h): metres and georeference from
// any DEM GDAL reads, images of other readers in degrees, unit overrides, and
// a failed request for a file it cannot read.
// An image as ParaView's GDAL Raster Reader makes it from a geographic DEM: one
// height per cell, the spacing in degrees and the CRS as a PROJ string.
#include "FilterTesting.h"
#include "TerrainImageConversion.h"
#include "TestData.h"
#include "vtkTerrainReader.h"

#include "Core/Error.h"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>

#include <gtest/gtest.h>

#include <cmath>
#include <string>

TEST(Filters, ReaderGivesMetresSpacingAndGeoreference)
{
  TSYNTH_SKIP_WITHOUT(tsynth::test::realDem("mount_jackson_n39_w107_3arc.tif"));
  vtkNew<vtkTerrainReader> reader;
  reader->SetFileName(tsynth::test::realDem("mount_jackson_n39_w107_3arc.tif").c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  int dims[3];
  image->GetDimensions(dims);
  EXPECT_EQ(dims[0], 1201);
  EXPECT_EQ(dims[1], 1201);
  EXPECT_EQ(dims[2], 1);
  double spacing[3];
  image->GetSpacing(spacing);
  EXPECT_NEAR(spacing[0], 71.5, 0.5);
  EXPECT_NEAR(spacing[1], 92.5, 0.3);
  vtkDataArray* z = image->GetPointData()->GetArray("Elevation");
  ASSERT_NE(z, nullptr);
  EXPECT_EQ(z->GetDataType(), VTK_FLOAT);
  EXPECT_DOUBLE_EQ(z->GetRange()[0], 1897.0);
  EXPECT_DOUBLE_EQ(z->GetRange()[1], 4385.0);
  EXPECT_EQ(image->GetPointData()->GetArray("Valid"), nullptr); // no nodata in this tile
  auto* crs = vtkStringArray::SafeDownCast(image->GetFieldData()->GetAbstractArray("CRS"));
  ASSERT_NE(crs, nullptr);
  EXPECT_NE(crs->GetValue(0).find("WGS 84"), std::string::npos);
  ASSERT_NE(image->GetFieldData()->GetArray("GeoTransform"), nullptr);
  EXPECT_NEAR(image->GetFieldData()->GetArray("GeoTransform")->GetComponent(0, 0), -107.0, 0.01);
}

// An image as ParaView's GDAL Raster Reader makes it from a geographic DEM: one
// height per cell, the spacing in degrees and the CRS as a PROJ string.
vtkSmartPointer<vtkImageData> gdalReaderImage(const char* projection, double spacing)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(11, 11, 1); // 10 x 10 cells
  image->SetSpacing(spacing, spacing, 1.0);
  image->SetOrigin(-107.0, 39.0, 0.0);
  vtkNew<vtkFloatArray> z;
  z->SetName("Elevation");
  z->SetNumberOfTuples(100);
  for (vtkIdType k = 0; k < 100; ++k)
  {
    z->SetValue(k, static_cast<float>(2000 + k));
  }
  image->GetCellData()->SetScalars(z);
  vtkNew<vtkStringArray> crs;
  crs->SetName("MAP_PROJECTION");
  crs->InsertNextValue(projection);
  image->GetFieldData()->AddArray(crs);
  return image;
}

TEST(Filters, ImagesInDegreesFromOtherReadersAreReadInMetres)
{
  // 3 arc-seconds at latitude 39: the Terrain Reader's cell size for the same
  // grid (ReaderGivesMetresSpacingAndGeoreference).
  const double arcSeconds3 = 3.0 / 3600.0;
  const tsynth::Heightfield geographic =
    tsynth::imageToHeightfield(gdalReaderImage("+proj=longlat +datum=WGS84 +no_defs", arcSeconds3));
  EXPECT_EQ(geographic.width, 10);
  EXPECT_NEAR(geographic.cellX, 72.0, 0.5);
  EXPECT_NEAR(geographic.cellY, 92.5, 0.3);
  EXPECT_TRUE(geographic.georef.isGeographic);
  // A projected grid is in metres already, and so is one without a CRS.
  const tsynth::Heightfield projected =
    tsynth::imageToHeightfield(gdalReaderImage("+proj=utm +zone=13 +datum=WGS84", 30.0));
  EXPECT_DOUBLE_EQ(projected.cellX, 30.0);
  EXPECT_FALSE(projected.georef.isGeographic);
  const tsynth::Heightfield unknown = tsynth::imageToHeightfield(gdalReaderImage("", 30.0));
  EXPECT_DOUBLE_EQ(unknown.cellY, 30.0);
  const tsynth::Heightfield garbled =
    tsynth::imageToHeightfield(gdalReaderImage("not a projection", 30.0));
  EXPECT_DOUBLE_EQ(garbled.cellX, 30.0);
}

TEST(Filters, ReaderUnitOverride)
{
  TSYNTH_SKIP_WITHOUT(tsynth::test::realDem("alaska.png"));
  vtkNew<vtkTerrainReader> reader;
  reader->SetFileName(tsynth::test::realDem("alaska.png").c_str());
  reader->SetZUnit(vtkTerrainReader::ZUNIT_METRES);
  reader->SetCellSize(10.0);
  reader->Update();
  double spacing[3];
  reader->GetOutput()->GetSpacing(spacing);
  EXPECT_DOUBLE_EQ(spacing[0], 10.0);
  EXPECT_NEAR(reader->GetOutput()->GetPointData()->GetArray("Elevation")->GetRange()[1],
    6180.0 / 0.3048,
    40.0);
}

TEST(Filters, ReaderFailsTheRequestOnBadFiles)
{
  vtkNew<vtkTerrainReader> reader;
  tsynth::test::FilterErrors errors(reader);
  reader->SetFileName("/nonexistent/dem.tif");
  reader->Update();
  EXPECT_NE(errors.text.find("/nonexistent/dem.tif"), std::string::npos) << errors.text;
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPoints(), 0);
  EXPECT_EQ(reader->CanReadFile("/nonexistent/dem.tif"), 0);
  EXPECT_EQ(reader->CanReadFile(tsynth::test::realDem("colorado.png").c_str()), 1);
}
