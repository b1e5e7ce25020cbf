// The Terrain Patch Matcher (Filters/vtkTerrainPatchMatcher.h) finds the
// matches its kernels find (Kernels/Matching/SiteMatch.h, matchAtSite over
// PatchMatcher), in both modes, with the window they go to; and refuses a
// target smaller than a patch. (Given the Candidate Builder's table:
// TestCandidatePoolTable.cxx.)
#include "FilterTesting.h"
#include "TestData.h"
#include "vtkTerrainPatchMatcher.h"
#include "vtkTerrainReader.h"

#include "Core/HeightfieldIO.h"
#include "Core/PatchSize.h"
#include "Features/Ppa.h"
#include "Matching/PatchMatcher.h"
#include "Matching/SiteMatch.h"
#include "Synthesis/ExemplarCache.h"

#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkTable.h>

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

namespace tsynth
{
namespace
{

constexpr int kPatch = 48;
constexpr double kSiteMetres = 5000.0; // on Colorado's 90 m cells, about cell (55, 55)

double column(vtkTable* t, const char* name, vtkIdType row)
{
  return vtkDataArray::SafeDownCast(t->GetColumnByName(name))->GetComponent(row, 0);
}

// Colorado matched against itself at the site, by the filter and by the kernels.
void expectTheKernelsMatches(int mode)
{
  const std::string path = test::realDem("colorado.png");
  vtkNew<vtkTerrainReader> reader;
  reader->SetFileName(path.c_str());
  vtkNew<vtkTerrainPatchMatcher> filter;
  test::FilterErrors errors(filter);
  filter->SetInputConnection(0, reader->GetOutputPort());
  filter->AddInputConnection(1, reader->GetOutputPort());
  filter->SetPatchSize(kPatch);
  filter->SetBackend(vtkTerrainPatchMatcher::CPU);
  filter->SetMode(mode);
  filter->SetSite(kSiteMetres, kSiteMetres);
  filter->Update();
  ASSERT_TRUE(errors.text.empty()) << errors.text;
  vtkTable* table = filter->GetMatches();

  const Heightfield colorado = readHeightfield(path);
  const FeatureGraph lines = ridgesAndValleys(colorado, exemplarPpaOptions());
  MatcherOptions o;
  o.patchSize = kPatch;
  o.backend = Backend::Cpu;
  PatchMatcher matcher({ &colorado }, { &lines }, o);
  const SiteMatchResult kernel = matchAtSite(matcher,
    colorado,
    std::vector<std::uint8_t>(colorado.size(), 1),
    kSiteMetres / colorado.cellX,
    kSiteMetres / colorado.cellY,
    mode == vtkTerrainPatchMatcher::FEATURE,
    kPatch);
  ASSERT_GT(kernel.candidates.size(), 1u);
  ASSERT_EQ(table->GetNumberOfRows(), static_cast<vtkIdType>(kernel.candidates.size()));
  for (std::size_t r = 0; r < kernel.candidates.size(); ++r)
  {
    const PatchCandidate& c = kernel.candidates[r];
    const auto row = static_cast<vtkIdType>(r);
    EXPECT_EQ(column(table, "Exemplar", row), c.exemplar) << r;
    EXPECT_EQ(column(table, "Variant", row), c.variant) << r;
    EXPECT_EQ(column(table, "CellX", row), c.centreX) << r;
    EXPECT_EQ(column(table, "CellY", row), c.centreY) << r;
    EXPECT_EQ(column(table, "Cost", row), c.cost) << r;
    EXPECT_EQ(column(table, "Feature", row), c.feature ? 1.0 : 0.0) << r;
    EXPECT_EQ(column(table, "FeatureType", row), c.feature ? matcher.pool().type[c.poolIndex] : 0)
      << r;
    EXPECT_EQ(column(table, "X", row), c.centreX * colorado.cellX) << r;
  }
  vtkDataArray* window = table->GetFieldData()->GetArray("PatchCell");
  EXPECT_EQ(window->GetComponent(0, 0), windowCorner(kernel.centreX, kPatch));
  EXPECT_EQ(window->GetComponent(1, 0), windowCorner(kernel.centreY, kPatch));
}

} // namespace

TEST(TerrainPatchMatcherFilter, FeatureModeFindsTheKernelsMatches)
{
  expectTheKernelsMatches(vtkTerrainPatchMatcher::FEATURE);
}

TEST(TerrainPatchMatcherFilter, DenseModeFindsTheKernelsMatches)
{
  expectTheKernelsMatches(vtkTerrainPatchMatcher::NON_FEATURE);
}

TEST(TerrainPatchMatcherFilter, ATargetSmallerThanAPatchFailsTheRequest)
{
  vtkNew<vtkTerrainReader> reader;
  reader->SetFileName(test::realDem("colorado.png").c_str());
  vtkNew<vtkTerrainPatchMatcher> filter;
  test::FilterErrors errors(filter);
  filter->SetInputData(0, test::imageOf(test::roughDem(20, 20, false)));
  filter->AddInputConnection(1, reader->GetOutputPort());
  filter->SetPatchSize(kPatch);
  filter->SetBackend(vtkTerrainPatchMatcher::CPU);
  filter->Update();
  EXPECT_FALSE(errors.text.empty());
}

} // namespace tsynth
