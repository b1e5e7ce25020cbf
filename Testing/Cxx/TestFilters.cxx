#include "FeatureGraphConversion.h"
#include "TerrainFileIO.h"
#include "TerrainImageConversion.h"
#include "TestData.h"
#include "vtkTerrainFeatureExtractor.h"
#include "vtkTerrainHillshade.h"
#include "vtkTerrainReader.h"

#include "Analysis/Hillshade.h"
#include "Core/Error.h"

#include <vtkCallbackCommand.h>
#include <vtkCellData.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkIdList.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

namespace
{

// Counts error events so a failing request is seen without printing.
struct ErrorCounter
{
  int errors = 0;
  vtkNew<vtkCallbackCommand> callback;
  ErrorCounter()
  {
    callback->SetClientData(this);
    callback->SetCallback([](vtkObject*, unsigned long, void* self, void*)
      { ++static_cast<ErrorCounter*>(self)->errors; });
  }
};

} // namespace

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
  ErrorCounter counter;
  reader->AddObserver(vtkCommand::ErrorEvent, counter.callback);
  reader->SetFileName("/nonexistent/dem.tif");
  reader->Update();
  EXPECT_GE(counter.errors, 1);
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPoints(), 0);
  EXPECT_EQ(reader->CanReadFile("/nonexistent/dem.tif"), 0);
  EXPECT_EQ(reader->CanReadFile(tsynth::test::realDem("colorado.png").c_str()), 1);
}

TEST(Filters, HillshadeMatchesTheKernelAndKeepsNodata)
{
  tsynth::Heightfield hf(20, 10);
  hf.cellX = 30.0;
  hf.cellY = 60.0;
  for (int j = 0; j < hf.height; ++j)
  {
    for (int i = 0; i < hf.width; ++i)
    {
      hf.at(i, j) = static_cast<float>(100.0 * std::sin(0.3 * i) + 5.0 * j);
    }
  }
  hf.at(7, 4) = std::numeric_limits<float>::quiet_NaN();
  tsynth::normaliseMask(hf);
  vtkNew<vtkImageData> image;
  tsynth::heightfieldToImage(hf, image);

  vtkNew<vtkTerrainHillshade> shade;
  shade->SetInputData(image);
  shade->SetAltitude(30.0);
  shade->Update();
  vtkImageData* out = shade->GetOutput();
  vtkDataArray* h = out->GetPointData()->GetArray("Hillshade");
  vtkDataArray* s = out->GetPointData()->GetArray("Slope");
  ASSERT_NE(h, nullptr);
  ASSERT_NE(s, nullptr);
  ASSERT_NE(out->GetPointData()->GetArray("Valid"), nullptr);
  EXPECT_STREQ(out->GetPointData()->GetScalars()->GetName(), "Hillshade");

  tsynth::HillshadeOptions o;
  o.altitudeDeg = 30.0;
  const auto expected = tsynth::computeHillshade(hf, o);
  for (vtkIdType k = 0; k < h->GetNumberOfTuples(); ++k)
  {
    const auto kk = static_cast<std::size_t>(k);
    if (std::isnan(expected.shade[kk]))
    {
      EXPECT_TRUE(std::isnan(h->GetComponent(k, 0)));
      continue;
    }
    EXPECT_FLOAT_EQ(static_cast<float>(h->GetComponent(k, 0)), expected.shade[kk]);
    EXPECT_FLOAT_EQ(static_cast<float>(s->GetComponent(k, 0)), expected.slopeDeg[kk]);
  }
  EXPECT_TRUE(std::isnan(h->GetComponent(static_cast<vtkIdType>(hf.index(7, 4)), 0)));
}

TEST(Filters, HillshadeRejectsAThreeDimensionalImage)
{
  vtkNew<vtkImageData> volume;
  volume->SetDimensions(4, 4, 4);
  volume->AllocateScalars(VTK_FLOAT, 1);
  volume->GetPointData()->GetScalars()->SetName("Elevation");
  vtkNew<vtkTerrainHillshade> shade;
  ErrorCounter counter;
  shade->AddObserver(vtkCommand::ErrorEvent, counter.callback);
  shade->SetInputData(volume);
  shade->Update();
  EXPECT_GE(counter.errors, 1);
}

