// The Terrain Distance Synthesis filter (Filters/vtkTerrainDistanceSynthesis.h)
// gives the terrain its kernel gives (Kernels/Distance: the inputs assembled,
// then synthesiseByDistance) from a stroke map, highest along the strokes, and
// refuses a map without a ridge.
#include "FilterTesting.h"
#include "vtkTerrainDistanceSynthesis.h"

#include "Distance/DistanceSources.h"
#include "Distance/DistanceSynthesis.h"

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkUnsignedCharArray.h>

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace tsynth
{
namespace
{

constexpr int kSide = 96; // pixels

// A white stroke map with a red ridge 3 pixels wide along row 48 from column 16
// to 80 (and nothing else when `withRidge` is false).
vtkSmartPointer<vtkImageData> strokeMap(bool withRidge)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(kSide, kSide, 1);
  vtkNew<vtkUnsignedCharArray> rgb;
  rgb->SetNumberOfComponents(3);
  rgb->SetNumberOfTuples(kSide * kSide);
  for (int j = 0; j < kSide; ++j)
  {
    for (int i = 0; i < kSide; ++i)
    {
      const bool ridge = withRidge && std::abs(j - 48) <= 1 && i >= 16 && i <= 80;
      rgb->SetTuple3(j * kSide + i, 255.0, ridge ? 0.0 : 255.0, ridge ? 0.0 : 255.0);
    }
  }
  image->GetPointData()->SetScalars(rgb);
  return image;
}

} // namespace

TEST(TerrainDistanceSynthesisFilter, GivesTheKernelsTerrainHighestAlongTheRidge)
{
  auto image = strokeMap(true);
  vtkNew<vtkTerrainDistanceSynthesis> filter;
  test::FilterErrors errors(filter);
  filter->SetInputData(0, image);
  filter->SetCellSize(30.0);
  filter->SetSeed(9);
  filter->Update();
  ASSERT_TRUE(errors.text.empty()) << errors.text;
  const std::vector<double> heights = test::pointValues(filter->GetOutput(), "Elevation");

  const ColourImage strokes = imageToColourImage(image);
  DistanceSources sources;
  sources.strokes = &strokes;
  std::vector<std::string> warnings;
  const DistanceInputs inputs = assembleDistanceInputs(sources, warnings);
  DistanceOptions o;
  o.cellSize = 30.0;
  o.seed = 9;
  const DistanceTerrain kernel = synthesiseByDistance(inputs, o);
  ASSERT_EQ(heights.size(), kernel.heights.size());
  for (std::size_t k = 0; k < heights.size(); ++k)
  {
    ASSERT_EQ(heights[k], kernel.heights.z[k]) << "cell " << k;
  }
  // The ridge's middle stands over the land 30 cells to either side of it.
  const auto at = [&](int i, int j) { return heights[static_cast<std::size_t>(j * kSide + i)]; };
  EXPECT_GT(at(48, 48), at(48, 18));
  EXPECT_GT(at(48, 48), at(48, 78));
}

TEST(TerrainDistanceSynthesisFilter, AMapWithoutARidgeFailsTheRequest)
{
  vtkNew<vtkTerrainDistanceSynthesis> filter;
  test::FilterErrors errors(filter);
  filter->SetInputData(0, strokeMap(false));
  filter->Update();
  EXPECT_NE(errors.text.find("no red ridge strokes"), std::string::npos) << errors.text;
}

} // namespace tsynth
