// The Terrain Sketch Features filter (Filters/vtkTerrainSketchFeatures.h) gives
// the feature trees its kernel (Kernels/Features/Sketch.h) gives, from a stroke
// map and from poly-lines, where they were drawn; and refuses what it cannot read.
#include "FeatureGraphConversion.h"
#include "FilterTesting.h"
#include "vtkTerrainSketchFeatures.h"
#include "vtkTerrainSketchLines.h"

#include "Features/Sketch.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnsignedCharArray.h>

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace tsynth
{
namespace
{

// Every value of `a` equals `b`'s, NaN where NaN.
void expectSameArray(vtkDataArray* a, vtkDataArray* b, const std::string& what)
{
  ASSERT_NE(a, nullptr) << what;
  ASSERT_NE(b, nullptr) << what;
  ASSERT_EQ(a->GetNumberOfTuples(), b->GetNumberOfTuples()) << what;
  ASSERT_EQ(a->GetNumberOfComponents(), b->GetNumberOfComponents()) << what;
  for (vtkIdType k = 0; k < a->GetNumberOfTuples(); ++k)
  {
    for (int c = 0; c < a->GetNumberOfComponents(); ++c)
    {
      const double x = a->GetComponent(k, c), y = b->GetComponent(k, c);
      ASSERT_TRUE(x == y || (std::isnan(x) && std::isnan(y))) << what << " at " << k;
    }
  }
}

// The same points, cells and point and cell arrays.
void expectSamePolyData(vtkPolyData* got, vtkPolyData* expected)
{
  ASSERT_EQ(got->GetNumberOfPoints(), expected->GetNumberOfPoints());
  ASSERT_EQ(got->GetNumberOfLines(), expected->GetNumberOfLines());
  ASSERT_EQ(got->GetNumberOfVerts(), expected->GetNumberOfVerts());
  expectSameArray(got->GetPoints()->GetData(), expected->GetPoints()->GetData(), "points");
  for (int a = 0; a < expected->GetPointData()->GetNumberOfArrays(); ++a)
  {
    const char* name = expected->GetPointData()->GetArrayName(a);
    expectSameArray(
      got->GetPointData()->GetArray(name), expected->GetPointData()->GetArray(a), name);
  }
  for (int a = 0; a < expected->GetCellData()->GetNumberOfArrays(); ++a)
  {
    const char* name = expected->GetCellData()->GetArrayName(a);
    expectSameArray(got->GetCellData()->GetArray(name), expected->GetCellData()->GetArray(a), name);
  }
}

// A 160 x 160 stroke map of 30 m pixels: a red ridge 7 pixels wide along row 100
// (from the south) and a blue valley down column 63, rows 20 to 70.
vtkSmartPointer<vtkImageData> strokeMap()
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(160, 160, 1);
  image->SetSpacing(30.0, 30.0, 1.0);
  vtkNew<vtkUnsignedCharArray> rgb;
  rgb->SetName("Sketch");
  rgb->SetNumberOfComponents(3);
  rgb->SetNumberOfTuples(160 * 160);
  for (int j = 0; j < 160; ++j)
  {
    for (int i = 0; i < 160; ++i)
    {
      const bool ridge = std::abs(j - 100) <= 3 && i >= 20 && i < 140;
      const bool valley = std::abs(i - 63) <= 3 && j >= 20 && j <= 70;
      const double colour[3] = { ridge ? 255.0
          : valley                     ? 0.0
                                       : 255.0,
        ridge || valley ? 0.0 : 255.0,
        ridge ? 0.0 : 255.0 };
      rgb->SetTuple(j * 160 + i, colour);
    }
  }
  image->GetPointData()->SetScalars(rgb);
  return image;
}

// The chains' mean y (ridges) or mean x (valleys), metres.
double meanCoordinate(vtkPolyData* tree, int featureType, int axis)
{
  vtkDataArray* types = tree->GetCellData()->GetArray("FeatureType");
  double sum = 0.0;
  int n = 0;
  for (vtkIdType c = 0; c < tree->GetNumberOfCells(); ++c)
  {
    if (tree->GetCell(c)->GetNumberOfPoints() < 2 || types->GetComponent(c, 0) != featureType)
    {
      continue;
    }
    for (vtkIdType p = 0; p < tree->GetCell(c)->GetNumberOfPoints(); ++p)
    {
      sum += tree->GetPoint(tree->GetCell(c)->GetPointId(p))[axis];
      ++n;
    }
  }
  return n > 0 ? sum / n : std::nan("");
}

} // namespace

