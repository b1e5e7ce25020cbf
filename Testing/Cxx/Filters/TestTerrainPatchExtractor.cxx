// The Terrain Patch Extractor (Filters/vtkTerrainPatchExtractor.h) between the
// Patch Matcher and the Graph-Cut Merger: the patch a match names, where the
// matcher matched, shifted to fit, with its core.
#include "TestData.h"
#include "vtkTerrainCandidateBuilder.h"
#include "vtkTerrainGraphCutMerger.h"
#include "vtkTerrainPatchExtractor.h"
#include "vtkTerrainPatchMatcher.h"
#include "vtkTerrainReader.h"

#include "Features/ChainPointGrid.h"
#include "Features/Ppa.h"
#include "Matching/LandformTerm.h"
#include "Synthesis/ExemplarCache.h"
#include "Synthesis/PatchExtraction.h"
#include "TerrainImageConversion.h"

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkTable.h>
#include <vtkUnsignedCharArray.h>

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <string>

namespace
{

struct Chain
{
  vtkNew<vtkTerrainReader> reader;
  vtkNew<vtkTerrainCandidateBuilder> builder;
  vtkNew<vtkTerrainPatchMatcher> matcher;
  vtkNew<vtkTerrainPatchExtractor> extractor;
  std::string errors;
  vtkNew<vtkCallbackCommand> onError;

  // Colorado matched against itself at a site of its own ridges (feature mode)
  // or at that window (dense mode), through the builder's pool, and the
  // extractor on the matcher's table.
  explicit Chain(int mode)
  {
    reader->SetFileName((tsynth::test::bundledData() / "dems" / "colorado.png").string().c_str());
    builder->SetInputConnection(0, reader->GetOutputPort());
    builder->Update();
    vtkTable* pool = builder->GetOutput();
    matcher->SetInputConnection(0, reader->GetOutputPort());
    matcher->AddInputConnection(1, reader->GetOutputPort());
    matcher->SetCandidatePoolConnection(builder->GetOutputPort());
    matcher->SetBackend(vtkTerrainPatchMatcher::CPU);
    matcher->SetMode(mode);
    matcher->SetSite(pool->GetColumnByName("X")->GetVariantValue(500).ToDouble(),
      pool->GetColumnByName("Y")->GetVariantValue(500).ToDouble());
    extractor->SetInputConnection(0, reader->GetOutputPort());
    extractor->AddInputConnection(1, reader->GetOutputPort());
    extractor->SetInputConnection(2, matcher->GetOutputPort(0));
    onError->SetClientData(this);
    onError->SetCallback([](vtkObject*, unsigned long, void* self, void* message)
      { static_cast<Chain*>(self)->errors += static_cast<const char*>(message); });
    extractor->AddObserver(vtkCommand::ErrorEvent, onError);
  }

  vtkImageData* terrain() { return reader->GetOutput(); }
  vtkImageData* patch() { return extractor->GetOutput(); }
  int patchCell(int axis)
  {
    return static_cast<int>(
      matcher->GetMatches()->GetFieldData()->GetArray("PatchCell")->GetComponent(axis, 0));
  }
  double field(const char* name)
  {
    return patch()->GetFieldData()->GetArray(name)->GetComponent(0, 0);
  }
};

double pointValue(vtkImageData* image, const char* array, int i, int j)
{
  int dims[3];
  image->GetDimensions(dims);
  return image->GetPointData()->GetArray(array)->GetComponent(
    static_cast<vtkIdType>(j) * dims[0] + i, 0);
}

} // namespace

