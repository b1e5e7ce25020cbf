#include "DistanceInputs.h"

#include "Core/Error.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <cmath>
#include <limits>

namespace tsynth
{
namespace
{

void appendCells(vtkPolyData* input,
  vtkCellArray* cells,
  vtkIdType firstCellId,
  double cellSize,
  std::vector<GeneratorLine>& out)
{
  if (cells == nullptr)
  {
    return;
  }
  vtkDataArray* cost = input->GetPointData()->GetArray("Cost");
  vtkDataArray* profile = input->GetCellData()->GetArray("Profile");
  vtkNew<vtkIdList> ids;
  vtkIdType cellId = firstCellId;
  for (cells->InitTraversal(); cells->GetNextCell(ids); ++cellId)
  {
    GeneratorLine line;
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
    {
      double x[3];
      input->GetPoint(ids->GetId(k), x);
      line.points.push_back({ x[0] / cellSize, x[1] / cellSize });
      if (cost != nullptr)
      {
        line.costs.push_back(static_cast<float>(cost->GetComponent(ids->GetId(k), 0)));
      }
    }
    if (profile != nullptr)
    {
      const double p = profile->GetComponent(cellId, 0);
      line.profile = p >= 0.0 ? static_cast<int>(std::lround(p)) : kNoProfile;
    }
    if (!line.points.empty())
    {
      out.push_back(std::move(line));
    }
  }
}

} // namespace

std::vector<GeneratorLine> polyDataToGeneratorLines(vtkPolyData* input, double cellSize)
{
  std::vector<GeneratorLine> out;
  // Cell ids run through verts, then lines, in vtkPolyData's numbering.
  appendCells(input, input->GetVerts(), 0, cellSize, out);
  appendCells(input, input->GetLines(), input->GetNumberOfVerts(), cellSize, out);
  return out;
}

} // namespace tsynth
