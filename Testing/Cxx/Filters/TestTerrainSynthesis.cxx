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