TEST(PatchExtractor, TheBestDenseSelfMatchIsTheTerrainItselfWhereTheMatcherMatched)
{
  Chain chain(vtkTerrainPatchMatcher::NON_FEATURE);
  chain.extractor->Update();
  ASSERT_EQ(chain.errors, "");
  vtkTable* matches = chain.matcher->GetMatches();
  ASSERT_GT(matches->GetNumberOfRows(), 1);
  ASSERT_EQ(matches->GetColumnByName("Feature")->GetVariantValue(0).ToInt(), 0);
  ASSERT_EQ(matches->GetColumnByName("Variant")->GetVariantValue(0).ToInt(), 0);
  vtkImageData* patch = chain.patch();
  int dims[3];
  patch->GetDimensions(dims);
  ASSERT_EQ(dims[0], 80);
  ASSERT_EQ(dims[1], 80);
  // Placed on the window: its origin is the PatchCell's point of the terrain.
  const int x0 = chain.patchCell(0);
  const int y0 = chain.patchCell(1);
  double spacing[3];
  chain.terrain()->GetSpacing(spacing);
  EXPECT_DOUBLE_EQ(patch->GetOrigin()[0], x0 * spacing[0]);
  EXPECT_DOUBLE_EQ(patch->GetOrigin()[1], y0 * spacing[1]);
  // The place itself, unrotated: every height the terrain's, no shift, and a
  // non-feature patch owns no cell whatever the seam.
  EXPECT_EQ(chain.field("VerticalOffset"), 0.0);
  double core = 0.0;
  for (int j = 0; j < 80; ++j)
  {
    for (int i = 0; i < 80; ++i)
    {
      ASSERT_EQ(pointValue(patch, "Elevation", i, j),
        pointValue(chain.terrain(), "Elevation", x0 + i, y0 + j))
        << i << ", " << j;
      core += pointValue(patch, "Core", i, j);
    }
  }
  EXPECT_EQ(core, 0.0);
}

TEST(PatchExtractor, ALesserMatchIsShiftedByItsMeanDifferenceToTheFilledTerrain)
{
  Chain chain(vtkTerrainPatchMatcher::FEATURE);
  chain.extractor->SetRank(1);
  chain.extractor->Update();
  ASSERT_EQ(chain.errors, "");
  const int x0 = chain.patchCell(0);
  const int y0 = chain.patchCell(1);
  const double offset = chain.field("VerticalOffset");
  // Every terrain cell is filled (no Filled array): the shift is the mean of
  // terrain minus the unshifted patch over the patch's valid cells.
  double sum = 0.0;
  double n = 0.0;
  for (int j = 0; j < 80; ++j)
  {
    for (int i = 0; i < 80; ++i)
    {
      const double shifted = pointValue(chain.patch(), "Elevation", i, j);
      if (std::isfinite(shifted))
      {
        sum += pointValue(chain.terrain(), "Elevation", x0 + i, y0 + j) - (shifted - offset);
        n += 1.0;
      }
    }
  }
  ASSERT_GT(n, 0.5 * 80 * 80);
  EXPECT_NEAR(offset, sum / n, 1e-3);
  EXPECT_GT(std::abs(offset), 0.01); // another place of the exemplar: another level
  // A feature match owns the disc of an eighth of a patch round its centre
  // (there are no drawn lines here) and a strip along its own ridge or valley,
  // as the synthesis' trial does: the same cells as the kernels give.
  vtkTable* matches = chain.matcher->GetMatches();
  ASSERT_EQ(matches->GetColumnByName("Feature")->GetVariantValue(1).ToInt(), 1);
  const int type = matches->GetColumnByName("FeatureType")->GetVariantValue(1).ToInt();
  ASSERT_TRUE(type == 1 || type == -1);
  tsynth::PatchCandidate match;
  match.variant = matches->GetColumnByName("Variant")->GetVariantValue(1).ToInt();
  match.centreX = matches->GetColumnByName("CellX")->GetVariantValue(1).ToDouble();
  match.centreY = matches->GetColumnByName("CellY")->GetVariantValue(1).ToDouble();
  const tsynth::Heightfield exemplar = tsynth::imageToHeightfield(chain.terrain());
  const std::vector<tsynth::Point2> own = tsynth::ownLineOffsets(
    tsynth::ChainPointGrid(tsynth::ridgesAndValleys(exemplar, tsynth::exemplarPpaOptions()),
      tsynth::kLineOffsetReachInPatches * 80),
    type > 0 ? tsynth::FeatureType::Ridge : tsynth::FeatureType::Valley,
    match,
    80);
  ASSERT_GT(own.size(), 10u) << "a feature candidate sits on its own line";
  std::vector<std::uint8_t> expected = tsynth::featureCore({}, 0, 0, 0, 0, 80); // the disc
  const double disc = std::accumulate(expected.begin(), expected.end(), 0.0);
  EXPECT_NEAR(disc, M_PI * 10.0 * 10.0, 0.1 * M_PI * 10.0 * 10.0);
  tsynth::addOwnLineStrip(expected, own, 80);
  double core = 0.0;
  for (int j = 0; j < 80; ++j)
  {
    for (int i = 0; i < 80; ++i)
    {
      const double c = pointValue(chain.patch(), "Core", i, j);
      ASSERT_EQ(c, expected[static_cast<std::size_t>(j * 80 + i)]) << i << ", " << j;
      core += c;
    }
  }
  EXPECT_GT(core, disc + 2 * 3 * 10) << "the strip reaches past the disc along the line";
  // Without the shift, the same heights less it.
  vtkNew<vtkImageData> shifted;
  shifted->DeepCopy(chain.patch());
  chain.extractor->VerticalOffsetOff();
  chain.extractor->Update();
  EXPECT_EQ(chain.field("VerticalOffset"), 0.0);
  EXPECT_NEAR(pointValue(shifted, "Elevation", 40, 40) - offset,
    pointValue(chain.patch(), "Elevation", 40, 40),
    1e-3);
}

