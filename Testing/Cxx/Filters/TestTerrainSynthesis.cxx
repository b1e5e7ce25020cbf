// The Terrain Synthesis filter (Filters/vtkTerrainSynthesis.h) gives the
// heights its kernels give for the same request (SynthesisRequest.h: the
// set-up, then synthesise), the same for the same seed and others for another;
// and refuses a request it cannot serve. A small Y of ridges over Colorado.
#include "FilterTesting.h"
#include "TestData.h"
#include "vtkTerrainReader.h"
#include "vtkTerrainSketchReader.h"
#include "vtkTerrainSynthesis.h"

#include "Core/HeightfieldIO.h"
#include "Synthesis/SynthesisRequest.h"

#include <vtkImageData.h>
#include <vtkNew.h>

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace tsynth
{
namespace
{

constexpr int kSize = 128; // cells a side
constexpr int kPatch = 32;

std::string coloradoPath()
{
  return test::realDem("colorado.png");
}

std::string yPath()
{
  return (test::bundledData() / "sketches" / "strokes_y_ridges.png").string();
}

// The filter on Colorado and the Y, read by the plugin's readers, on the CPU.
struct YFilter
{
  vtkNew<vtkTerrainReader> exemplar;
  vtkNew<vtkTerrainSketchReader> sketch;
  vtkNew<vtkTerrainSynthesis> synthesis;
  test::FilterErrors errors{ synthesis };

  explicit YFilter(int seed)
  {
    exemplar->SetFileName(coloradoPath().c_str());
    sketch->SetFileName(yPath().c_str());
    sketch->SetExemplarFileName(coloradoPath().c_str());
    synthesis->AddInputConnection(0, exemplar->GetOutputPort());
    synthesis->SetSketchConnection(sketch->GetOutputPort());
    synthesis->SetOutputSize(kSize, kSize);
    synthesis->SetPatchSize(kPatch);
    synthesis->SetBackend(vtkTerrainSynthesis::CPU);
    synthesis->SetUseExemplarCache(false);
    synthesis->SetSeed(seed);
  }
  std::vector<double> heights()
  {
    synthesis->Update();
    return test::pointValues(synthesis->GetTerrain(), "Elevation");
  }
};

} // namespace

TEST(TerrainSynthesisFilter, GivesTheKernelsHeightsForTheSameRequest)
{
  YFilter filter(5);
  const std::vector<double> heights = filter.heights();
  ASSERT_TRUE(filter.errors.text.empty()) << filter.errors.text;
  ASSERT_EQ(heights.size(), static_cast<std::size_t>(kSize * kSize));

  SynthesisRequest request;
  request.grid.width = kSize;
  request.grid.height = kSize;
  request.options.patchSize = kPatch;
  request.options.backend = Backend::Cpu;
  request.options.seed = 5;
  request.useExemplarCache = false;
  const SketchInput sketch = readColourImage(yPath());
  const SetupOptionNames names;
  resolvePatchSize(request, sketch, names);
  const SynthesisSetup setup = prepareSynthesis(
    setupInputs(request, { readHeightfield(coloradoPath()) }, { "colorado.png" }, sketch, names));
  const SynthesisResult kernel = synthesise(setup, request.options);
  ASSERT_EQ(kernel.terrain.size(), heights.size());
  for (std::size_t k = 0; k < heights.size(); ++k)
  {
    ASSERT_EQ(heights[k], kernel.terrain.z[k]) << "cell " << k;
  }
}

TEST(TerrainSynthesisFilter, TheSameSeedGivesTheSameTerrainAndAnotherSeedAnother)
{
  YFilter a(11), b(11), c(12);
  const std::vector<double> first = a.heights();
  ASSERT_TRUE(a.errors.text.empty()) << a.errors.text;
  EXPECT_EQ(first, b.heights());
  const std::vector<double> other = c.heights();
  ASSERT_EQ(other.size(), first.size());
  std::size_t differ = 0;
  for (std::size_t k = 0; k < first.size(); ++k)
  {
    differ += first[k] != other[k] ? 1 : 0;
  }
  EXPECT_GT(differ, first.size() / 2) << "another seed places other patches";
}

TEST(TerrainSynthesisFilter, APatchSizeItCannotUseFailsTheRequestNamingIt)
{
  YFilter filter(1);
  filter.synthesis->SetPatchSize(30); // not a multiple of 4
  filter.synthesis->Update();
  EXPECT_NE(filter.errors.text.find("Patch Size"), std::string::npos) << filter.errors.text;
}

} // namespace tsynth

