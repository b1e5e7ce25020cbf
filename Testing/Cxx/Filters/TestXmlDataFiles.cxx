// Filters/XmlDataFiles.h: damaged VTK XML poly-data files refused with one
// sentence before VTK's parser reads past their ends (found by the fuzz targets).
// Found while writing the poly-line fuzz target: a cell naming a point past the
// end made every reader of the lines read past the points (a crash or garbage).
// Found by the polylines fuzz target: a field-data array of an unknown type made
// VTK's reader dereference a null pointer (the process died).
#include "FeatureGraphConversion.h"
#include "TestData.h"

#include "Core/Error.h"

#include <vtkNew.h>
#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

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
