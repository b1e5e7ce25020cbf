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

void requireSameSize(const ColourImage& image, int width, int height, const char* what)
{
  if (image.width != width || image.height != height)
  {
    throw Error(std::string("The ") + what + " is " + std::to_string(image.width) + "x" +
      std::to_string(image.height) + " but the generators' grid is " + std::to_string(width) + "x" +
      std::to_string(height) + "; give one of the same size.");
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

DistanceInputs assembleDistanceInputs(const DistanceSources& s, std::vector<std::string>& warnings)
{
  DistanceInputs in;
  in.profiles = s.profiles;
  const int profileCount = static_cast<int>(s.profiles.size());
  if (s.strokes != nullptr)
  {
    in.width = s.strokes->width;
    in.height = s.strokes->height;
    StrokeGenerators g = generatorsFromStrokes(*s.strokes, profileCount, s.assignment, s.labels);
    if (g.valleyPixels > 0)
    {
      warnings.push_back(std::to_string(g.valleyPixels) +
        " blue valley pixels are ignored: distance synthesis makes valleys between ridge strokes.");
    }
    if (profileCount > 0 && g.colours > profileCount &&
      s.assignment == ProfileAssignment::ByColour && s.labels == nullptr)
    {
      warnings.push_back(std::to_string(g.colours) + " ridge colours share " +
        std::to_string(profileCount) + " profiles (colour index mod the profile count).");
    }
    in.features = std::move(g.features);
  }
  else if (s.lines != nullptr)
  {
    if (s.width < 1 || s.height < 1)
    {
      throw Error("Poly-line generators need a grid of two positive numbers of cells (OutputSize, "
                  "--size), not " +
        std::to_string(s.width) + " x " + std::to_string(s.height) + ".");
    }
    in.width = s.width;
    in.height = s.height;
    in.features = generatorsFromLines(*s.lines, s.width, s.height, profileCount);
  }
  else
  {
    throw Error("There are no generators: give a stroke map or poly-lines.");
  }
  if (s.regionProfile != kNoProfile)
  {
    if (s.regionProfile < 0 || s.regionProfile >= profileCount)
    {
      throw Error("The region profile " + std::to_string(s.regionProfile) +
        " does not exist; there are " + std::to_string(profileCount) + " profiles.");
    }
    in.regions = enclosedRegions(in.features, in.width, in.height, s.regionProfile);
    if (in.regions.empty())
    {
      warnings.push_back("No stroke encloses any cells, so the region profile is not used.");
    }
  }
  if (s.edgeWeights != nullptr)
  {
    requireSameSize(*s.edgeWeights, in.width, in.height, "edge-weight image");
    in.nodeWeights = greyToWeights(s.edgeWeights->data.data(),
      in.width,
      in.height,
      s.edgeWeights->channels,
      s.edgeLow,
      s.edgeHigh);
  }
  return in;
}

} // namespace tsynth
