// The Terrain Sketch Lines filter (Filters/vtkTerrainSketchLines.h) marks drawn
// lines as the sketch the synthesis reads: each elevation mode, the feature
// type, the lines read back as the kernels' poly-lines, and its refusals.
#include "FeatureGraphConversion.h"
#include "FilterTesting.h"
#include "vtkTerrainSketchLines.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

namespace tsynth
{
namespace
{

// Two poly-lines in metres with heights in z: three points and two.
const std::vector<std::array<double, 3>> kPoints = { { 100.0, 200.0, 1500.0 },
  { 900.0, 250.0, 1600.0 },
  { 1500.0, 800.0, 1700.0 },
  { 300.0, 1200.0, 900.0 },
  { 1300.0, 1100.0, 950.0 } };

vtkSmartPointer<vtkPolyData> drawnLines()
{
  vtkNew<vtkPoints> points;
  for (const auto& p : kPoints)
  {
    points->InsertNextPoint(p.data());
  }
  vtkNew<vtkCellArray> lines;
  const vtkIdType first[] = { 0, 1, 2 };
  const vtkIdType second[] = { 3, 4 };
  lines->InsertNextCell(3, first);
  lines->InsertNextCell(2, second);
  auto data = vtkSmartPointer<vtkPolyData>::New();
  data->SetPoints(points);
  data->SetLines(lines);
  return data;
}

std::vector<double> array(vtkDataArray* a)
{
  std::vector<double> values;
  for (vtkIdType k = 0; a != nullptr && k < a->GetNumberOfTuples(); ++k)
  {
    values.push_back(a->GetComponent(k, 0));
  }
  return values;
}

} // namespace

TEST(TerrainSketchLinesFilter, EachElevationModeSetsTheHeightsItSays)
{
  vtkNew<vtkTerrainSketchLines> marker;
  test::FilterErrors errors(marker);
  marker->SetInputData(drawnLines());
  marker->SetFeatureType(vtkTerrainSketchLines::VALLEY);

  marker->Update(); // NO_ELEVATION by default
  ASSERT_TRUE(errors.text.empty()) << errors.text;
  vtkPolyData* out = marker->GetOutput();
  EXPECT_EQ(array(out->GetCellData()->GetArray("FeatureType")), std::vector<double>({ -1, -1 }));
  EXPECT_EQ(out->GetCellData()->GetScalars()->GetName(), std::string("FeatureType"));
  for (double e : array(out->GetPointData()->GetArray("Elevation")))
  {
    EXPECT_TRUE(std::isnan(e));
  }

  marker->SetElevationMode(vtkTerrainSketchLines::ELEVATION_FROM_Z);
  marker->Update();
  out = marker->GetOutput();
  const std::vector<double> fromZ = array(out->GetPointData()->GetArray("Elevation"));
  ASSERT_EQ(fromZ.size(), kPoints.size());
  for (std::size_t k = 0; k < kPoints.size(); ++k)
  {
    EXPECT_EQ(fromZ[k], kPoints[k][2]);
    double p[3];
    out->GetPoint(static_cast<vtkIdType>(k), p);
    EXPECT_EQ(p[0], kPoints[k][0]);
    EXPECT_EQ(p[1], kPoints[k][1]);
    EXPECT_EQ(p[2], 0.0) << "laid flat";
  }

  marker->SetElevationMode(vtkTerrainSketchLines::CONSTANT_ELEVATION);
  marker->SetElevation(2500.0);
  marker->Update();
  EXPECT_EQ(array(marker->GetOutput()->GetPointData()->GetArray("Elevation")),
    std::vector<double>(kPoints.size(), 2500.0));
}

TEST(TerrainSketchLinesFilter, TheSynthesisReadsTheMarkedLinesAsDrawn)
{
  vtkNew<vtkTerrainSketchLines> marker;
  marker->SetInputData(drawnLines());
  marker->SetFeatureType(vtkTerrainSketchLines::VALLEY);
  marker->SetElevationMode(vtkTerrainSketchLines::ELEVATION_FROM_Z);
  marker->Update();
  std::string warning;
  const std::vector<Polyline> lines =
    polyDataToPolylines(marker->GetOutput(), 10.0, 10.0, 0.0, 0.0, &warning);
  EXPECT_TRUE(warning.empty()) << warning;
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0].type, FeatureType::Valley);
  ASSERT_EQ(lines[0].points.size(), 3u);
  EXPECT_DOUBLE_EQ(lines[0].points[1].x, 90.0) << "metres over 10 m cells";
  EXPECT_DOUBLE_EQ(lines[0].points[1].y, 25.0);
  ASSERT_EQ(lines[1].elevation.size(), 2u);
  EXPECT_EQ(lines[1].elevation[1], 950.0f);
}

TEST(TerrainSketchLinesFilter, NoLinesOrATypeBetweenRidgeAndValleyFailsTheRequest)
{
  vtkNew<vtkTerrainSketchLines> empty;
  test::FilterErrors emptyErrors(empty);
  empty->SetInputData(vtkSmartPointer<vtkPolyData>::New());
  empty->Update();
  EXPECT_NE(emptyErrors.text.find("The input has no lines"), std::string::npos) << emptyErrors.text;

  vtkNew<vtkTerrainSketchLines> zero;
  test::FilterErrors zeroErrors(zero);
  zero->SetInputData(drawnLines());
  zero->SetFeatureType(0);
  zero->Update();
  EXPECT_NE(
    zeroErrors.text.find("Feature type 0 is none of 1 ridge or -1 valley."), std::string::npos)
    << zeroErrors.text;
}

} // namespace tsynth
