// The Terrain Optimisation filter (Filters/vtkTerrainOptimisation.h) gives the
// terrain its kernels give (Kernels/Optimisation: the guide, then the
// optimisation) from a source DEM and a DEM guide, and refuses a source with
// nothing to copy.
#include "FilterTesting.h"
#include "Optimisation/OptimisationTestData.h"
#include "TestData.h"
#include "vtkTerrainOptimisation.h"

#include "Core/HeightfieldIO.h"
#include "Optimisation/OptimisationGuide.h"
#include "Optimisation/TerrainOptimisation.h"

#include <vtkImageData.h>
#include <vtkNew.h>

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace tsynth
{
namespace
{

using test::optimisation::crop;

// Two parts of Colorado (90 m cells): a source of 128 x 128 cells and a guide of 96 x 96.
const Heightfield& colorado()
{
  static const Heightfield c = readHeightfield(test::realDem("colorado.png"));
  return c;
}

} // namespace

TEST(TerrainOptimisationFilter, GivesTheKernelsTerrainFromADemGuide)
{
  const Heightfield source = crop(colorado(), 40, 60, 128, 128);
  const Heightfield guide = crop(colorado(), 300, 350, 96, 96);
  vtkNew<vtkTerrainOptimisation> filter;
  test::FilterErrors errors(filter);
  filter->SetInputData(0, test::imageOf(source));
  filter->SetInputData(1, test::imageOf(guide));
  filter->SetSeed(3);
  filter->SetPitRemoval(vtkTerrainOptimisation::NO_PIT_REMOVAL);
  filter->Update();
  ASSERT_TRUE(errors.text.empty()) << errors.text;
  const std::vector<double> heights = test::pointValues(filter->GetOutput(), "Elevation");

  OptimisationOptions o;
  o.seed = 3;
  o.removePits = false;
  const OptimisationGuide g = buildOptimisationGuide(source, guide, {}, o);
  o.guideConfidence = g.confidence;
  const OptimisationResult kernel = optimiseTerrain(source, g.field, o);
  ASSERT_EQ(heights.size(), kernel.terrain.size());
  ASSERT_EQ(kernel.terrain.width, guide.width) << "on the guide's grid";
  for (std::size_t k = 0; k < heights.size(); ++k)
  {
    ASSERT_EQ(heights[k], kernel.terrain.z[k]) << "cell " << k;
  }
}

TEST(TerrainOptimisationFilter, AFlatSourceFailsTheRequest)
{
  Heightfield flat(64, 64);
  flat.cellX = flat.cellY = 90.0;
  flat.z.assign(flat.size(), 1000.0f);
  vtkNew<vtkTerrainOptimisation> filter;
  test::FilterErrors errors(filter);
  filter->SetInputData(0, test::imageOf(flat));
  filter->SetInputData(1, test::imageOf(crop(colorado(), 300, 350, 96, 96)));
  filter->Update();
  EXPECT_NE(errors.text.find("flat"), std::string::npos) << errors.text;
}

} // namespace tsynth