TEST(Filters, VtiRoundTripKeepsHeightsMaskAndGeoreference)
{
  TSYNTH_SKIP_WITHOUT(tsynth::test::realDem("mount_jackson_n39_w107_3arc.tif"));
  tsynth::Heightfield hf =
    tsynth::readTerrainFile(tsynth::test::realDem("mount_jackson_n39_w107_3arc.tif"));
  hf.z[5] = std::numeric_limits<float>::quiet_NaN();
  tsynth::normaliseMask(hf);
  const std::string path = (tsynth::test::scratchDir() / "roundtrip.vti").string();
  tsynth::writeTerrainFile(path, hf);
  {
    // Inline binary, never an appended-data section (see DESIGN.md on expat).
    std::ifstream in(path);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(text.find("AppendedData"), std::string::npos);
    EXPECT_NE(text.find("format=\"binary\""), std::string::npos);
  }
  const tsynth::Heightfield back = tsynth::readTerrainFile(path);
  ASSERT_EQ(back.width, hf.width);
  ASSERT_EQ(back.height, hf.height);
  EXPECT_DOUBLE_EQ(back.cellX, hf.cellX);
  EXPECT_DOUBLE_EQ(back.cellY, hf.cellY);
  EXPECT_EQ(back.validCount(), hf.validCount());
  EXPECT_FALSE(back.isValid(5));
  for (std::size_t k = 0; k < hf.size(); ++k)
  {
    if (hf.isValid(k))
    {
      ASSERT_EQ(back.z[k], hf.z[k]);
    }
  }
  EXPECT_EQ(back.georef.crsWkt, hf.georef.crsWkt);
  EXPECT_EQ(back.georef.geoTransform, hf.georef.geoTransform);

  // A .vti written from VTK goes back to GeoTIFF with its georeference.
  const std::string tif = (tsynth::test::scratchDir() / "from_vti.tif").string();
  tsynth::writeTerrainFile(tif, back);
  tsynth::RasterInfo info;
  tsynth::readTerrainFile(tif, {}, &info);
  EXPECT_TRUE(info.georef.isGeographic);
  EXPECT_NEAR(info.cellX, hf.cellX, 1e-9);
}

TEST(Filters, VtiErrors)
{
  EXPECT_THROW(tsynth::readTerrainFile("/nonexistent/x.vti"), tsynth::Error);
  const std::string junk = (tsynth::test::scratchDir() / "junk.vti").string();
  std::ofstream(junk) << "<VTKFile> not really";
  EXPECT_THROW(tsynth::readTerrainFile(junk), tsynth::Error);
}

// Found while writing the poly-line fuzz target: a cell naming a point past the
// end made every reader of the lines read past the points (a crash or garbage).
TEST(Filters, PolyDataFileWithAPointIdPastTheEndIsDamaged)
{
  const std::string path = (tsynth::test::scratchDir() / "bad-point-id.vtp").string();
  std::ofstream(path) << R"(<?xml version="1.0"?>
<VTKFile type="PolyData" version="1.0" byte_order="LittleEndian" header_type="UInt64">
  <PolyData><Piece NumberOfPoints="3" NumberOfLines="1">
    <Points><DataArray type="Float64" NumberOfComponents="3" format="ascii">0 0 0 1 1 0 2 0 0</DataArray></Points>
    <Lines><DataArray type="Int64" Name="connectivity" format="ascii">0 1 3</DataArray>
      <DataArray type="Int64" Name="offsets" format="ascii">3</DataArray></Lines>
  </Piece></PolyData>
</VTKFile>
)";
  vtkNew<vtkPolyData> lines;
  try
  {
    tsynth::readPolyDataFile(path, lines);
    ADD_FAILURE() << "no error";
  }
  catch (const tsynth::Error& e)
  {
    EXPECT_NE(
      std::string(e.what()).find("refers to point 3 but the file has 3 points"), std::string::npos)
      << e.what();
  }
}

