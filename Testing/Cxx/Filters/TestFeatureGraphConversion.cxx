// Filters/FeatureGraphConversion.h: a feature graph as poly-data.
#include "FeatureGraphConversion.h"
#include "TestData.h"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

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
