// The Terrain Sketch Reader (Filters/vtkTerrainSketchReader.h) lays a sketch
// file on the grid a synthesis from the exemplar makes of it: a stroke map's
// pixels bottom row first in the exemplar's cells, a DEM target's heights with
// its nodata; and refuses a missing file.
#include "FilterTesting.h"
#include "TerrainFileIO.h"
#include "TestData.h"
#include "vtkTerrainSketchReader.h"

#include "Core/HeightfieldIO.h"

#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <variant>
#include <vector>

namespace tsynth
{

TEST(TerrainSketchReaderFilter, AStrokeMapTakesTheExemplarsCellsBottomRowFirst)
{
  const std::string sketch = (test::bundledData() / "sketches" / "strokes_y_ridges.png").string();
  vtkNew<vtkTerrainSketchReader> reader;
  test::FilterErrors errors(reader);
  reader->SetFileName(sketch.c_str());
  reader->SetExemplarFileName((test::bundledData() / "dems" / "colorado.png").string().c_str());
  reader->Update();
  ASSERT_TRUE(errors.text.empty()) << errors.text;
  vtkImageData* out = reader->GetOutput();
  const ColourImage pixels = readColourImage(sketch);
  int dims[3];
  out->GetDimensions(dims);
  EXPECT_EQ(dims[0], pixels.width);
  EXPECT_EQ(dims[1], pixels.height);
  double spacing[3];
  out->GetSpacing(spacing);
  EXPECT_EQ(spacing[0], 90.0) << "Colorado's cells (its sidecar)";
  EXPECT_EQ(spacing[1], 90.0);
  vtkDataArray* sketchArray = out->GetPointData()->GetArray("Sketch");
  ASSERT_NE(sketchArray, nullptr);
  ASSERT_EQ(sketchArray->GetNumberOfComponents(), pixels.channels);
  // Point (i, j) of the image, j from the south, is the file's pixel in row height-1-j.
  for (int j : { 0, pixels.height / 3, pixels.height - 1 })
  {
    for (int i : { 0, pixels.width / 2, pixels.width - 5 })
    {
      for (int c = 0; c < pixels.channels; ++c)
      {
        EXPECT_EQ(sketchArray->GetComponent(j * pixels.width + i, c),
          pixels.pixel(i, pixels.height - 1 - j)[c]);
      }
    }
  }
  // A cell size given wins over the exemplar's.
  reader->SetCellSize(25.0);
  reader->Update();
  reader->GetOutput()->GetSpacing(spacing);
  EXPECT_EQ(spacing[0], 25.0);
}

TEST(TerrainSketchReaderFilter, ADemTargetKeepsItsHeightsAndNodata)
{
  const std::string dem = test::realDem("mount_jackson_crop601.tif");
  vtkNew<vtkTerrainSketchReader> reader;
  test::FilterErrors errors(reader);
  reader->SetFileName(dem.c_str());
  reader->SetCellSize(30.0);
  reader->Update();
  ASSERT_TRUE(errors.text.empty()) << errors.text;
  std::vector<std::string> warnings;
  const SketchInput read = readSketchInput(dem, warnings);
  const Heightfield* heights = std::get_if<Heightfield>(&read);
  ASSERT_NE(heights, nullptr) << "a one-band float raster is a DEM target";
  const std::vector<double> elevation = test::pointValues(reader->GetOutput(), "Elevation");
  ASSERT_EQ(elevation.size(), heights->size());
  for (std::size_t k = 0; k < elevation.size(); ++k)
  {
    if (heights->isValid(k))
    {
      ASSERT_EQ(elevation[k], heights->z[k]) << "cell " << k;
    }
    else
    {
      ASSERT_TRUE(std::isnan(elevation[k])) << "nodata, cell " << k;
    }
  }
}

TEST(TerrainSketchReaderFilter, AMissingFileFailsTheRequestNamingIt)
{
  vtkNew<vtkTerrainSketchReader> reader;
  test::FilterErrors errors(reader);
  reader->SetFileName("/nonexistent/sketch.png");
  reader->Update();
  EXPECT_NE(errors.text.find("/nonexistent/sketch.png"), std::string::npos) << errors.text;
  vtkNew<vtkTerrainSketchReader> unnamed;
  test::FilterErrors unnamedErrors(unnamed);
  unnamed->Update();
  EXPECT_NE(unnamedErrors.text.find("set FileName"), std::string::npos) << unnamedErrors.text;
}

} // namespace tsynth