// Found by the polylines fuzz target: a field-data array of an unknown type made
// VTK's reader dereference a null pointer (the process died).
TEST(Filters, PolyDataFileWithAnUnknownArrayTypeIsDamaged)
{
  const std::string path = (tsynth::test::scratchDir() / "bad-array-type.vtp").string();
  std::ofstream(path) << R"(<?xml version="1.0"?>
<VTKFile type="PolyData" version="1.0" byte_order="LittleEndian" header_type="UInt64">
  <PolyData>
    <FieldData><DataArray type="Float82" Name="CellSize" NumberOfTuples="2" format="ascii">30 30</DataArray></FieldData>
    <Piece NumberOfPoints="2" NumberOfLines="1">
      <Points><DataArray type="Float64" NumberOfComponents="3" format="ascii">0 0 0 1 1 0</DataArray></Points>
      <Lines><DataArray type="Int64" Name="connectivity" format="ascii">0 1</DataArray>
        <DataArray type="Int64" Name="offsets" format="ascii">2</DataArray></Lines>
    </Piece>
  </PolyData>
</VTKFile>
)";
  vtkNew<vtkPolyData> lines;
  try
  {
    tsynth::readPolyDataFile(path, lines);
    ADD_FAILURE() << "no error";
  }
  catch (const tsynth::Error& e)
  {
    EXPECT_NE(std::string(e.what()).find("its data array CellSize has no type VTK knows"),
      std::string::npos)
      << e.what();
  }
}

// Found by the polylines fuzz target: a damaged block count in a compressed
// array's header made VTK's parser allocate 8 GB (20 s) for a 5 KB file.
TEST(Filters, PolyDataFileWithADamagedCompressionHeaderIsRefusedAtOnce)
{
  std::vector<tsynth::Polyline> lines(1);
  lines[0].points = { { 1, 1 }, { 20, 25 } };
  vtkNew<vtkPolyData> pd;
  tsynth::featureGraphToPolyData(tsynth::polylineFeatures(lines, 30, 30, 30.0, 30.0), pd);
  const std::string good = (tsynth::test::scratchDir() / "compressed.vtp").string();
  tsynth::writePolyDataFile(good, pd);
  std::ifstream in(good, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // The first binary array's header starts with its block count: make it 2^31 - 1.
  const std::size_t data = text.find('>', text.find("format=\"binary\"")) + 1;
  const std::size_t first = text.find_first_not_of(" \n", data);
  ASSERT_NE(first, std::string::npos);
  text.replace(first, 8, "////fwAA");
  const std::string bad = (tsynth::test::scratchDir() / "compressed-damaged.vtp").string();
  std::ofstream(bad, std::ios::binary) << text;

  vtkNew<vtkPolyData> back;
  EXPECT_NO_THROW(tsynth::readPolyDataFile(good, back));
  try
  {
    tsynth::readPolyDataFile(bad, back);
    ADD_FAILURE() << "no error";
  }
  catch (const tsynth::Error& e)
  {
    EXPECT_NE(std::string(e.what()).find("claims 2147483647 blocks, more than the file holds"),
      std::string::npos)
      << e.what();
  }
}

// Found by the polylines fuzz target: NumberOfComponents="3333333333333333333"
// kept VTK's reader looping over components for minutes.
TEST(Filters, PolyDataFileWithAbsurdComponentCountIsDamaged)
{
  const std::string path = (tsynth::test::scratchDir() / "bad-components.vtp").string();
  std::ofstream(path) << R"(<?xml version="1.0"?>
<VTKFile type="PolyData" version="1.0" byte_order="LittleEndian" header_type="UInt64">
  <PolyData><Piece NumberOfPoints="2" NumberOfLines="1">
    <Points><DataArray type="Float64" NumberOfComponents="3333333333333333333" format="ascii">0 0 0 1 1 0</DataArray></Points>
    <Lines><DataArray type="Int64" Name="connectivity" format="ascii">0 1</DataArray>
      <DataArray type="Int64" Name="offsets" format="ascii">2</DataArray></Lines>
  </Piece></PolyData>
</VTKFile>
)";
  vtkNew<vtkPolyData> lines;
  try
  {
    tsynth::readPolyDataFile(path, lines);
    ADD_FAILURE() << "no error";
  }
  catch (const tsynth::Error& e)
  {
    EXPECT_NE(std::string(e.what()).find("has 3333333333333333333 components (1 to 1024"),
      std::string::npos)
      << e.what();
  }
}

