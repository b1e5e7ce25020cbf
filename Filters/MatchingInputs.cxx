#include "MatchingInputs.h"

#include "Synthesis/ExemplarCache.h"

#include "FeatureGraphConversion.h"
#include "TerrainImageConversion.h"

#include "Core/Error.h"
#include "Features/Ppa.h"
#include "Features/Sketch.h"

#include <vtkDataObject.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

namespace tsynth
{

std::vector<const Heightfield*> ExemplarInputs::heightPointers() const
{
  std::vector<const Heightfield*> out;
  for (const Heightfield& h : heights)
  {
    out.push_back(&h);
  }
  return out;
}

std::vector<const FeatureGraph*> ExemplarInputs::graphPointers() const
{
  std::vector<const FeatureGraph*> out;
  for (const FeatureGraph& g : graphs)
  {
    out.push_back(&g);
  }
  return out;
}

ExemplarHeights exemplarHeightsNamed(vtkInformation* chosen, vtkInformationVector* images)
{
  const std::string name = chosen != nullptr && chosen->Has(vtkDataObject::FIELD_NAME())
    ? chosen->Get(vtkDataObject::FIELD_NAME())
    : "";
  return [name, images](int connection) -> vtkDataArray*
  {
    vtkImageData* image = vtkImageData::GetData(images, connection);
    return name.empty() || image == nullptr ? nullptr
                                            : image->GetPointData()->GetArray(name.c_str());
  };
}

ExemplarInputs gatherExemplarImages(vtkInformationVector* images, const ExemplarHeights& heights)
{
  ExemplarInputs in;
  const int n = images != nullptr ? images->GetNumberOfInformationObjects() : 0;
  if (n == 0)
  {
    throw Error("No exemplar: connect at least one heightfield.");
  }
  for (int e = 0; e < n; ++e)
  {
    vtkImageData* image = vtkImageData::GetData(images, e);
    double ox = 0.0;
    double oy = 0.0;
    gridOrigin(image, ox, oy);
    in.heights.push_back(imageToHeightfield(image, heights ? heights(e) : nullptr));
    requireValidHeights(in.heights.back());
    in.originX.push_back(ox);
    in.originY.push_back(oy);
  }
  return in;
}

ExemplarInputs gatherExemplars(vtkInformationVector* images,
  vtkInformationVector* trees,
  const ExemplarHeights& heights)
{
  ExemplarInputs in = gatherExemplarImages(images, heights);
  const int n = static_cast<int>(in.heights.size());
  const int t = trees != nullptr ? trees->GetNumberOfInformationObjects() : 0;
  if (t != 0 && t != n)
  {
    throw Error("Give one feature tree per exemplar (" + std::to_string(n) + " exemplars, " +
      std::to_string(t) + " trees), or none to extract them.");
  }
  for (int e = 0; e < n; ++e)
  {
    const Heightfield& hf = in.heights[static_cast<std::size_t>(e)];
    FeatureGraph graph;
    if (t > 0)
    {
      // The tree's poly-lines, snapped back onto the exemplar's grid.
      const auto lines = polyDataToPolylines(vtkPolyData::GetData(trees, e),
        hf.cellX,
        hf.cellY,
        in.originX[static_cast<std::size_t>(e)],
        in.originY[static_cast<std::size_t>(e)]);
      graph = polylineFeatures(lines, hf.width, hf.height, hf.cellX, hf.cellY, 0.5);
    }
    else
    {
      graph = ridgesAndValleys(hf, exemplarPpaOptions()); // as the synthesis finds them
    }
    in.graphs.push_back(std::move(graph));
  }
  return in;
}

} // namespace tsynth