TEST(TerrainSketchFeaturesFilter, AStrokeMapGivesTheKernelsTreeWhereTheStrokesAre)
{
  auto image = strokeMap();
  vtkNew<vtkTerrainSketchFeatures> filter;
  test::FilterErrors errors(filter);
  filter->SetInputData(image);
  filter->Update();
  ASSERT_TRUE(errors.text.empty()) << errors.text;

  SketchOptions o;
  o.cellSize = 30.0;
  const SketchFeatures kernel = sketchFeatures(imageToColourImage(image), o);
  vtkNew<vtkPolyData> expected;
  featureGraphToPolyData(kernel.graph, expected, 0.0, 0.0);
  expectSamePolyData(filter->GetOutput(0), expected);
  // Where they were drawn: the ridge along y = 3000 m, the valley along x = 1890 m.
  EXPECT_NEAR(meanCoordinate(filter->GetOutput(0), 1, 1), 100 * 30.0, 2 * 30.0);
  EXPECT_NEAR(meanCoordinate(filter->GetOutput(0), -1, 0), 63 * 30.0, 2 * 30.0);
  EXPECT_GT(filter->GetOutput(1)->GetNumberOfPoints(), 0) << "control points";
}

TEST(TerrainSketchFeaturesFilter, MarkedPolyLinesGiveTheKernelsTree)
{
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(200.0, 300.0, 0.0);
  points->InsertNextPoint(1200.0, 900.0, 0.0);
  points->InsertNextPoint(2000.0, 950.0, 0.0);
  vtkNew<vtkCellArray> cells;
  const vtkIdType ids[] = { 0, 1, 2 };
  cells->InsertNextCell(3, ids);
  vtkNew<vtkPolyData> drawn;
  drawn->SetPoints(points);
  drawn->SetLines(cells);
  vtkNew<vtkTerrainSketchLines> marker;
  marker->SetInputData(drawn);
  marker->SetFeatureType(vtkTerrainSketchLines::VALLEY);
  vtkNew<vtkTerrainSketchFeatures> filter;
  test::FilterErrors errors(filter);
  filter->SetInputConnection(marker->GetOutputPort());
  filter->SetCellSize(20.0);
  filter->Update();
  ASSERT_TRUE(errors.text.empty()) << errors.text;

  marker->Update();
  const std::vector<Polyline> lines = polyDataToPolylines(marker->GetOutput(), 20.0, 20.0, 0, 0);
  // The grid reaches the lines' far corner: 2000 / 20 + 1 by 950 / 20 rounded up + 1 cells.
  const FeatureGraph graph =
    polylineFeatures(lines, 101, 49, 20.0, 20.0, kDefaultSnapCells, 0.5 * kDefaultSynthesisPatch);
  vtkNew<vtkPolyData> expected;
  featureGraphToPolyData(graph, expected, 0.0, 0.0);
  expectSamePolyData(filter->GetOutput(0), expected);
  EXPECT_EQ(filter->GetOutput(0)->GetCellData()->GetArray("FeatureType")->GetRange()[1], -1.0)
    << "every chain a valley";
}

TEST(TerrainSketchFeaturesFilter, ABadPatchOrAMapWithoutStrokesFailsTheRequest)
{
  vtkNew<vtkTerrainSketchFeatures> odd;
  test::FilterErrors oddErrors(odd);
  odd->SetInputData(strokeMap());
  odd->SetPatchSize(30);
  odd->Update();
  EXPECT_NE(oddErrors.text.find("Patch Size"), std::string::npos) << oddErrors.text;

  auto blank = strokeMap();
  auto* rgb = blank->GetPointData()->GetScalars();
  for (vtkIdType k = 0; k < rgb->GetNumberOfTuples(); ++k)
  {
    rgb->SetTuple3(k, 40.0, 200.0, 40.0); // green: neither ridge nor valley
  }
  vtkNew<vtkTerrainSketchFeatures> green;
  test::FilterErrors greenErrors(green);
  green->SetInputData(blank);
  green->Update();
  EXPECT_FALSE(greenErrors.text.empty());
}

} // namespace tsynth