TEST(Filters, FeatureGraphBecomesPolyDataWithSharedNodePoints)
{
  // A Y of poly-lines: one branch node shared by three chains.
  std::vector<tsynth::Polyline> lines(3);
  lines[0].points = { { 10, 0 }, { 10, 10 } };
  lines[1].points = { { 10, 10 }, { 0, 20 } };
  lines[2].points = { { 10, 10 }, { 20, 20 } };
  const tsynth::FeatureGraph g = tsynth::polylineFeatures(lines, 30, 30, 90.0, 30.0, 0.5, 5.0);
  vtkNew<vtkPolyData> pd;
  tsynth::featureGraphToPolyData(g, pd, 1000.0, 2000.0);
  ASSERT_EQ(pd->GetNumberOfLines(), 3);
  ASSERT_EQ(pd->GetNumberOfPoints(), 4); // 1 branch + 3 ends, no interior points
  vtkDataArray* kind = pd->GetPointData()->GetArray("NodeKind");
  vtkDataArray* degree = pd->GetPointData()->GetArray("Degree");
  ASSERT_NE(kind, nullptr);
  ASSERT_NE(degree, nullptr);
  int branch = -1;
  for (vtkIdType p = 0; p < 4; ++p)
  {
    if (kind->GetComponent(p, 0) == 2)
    {
      branch = static_cast<int>(p);
      EXPECT_EQ(degree->GetComponent(p, 0), 3);
    }
  }
  ASSERT_GE(branch, 0);
  double x[3];
  pd->GetPoint(branch, x);
  EXPECT_DOUBLE_EQ(x[0], 1000.0 + 10 * 90.0); // metres, offset by the origin
  EXPECT_DOUBLE_EQ(x[1], 2000.0 + 10 * 30.0);
  // Every line starts or ends at the shared branch point.
  vtkNew<vtkIdList> ids;
  ASSERT_EQ(pd->GetNumberOfVerts(), 4); // each node is also a vertex cell, before the lines
  for (vtkIdType c = 4; c < 7; ++c)
  {
    pd->GetCellPoints(c, ids);
    EXPECT_TRUE(ids->GetId(0) == branch || ids->GetId(ids->GetNumberOfIds() - 1) == branch);
  }
  EXPECT_EQ(pd->GetCellData()->GetArray("FeatureType")->GetComponent(0, 0), 1);
  EXPECT_EQ(pd->GetFieldData()->GetArray("BFSOrder")->GetComponent(0, 0), branch);

  // Back to poly-lines and to a graph again: the same nodes.
  const auto again = tsynth::polyDataToPolylines(pd, 90.0, 30.0, 1000.0, 2000.0);
  const tsynth::FeatureGraph g2 = tsynth::polylineFeatures(again, 30, 30, 90.0, 30.0, 0.5, 5.0);
  EXPECT_EQ(g2.countKind(tsynth::NodeKind::Branch), 1);
  EXPECT_EQ(g2.countKind(tsynth::NodeKind::End), 3);
}

TEST(Filters, FeatureExtractorOffsetsPointsByTheImageOrigin)
{
  vtkNew<vtkTerrainReader> reader;
  reader->SetFileName((tsynth::test::bundledData() / "dems" / "colorado.png").string().c_str());
  reader->Update();
  vtkNew<vtkImageData> shifted;
  shifted->ShallowCopy(reader->GetOutput());
  shifted->SetOrigin(5000.0, -3000.0, 0.0);
  vtkNew<vtkTerrainFeatureExtractor> features;
  features->SetInputData(shifted);
  features->Update();
  vtkPolyData* tree = features->GetOutput(0);
  ASSERT_GT(tree->GetNumberOfPoints(), 100);
  double bounds[6];
  tree->GetBounds(bounds);
  EXPECT_GE(bounds[0], 5000.0);
  EXPECT_LE(bounds[1], 5000.0 + 647 * 90.0);
  EXPECT_GE(bounds[2], -3000.0);
  EXPECT_LE(bounds[3], -3000.0 + 647 * 90.0);
  EXPECT_GT(features->GetOutput(1)->GetNumberOfPoints(), 100); // control points
}
