// The Terrain Graph-Cut Merger (Filters/vtkTerrainGraphCutMerger.h) merges a
// patch as its kernel does (Kernels/Merging/PatchMerger.h, PatchMerger::merge),
// in every mode, at the patch's origin or at PatchCell, never changing the old
// terrain outside the cells the patch takes.
#include "FilterTesting.h"
#include "vtkTerrainGraphCutMerger.h"

#include "Merging/PatchMerger.h"

#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkUnsignedCharArray.h>

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

namespace tsynth
{
namespace
{

// A 64 x 48 terrain filled on its west 40 columns, and a 32 x 32 patch of
// other land 120 m higher placed at cell (24, 10): 16 columns of overlap.
struct Scene
{
  Heightfield terrain = test::roughDem(64, 48, false);
  std::vector<std::uint8_t> filled;
  Heightfield patch;
  int x0 = 24;
  int y0 = 10;

  Scene()
  {
    filled.assign(terrain.size(), 0);
    for (int j = 0; j < terrain.height; ++j)
    {
      for (int i = 0; i < 40; ++i)
      {
        filled[terrain.index(i, j)] = 1;
      }
    }
    const Heightfield other = test::roughDem(96, 96, false);
    patch = Heightfield(32, 32);
    patch.cellX = patch.cellY = terrain.cellX;
    for (int j = 0; j < 32; ++j)
    {
      for (int i = 0; i < 32; ++i)
      {
        patch.at(i, j) = other.at(50 + i, 40 + j) + 120.0f;
      }
    }
  }

  vtkSmartPointer<vtkImageData> terrainImage() const
  {
    auto image = test::imageOf(terrain);
    vtkNew<vtkUnsignedCharArray> flags;
    flags->SetName("Filled");
    flags->SetNumberOfTuples(static_cast<vtkIdType>(filled.size()));
    std::copy(filled.begin(), filled.end(), flags->GetPointer(0));
    image->GetPointData()->AddArray(flags);
    return image;
  }
};

} // namespace

TEST(TerrainGraphCutMergerFilter, EachModeMergesAsTheKernelDoes)
{
  const Scene scene;
  for (int mode = 0; mode < 4; ++mode)
  {
    SCOPED_TRACE(mode);
    vtkNew<vtkTerrainGraphCutMerger> merger;
    test::FilterErrors errors(merger);
    merger->SetInputData(0, scene.terrainImage());
    merger->SetInputData(1, test::imageOf(scene.patch));
    merger->SetUsePatchOrigin(false);
    merger->SetPatchCell(scene.x0, scene.y0);
    merger->SetMode(mode);
    merger->Update();
    ASSERT_TRUE(errors.text.empty()) << errors.text;

    Heightfield terrain = scene.terrain;
    std::vector<std::uint8_t> filled = scene.filled;
    const std::vector<std::uint8_t> noCore(scene.patch.size(), 0);
    MergeOptions options;
    options.mode = static_cast<MergeMode>(mode);
    PatchMerger kernel;
    const MergeResult r =
      kernel.merge(terrain, filled, scene.patch, scene.x0, scene.y0, &noCore, options);
    const std::vector<double> heights = test::pointValues(merger->GetOutput(), "Elevation");
    ASSERT_EQ(heights.size(), terrain.size());
    for (std::size_t k = 0; k < heights.size(); ++k)
    {
      ASSERT_EQ(heights[k], terrain.z[k]) << "cell " << k;
    }
    // Old terrain changes only where the cut gave the cell to the patch.
    for (int j = 0; j < scene.terrain.height; ++j)
    {
      for (int i = 0; i < scene.terrain.width; ++i)
      {
        const std::size_t k = scene.terrain.index(i, j);
        const int wi = i - r.x0, wj = j - r.y0;
        const bool taken = wi >= 0 && wj >= 0 && wi < r.width && wj < r.height &&
          r.takeNew[static_cast<std::size_t>(wj * r.width + wi)] != 0;
        if (scene.filled[k] != 0 && !taken)
        {
          ASSERT_EQ(heights[k], scene.terrain.z[k]) << i << ", " << j;
        }
      }
    }
    EXPECT_EQ(test::pointValues(merger->GetOutput(), "Filled"), test::asDoubles(filled));
    EXPECT_EQ(
      merger->GetOutput()->GetFieldData()->GetArray("CutCost")->GetComponent(0, 0), r.cutCost);
    EXPECT_GT(r.cutEdges, 0) << "16 columns of overlap are cut";
  }
}

TEST(TerrainGraphCutMergerFilter, ThePatchGoesWhereItsOriginLies)
{
  const Scene scene;
  auto patchImage = test::imageOf(scene.patch);
  patchImage->SetOrigin(scene.x0 * scene.terrain.cellX, scene.y0 * scene.terrain.cellY, 0.0);
  vtkNew<vtkTerrainGraphCutMerger> byOrigin;
  byOrigin->SetInputData(0, scene.terrainImage());
  byOrigin->SetInputData(1, patchImage);
  byOrigin->Update();
  vtkNew<vtkTerrainGraphCutMerger> byCell;
  byCell->SetInputData(0, scene.terrainImage());
  byCell->SetInputData(1, test::imageOf(scene.patch));
  byCell->SetUsePatchOrigin(false);
  byCell->SetPatchCell(scene.x0, scene.y0);
  byCell->Update();
  EXPECT_EQ(test::pointValues(byOrigin->GetOutput(), "Elevation"),
    test::pointValues(byCell->GetOutput(), "Elevation"));
}

} // namespace tsynth