namespace
{

// The chain's terrain with a uint8 point array `name`, 1 where `on(i, j)`.
template<class On>
vtkSmartPointer<vtkImageData> markedTerrain(Chain& chain, const char* name, On on)
{
  auto marked = vtkSmartPointer<vtkImageData>::New();
  marked->DeepCopy(chain.terrain());
  int dims[3];
  marked->GetDimensions(dims);
  vtkNew<vtkUnsignedCharArray> flags;
  flags->SetName(name);
  flags->SetNumberOfTuples(static_cast<vtkIdType>(dims[0]) * dims[1]);
  for (int j = 0; j < dims[1]; ++j)
  {
    for (int i = 0; i < dims[0]; ++i)
    {
      flags->SetValue(static_cast<vtkIdType>(j) * dims[0] + i, on(i, j) ? 1 : 0);
    }
  }
  marked->GetPointData()->AddArray(flags);
  return marked;
}

} // namespace

TEST(PatchExtractor, AFillMatchLeavesTheLinesLaidAsTheSynthesisDoes)
{
  Chain chain(vtkTerrainPatchMatcher::NON_FEATURE);
  chain.matcher->Update();
  const int x0 = chain.patchCell(0);
  const int y0 = chain.patchCell(1);
  // A line across the window's middle row, and a frozen corner (a tile before).
  auto lined = markedTerrain(chain, "Line", [&](int, int j) { return j == y0 + 40; });
  auto marked =
    markedTerrain(chain, "Frozen", [&](int i, int j) { return i < x0 + 10 && j < y0 + 10; });
  marked->GetPointData()->AddArray(lined->GetPointData()->GetArray("Line"));
  chain.extractor->SetInputData(0, marked);
  chain.extractor->Update();
  ASSERT_EQ(chain.errors, "");
  for (int j = 0; j < 80; ++j)
  {
    for (int i = 0; i < 80; ++i)
    {
      const bool kept = j == 40 || (i < 10 && j < 10);
      const double z = pointValue(chain.patch(), "Elevation", i, j);
      ASSERT_EQ(std::isnan(z), kept) << i << ", " << j;
      ASSERT_EQ(pointValue(chain.patch(), "Valid", i, j), kept ? 0.0 : 1.0) << i << ", " << j;
    }
  }
  // A feature match lays lines: none of its cells is kept out.
  Chain feature(vtkTerrainPatchMatcher::FEATURE);
  feature.matcher->Update();
  const int fy0 = feature.patchCell(1);
  feature.extractor->SetInputData(
    0, markedTerrain(feature, "Line", [&](int, int j) { return j == fy0 + 40; }));
  feature.extractor->Update();
  ASSERT_EQ(feature.errors, "");
  EXPECT_TRUE(std::isfinite(pointValue(feature.patch(), "Elevation", 20, 40)));
  EXPECT_EQ(pointValue(feature.patch(), "Core", 50, 40), 1.0) << "the line within a quarter patch";
}

