// Tests of Kernels/Synthesis/Preview.cxx.
// The preview level (Synthesis/Preview.h): its grid and patch, the options it
// changes, and the upsampling that shows it on the terrain's grid.
#include "Core/Error.h"
#include "PreviewTestData.h"
#include "Synthesis/Preview.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace tsynth;
using tsynth::test::preview::inputsFor;
using tsynth::test::preview::kCell;

TEST(Preview, DefaultPatchGivesCellsFourTimesCoarserAndPatchesFourTimesSmaller)
{
  const PreviewPlan plan = planPreview(inputsFor(1024, 80));
  ASSERT_TRUE(plan.available());
  EXPECT_EQ(plan.factor, 4);
  EXPECT_EQ(plan.full.width, 1024);
  EXPECT_EQ(plan.full.height, 512);
  // The coarse cell centres reach the last full cell centre: (1023 / 4 rounded up) + 1.
  EXPECT_EQ(plan.coarse.width, 257);
  EXPECT_EQ(plan.coarse.height, 129);
  EXPECT_DOUBLE_EQ(plan.coarse.cellX, 4 * kCell);
  EXPECT_DOUBLE_EQ(plan.coarse.cellY, 4 * kCell);
  EXPECT_EQ(plan.patchSize, 20); // the same 7.2 km of ground
}

TEST(Preview, SmallerPatchesHalveAndTheSmallestHaveNoPreview)
{
  const PreviewPlan half = planPreview(inputsFor(600, 48));
  EXPECT_EQ(half.factor, 2);
  EXPECT_EQ(half.patchSize, 24);
  EXPECT_EQ(half.coarse.width, 301);
  EXPECT_DOUBLE_EQ(half.coarse.cellX, 2 * kCell);
  // 60 / 4 = 15 is under the smallest patch: halved instead, 30 rounded down to 28.
  EXPECT_EQ(planPreview(inputsFor(600, 60)).factor, 2);
  EXPECT_EQ(planPreview(inputsFor(600, 60)).patchSize, 28);
  EXPECT_EQ(planPreview(inputsFor(600, 64)).factor, 4);
  const PreviewPlan none = planPreview(inputsFor(600, 28));
  EXPECT_FALSE(none.available());
  EXPECT_EQ(none.patchSize, 28);
  EXPECT_EQ(none.coarse.width, none.full.width);
  try
  {
    synthesisePreview(inputsFor(600, 28), SynthesisOptions{});
    FAIL() << "a patch of 28 has no preview";
  }
  catch (const Error& e)
  {
    EXPECT_NE(std::string(e.what()).find("at least 32"), std::string::npos) << e.what();
  }
}

TEST(Preview, InputsAndOptionsAreTheCoarseLevelsAndKeepTheRest)
{
  SetupInputs in = inputsFor(512, 80);
  in.seed = 7;
  in.landformRelief = 1.5;
  const PreviewPlan plan = planPreview(in);
  const SetupInputs coarse = previewInputs(in, plan);
  EXPECT_EQ(coarse.grid.width, 129);
  EXPECT_EQ(coarse.grid.height, 65);
  EXPECT_DOUBLE_EQ(coarse.grid.cellX, 360.0);
  EXPECT_EQ(coarse.patchSize, 20);
  EXPECT_EQ(coarse.rasterSketchPatch, 80); // the sketch read as the whole synthesis reads it
  EXPECT_EQ(coarse.seed, 7u);
  EXPECT_DOUBLE_EQ(coarse.landformRelief, 1.5);

  SynthesisOptions o;
  o.patchSize = 80;
  o.seed = 7;
  o.correctionScale = 12.0; // full cells
  o.regionLabels.assign(512 * 256, 0);
  for (int j = 0; j < 256; ++j)
  {
    for (int i = 256; i < 512; ++i)
    {
      o.regionLabels[static_cast<std::size_t>(j) * 512 + i] = 1; // the east half
    }
  }
  const SynthesisOptions p = previewOptions(o, plan);
  EXPECT_EQ(p.patchSize, 20);
  EXPECT_EQ(p.seed, 7u);
  EXPECT_EQ(p.backend, Backend::Cpu);
  EXPECT_EQ(p.fillK, 1u);
  EXPECT_DOUBLE_EQ(p.fillSpacing, kMaxFillSpacing);
  EXPECT_DOUBLE_EQ(p.correctionScale, 3.0);
  ASSERT_EQ(p.regionLabels.size(), 129u * 65u);
  EXPECT_EQ(p.regionLabels[0], 0);
  EXPECT_EQ(p.regionLabels[63], 0);  // full column 252
  EXPECT_EQ(p.regionLabels[64], 1);  // full column 256
  EXPECT_EQ(p.regionLabels[128], 1); // full column 512 clamped to 511
}

TEST(Preview, UpsamplingKeepsAPlaneAndTheCoarseCellsAndNodataOnlyWhereItWeighs)
{
  OutputGrid full;
  full.width = 1023;
  full.height = 510;
  full.cellX = kCell;
  full.cellY = kCell;
  Heightfield coarse(257, 129); // planPreview's coarse grid for 1023 x 510
  coarse.cellX = 4 * kCell;
  coarse.cellY = 4 * kCell;
  auto plane = [](double x, double y) { return 1000.0 + 0.02 * x - 0.05 * y; };
  for (int j = 0; j < coarse.height; ++j)
  {
    for (int i = 0; i < coarse.width; ++i)
    {
      coarse.at(i, j) = static_cast<float>(plane(i * coarse.cellX, j * coarse.cellY));
    }
  }
  const Heightfield up = upsampleOnto(coarse, full);
  ASSERT_EQ(up.width, 1023);
  ASSERT_EQ(up.height, 510);
  EXPECT_DOUBLE_EQ(up.cellX, kCell);
  EXPECT_FALSE(up.hasMask());
  double worst = 0.0;
  for (int j = 0; j < up.height; ++j)
  {
    for (int i = 0; i < up.width; ++i)
    {
      worst = std::max(worst, std::abs(up.at(i, j) - plane(i * kCell, j * kCell)));
    }
  }
  EXPECT_LT(worst, 1e-3); // float heights near 1000 m
  EXPECT_EQ(up.at(8, 12), coarse.at(2, 3));

  coarse.at(10, 10) = std::nanf("");
  coarse.valid.assign(coarse.size(), 1);
  coarse.valid[coarse.index(10, 10)] = 0;
  const Heightfield holed = upsampleOnto(coarse, full);
  ASSERT_TRUE(holed.hasMask());
  EXPECT_FALSE(holed.isValid(40, 40));
  EXPECT_FALSE(holed.isValid(37, 43)); // between coarse 9 and 10
  EXPECT_TRUE(holed.isValid(36, 40));  // on coarse column 9
  EXPECT_TRUE(holed.isValid(44, 44));  // on coarse cell (11, 11)
  EXPECT_TRUE(std::isnan(holed.at(41, 40)));
}
