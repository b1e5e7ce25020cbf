// The Terrain Candidate Builder (Filters/vtkTerrainCandidateBuilder.h) writes
// the pool its kernel builds (Kernels/Matching/CandidatePool.h,
// buildCandidatePool over the exemplar's ridges and valleys as the synthesis
// finds them), every candidate and every descriptor, and refuses a patch size
// out of range. (Its table read back by the Patch Matcher:
// TestCandidatePoolTable.cxx.)
#include "CandidatePoolTable.h"
#include "FilterTesting.h"
#include "TestData.h"
#include "vtkTerrainCandidateBuilder.h"
#include "vtkTerrainReader.h"

#include "Core/HeightfieldIO.h"
#include "Features/Ppa.h"
#include "Matching/CandidatePool.h"
#include "Synthesis/ExemplarCache.h"

#include <vtkNew.h>
#include <vtkTable.h>

#include <gtest/gtest.h>

#include <string>

namespace tsynth
{

TEST(TerrainCandidateBuilderFilter, ItsTableIsTheKernelsPoolForTheSynthesisLines)
{
  const std::string path = test::realDem("colorado.png");
  vtkNew<vtkTerrainReader> reader;
  reader->SetFileName(path.c_str());
  vtkNew<vtkTerrainCandidateBuilder> builder;
  test::FilterErrors errors(builder);
  builder->SetInputConnection(0, reader->GetOutputPort());
  builder->SetPatchSize(48);
  builder->Update();
  ASSERT_TRUE(errors.text.empty()) << errors.text;
  const CandidatePool table = poolFromTable(builder->GetOutput());

  const Heightfield colorado = readHeightfield(path);
  const FeatureGraph lines = ridgesAndValleys(colorado, exemplarPpaOptions());
  PoolOptions o;
  o.patchSize = 48;
  const CandidatePool kernel = buildCandidatePool({ &colorado }, { &lines }, o);
  ASSERT_GT(kernel.size(), 1000u) << "Colorado's ridges and valleys, 16 variants a site";
  ASSERT_EQ(table.size(), kernel.size());
  EXPECT_EQ(table.patchSize, 48);
  EXPECT_EQ(table.exemplar, kernel.exemplar);
  EXPECT_EQ(table.variant, kernel.variant);
  EXPECT_EQ(table.kind, kernel.kind);
  EXPECT_EQ(table.type, kernel.type);
  EXPECT_EQ(table.arms, kernel.arms);
  EXPECT_EQ(table.centreX, kernel.centreX);
  EXPECT_EQ(table.centreY, kernel.centreY);
  EXPECT_EQ(table.angles, kernel.angles);
  EXPECT_EQ(table.along, kernel.along);
  EXPECT_EQ(table.across, kernel.across);
  EXPECT_EQ(table.noise, kernel.noise);
  EXPECT_EQ(table.descriptor, kernel.descriptor);
  EXPECT_EQ(table.landform, kernel.landform);
  EXPECT_EQ(table.heightScale, kernel.heightScale);
}

TEST(TerrainCandidateBuilderFilter, APatchSizeOutOfRangeFailsTheRequest)
{
  vtkNew<vtkTerrainReader> reader;
  reader->SetFileName(test::realDem("colorado.png").c_str());
  vtkNew<vtkTerrainCandidateBuilder> builder;
  test::FilterErrors errors(builder);
  builder->SetInputConnection(0, reader->GetOutputPort());
  builder->SetPatchSize(8);
  builder->Update();
  EXPECT_NE(errors.text.find("Patch Size"), std::string::npos) << errors.text;
}

} // namespace tsynth