TEST(PatchExtractor, AGivenTargetPullsTheShiftAsInTheSynthesis)
{
  Chain chain(vtkTerrainPatchMatcher::FEATURE);
  chain.extractor->SetRank(1);
  chain.matcher->Update();
  const int x0 = chain.patchCell(0);
  const int y0 = chain.patchCell(1);
  // A quarter of the window filled (its west 20 columns), and a target 500 m
  // above the terrain, as the construction output's Target and TargetConfidence.
  auto marked = markedTerrain(chain, "Filled", [&](int i, int) { return i < x0 + 20; });
  const tsynth::Heightfield terrain = tsynth::imageToHeightfield(chain.terrain());
  tsynth::Heightfield target = terrain;
  for (float& z : target.z)
  {
    z += 500.0f;
  }
  std::vector<float> confidence(terrain.size(), 1.0f);
  vtkNew<vtkImageData> targetImage;
  tsynth::heightfieldToImage(target, targetImage);
  vtkDataArray* targetArray = targetImage->GetPointData()->GetArray("Elevation");
  targetArray->SetName("Target");
  marked->GetPointData()->AddArray(targetArray);
  tsynth::addPointArray(marked, "TargetConfidence", confidence.data());
  chain.extractor->SetInputData(0, marked);
  chain.extractor->Update();
  ASSERT_EQ(chain.errors, "");
  const double pulled = chain.field("VerticalOffset");

  // The kernel's fit of the same patch to the same grid.
  vtkTable* matches = chain.matcher->GetMatches();
  tsynth::PatchCandidate match;
  match.variant = matches->GetColumnByName("Variant")->GetVariantValue(1).ToInt();
  match.centreX = matches->GetColumnByName("CellX")->GetVariantValue(1).ToDouble();
  match.centreY = matches->GetColumnByName("CellY")->GetVariantValue(1).ToDouble();
  const tsynth::Heightfield patch = tsynth::extractPatch(terrain, match, 80);
  const std::vector<std::uint8_t> filled = tsynth::filledCells(marked, terrain);
  const tsynth::Heightfield low = tsynth::landformImage(target, 80);
  EXPECT_EQ(pulled, tsynth::fitPatchOffset(patch, x0, y0, { terrain, filled, low, confidence }));
  // Without the target, only the filled quarter counts: the target's 500 m pull is gone.
  marked->GetPointData()->RemoveArray("Target");
  marked->Modified();
  chain.extractor->Update();
  const double unpulled = chain.field("VerticalOffset");
  EXPECT_GT(pulled - unpulled, 100.0) << pulled << " against " << unpulled;
}

TEST(PatchExtractor, TheMergerPlacesTheExtractedPatchOnTheMatchedWindow)
{
  // Matcher, extractor and merger chained: the best feature match merged into
  // the DEM takes at least its core, on the matched window only; the rest of
  // the terrain stays as it was, bit for bit.
  Chain chain(vtkTerrainPatchMatcher::FEATURE);
  vtkNew<vtkTerrainGraphCutMerger> merger;
  merger->SetInputConnection(0, chain.reader->GetOutputPort());
  merger->SetInputConnection(1, chain.extractor->GetOutputPort());
  merger->Update();
  ASSERT_EQ(chain.errors, "");
  vtkImageData* merged = merger->GetOutput();
  const int x0 = chain.patchCell(0);
  const int y0 = chain.patchCell(1);
  int taken = 0;
  int dims[3];
  merged->GetDimensions(dims);
  for (int j = 0; j < dims[1]; ++j)
  {
    for (int i = 0; i < dims[0]; ++i)
    {
      const bool inWindow = i >= x0 && i < x0 + 80 && j >= y0 && j < y0 + 80;
      if (pointValue(merged, "PatchId", i, j) == 1.0)
      {
        ++taken;
        ASSERT_TRUE(inWindow) << i << ", " << j;
      }
      if (!inWindow)
      {
        ASSERT_EQ(
          pointValue(merged, "Elevation", i, j), pointValue(chain.terrain(), "Elevation", i, j))
          << i << ", " << j;
      }
    }
  }
  EXPECT_GT(taken, 250); // the core alone is about 314 cells
}

TEST(PatchExtractor, RefusesARankPastTheMatchesAndATableWithoutCentres)
{
  Chain chain(vtkTerrainPatchMatcher::FEATURE);
  chain.extractor->SetRank(1000);
  chain.extractor->Update();
  EXPECT_NE(chain.errors.find("Rank 1000 asks for a match past the"), std::string::npos)
    << chain.errors;
  EXPECT_EQ(chain.patch()->GetNumberOfPoints(), 0);
  chain.errors.clear();
  chain.matcher->Update();
  vtkNew<vtkTable> noCentres;
  noCentres->DeepCopy(chain.matcher->GetMatches());
  noCentres->RemoveColumnByName("CellX");
  chain.extractor->SetRank(0);
  chain.extractor->SetInputData(2, noCentres);
  chain.extractor->Update();
  EXPECT_NE(chain.errors.find("The matches have no column CellX"), std::string::npos)
    << chain.errors;
}