namespace tsynth
{
namespace
{

// Two ridges far apart on a 384 x 256 sketch, the east one shifted by `shift` pixels.
std::string twoRidgesSketch(int shift)
{
  constexpr int kWidth = 384;
  constexpr int kHeight = 256;
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(kWidth) * kHeight * 3, 255);
  auto ridge = [&](int x0, int x1)
  {
    for (int row = 40; row <= 215; ++row)
    {
      const int centre = x0 + (x1 - x0) * (row - 40) / (215 - 40);
      for (int column = centre - 1; column <= centre + 1; ++column)
      {
        std::uint8_t* p = rgb.data() + (static_cast<std::size_t>(row) * kWidth + column) * 3;
        p[0] = 230;
        p[1] = 20;
        p[2] = 20;
      }
    }
  };
  ridge(50, 60);
  ridge(320 + shift, 330 + shift);
  const std::string path =
    (test::scratchDir() / ("two-ridges-" + std::to_string(shift) + ".png")).string();
  writeRgbPng(path, kWidth, kHeight, rgb);
  return path;
}

struct TiledFilter
{
  vtkNew<vtkTerrainReader> exemplar;
  vtkNew<vtkTerrainSketchReader> sketch;
  vtkNew<vtkTerrainSynthesis> synthesis;
  test::FilterErrors errors{ synthesis };

  explicit TiledFilter(const std::string& sketchPath)
  {
    exemplar->SetFileName(coloradoPath().c_str());
    sketch->SetFileName(sketchPath.c_str());
    sketch->SetExemplarFileName(coloradoPath().c_str());
    synthesis->AddInputConnection(0, exemplar->GetOutputPort());
    synthesis->SetSketchConnection(sketch->GetOutputPort());
    synthesis->SetOutputSize(384, 256);
    synthesis->SetPatchSize(kPatch);
    synthesis->SetTileSize(2 * kPatch);
    synthesis->SetBackend(vtkTerrainSynthesis::CPU);
    synthesis->SetUseExemplarCache(false);
  }
  std::vector<double> heights()
  {
    synthesis->Update();
    return test::pointValues(synthesis->GetTerrain(), "Elevation");
  }
};

} // namespace

TEST(TerrainSynthesisFilter, AnEditedSketchPlacesAgainOnlyTheTilesItReaches)
{
  const std::string before = twoRidgesSketch(0);
  const std::string after = twoRidgesSketch(10);
  TiledFilter filter(before);
  filter.heights();
  ASSERT_TRUE(filter.errors.text.empty()) << filter.errors.text;
  EXPECT_EQ(filter.synthesis->GetTilesTakenOver(), 0);
  filter.sketch->SetFileName(after.c_str());
  const std::vector<double> edited = filter.heights();
  ASSERT_TRUE(filter.errors.text.empty()) << filter.errors.text;
  // 24 tiles in two passes; the west ridge's third of them lies past the edit's reach.
  EXPECT_GE(filter.synthesis->GetTilesTakenOver(), 16);
  EXPECT_LT(filter.synthesis->GetTilesTakenOver(), 48);
  TiledFilter fresh(after);
  EXPECT_EQ(edited, fresh.heights());
  EXPECT_EQ(fresh.synthesis->GetTilesTakenOver(), 0);
  // Another seed: the record cannot serve it, and the synthesis is a full one.
  filter.synthesis->SetSeed(3);
  filter.heights();
  ASSERT_TRUE(filter.errors.text.empty()) << filter.errors.text;
  EXPECT_EQ(filter.synthesis->GetTilesTakenOver(), 0);
}

} // namespace tsynth
