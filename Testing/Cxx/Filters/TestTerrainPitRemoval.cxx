// The Terrain Pit Removal filter (Filters/vtkTerrainPitRemoval.h) gives what
// its kernel (Kernels/Hydrology/PitRemoval.h) and the flow routing (Flow.h)
// give, keeps nodata and the user's sinks, and refuses what cannot drain.
#include "FilterTesting.h"
#include "vtkTerrainPitRemoval.h"

#include "Hydrology/Flow.h"
#include "Hydrology/PitRemoval.h"

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkTrivialProducer.h>

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace tsynth
{
namespace
{

using test::asDoubles;
using test::pointValues;

struct PitRun
{
  vtkNew<vtkTerrainPitRemoval> filter;
  test::FilterErrors errors{ filter };
  bool ok = false;
  vtkImageData* output() { return filter->GetOutput(); }
};

// The filter on `dem` with `method` (and sinks where `sinks` is non-zero).
void run(PitRun& r,
  const Heightfield& dem,
  int method,
  const Heightfield* sinks = nullptr,
  int streamThreshold = 0)
{
  r.filter->SetInputData(0, test::imageOf(dem));
  if (sinks != nullptr)
  {
    r.filter->SetInputData(1, test::imageOf(*sinks));
  }
  r.filter->SetMethod(method);
  r.filter->SetStreamThreshold(streamThreshold);
  r.filter->Update();
  r.ok = r.errors.text.empty();
}

} // namespace

TEST(TerrainPitRemovalFilter, EachMethodGivesItsKernelsHeightsAndFlow)
{
  const Heightfield dem = test::roughDem(64, 48, true);
  ASSERT_GT(countPits(dem), 5u) << "the test DEM should have pits to remove";
  const int methods[] = {
    vtkTerrainPitRemoval::FILL, vtkTerrainPitRemoval::BREACH, vtkTerrainPitRemoval::HYBRID
  };
  for (int method : methods)
  {
    SCOPED_TRACE(method);
    PitRun r;
    run(r, dem, method);
    ASSERT_TRUE(r.ok) << r.errors.text;
    PitRemovalOptions options;
    options.method = static_cast<PitRemovalMethod>(method);
    const PitRemovalResult kernel = removePits(dem, options);
    const std::vector<double> heights = pointValues(r.output(), "Elevation");
    ASSERT_EQ(heights.size(), dem.size());
    for (std::size_t k = 0; k < dem.size(); ++k)
    {
      if (dem.isValid(k))
      {
        ASSERT_EQ(heights[k], kernel.dem.z[k]) << "cell " << k;
      }
      else
      {
        ASSERT_TRUE(std::isnan(heights[k])) << "nodata stays nodata, cell " << k;
      }
    }
    EXPECT_EQ(pointValues(r.output(), "Changed"), asDoubles(kernel.changed));
    const std::vector<std::int8_t> directions = flowDirections(kernel.dem);
    EXPECT_EQ(pointValues(r.output(), "FlowDirection"), asDoubles(directions));
    EXPECT_EQ(pointValues(r.output(), "FlowAccumulation"),
      asDoubles(flowAccumulation(directions, dem.width, dem.height, &dem.valid)));
    EXPECT_EQ(pointValues(r.output(), "Valid"), asDoubles(dem.valid));
    EXPECT_TRUE(pointValues(r.output(), "Streams").empty()) << "no threshold, no streams";
    EXPECT_TRUE(drainsEverywhere(kernel.dem, nullptr));
  }
}

TEST(TerrainPitRemovalFilter, AUserSinkKeepsItsHeightAndStreamsFollowTheThreshold)
{
  const Heightfield dem = test::roughDem(64, 48, false);
  // The lowest interior pit is the user's lake.
  std::size_t lake = dem.size();
  for (int j = 1; j + 1 < dem.height; ++j)
  {
    for (int i = 1; i + 1 < dem.width; ++i)
    {
      bool pit = true;
      for (int dj = -1; dj <= 1; ++dj)
      {
        for (int di = -1; di <= 1; ++di)
        {
          pit = pit && ((di == 0 && dj == 0) || dem.at(i + di, j + dj) > dem.at(i, j));
        }
      }
      if (pit && (lake == dem.size() || dem.at(i, j) < dem.z[lake]))
      {
        lake = dem.index(i, j);
      }
    }
  }
  ASSERT_LT(lake, dem.size());
  Heightfield sinks(dem.width, dem.height);
  sinks.cellX = dem.cellX;
  sinks.cellY = dem.cellY;
  sinks.z[lake] = 1.0f;
  PitRun filled;
  run(filled, dem, vtkTerrainPitRemoval::FILL, &sinks, 40);
  ASSERT_TRUE(filled.ok) << filled.errors.text;
  const std::vector<double> heights = pointValues(filled.output(), "Elevation");
  EXPECT_EQ(heights[lake], dem.z[lake]) << "the lake is not filled";
  PitRun without;
  run(without, dem, vtkTerrainPitRemoval::FILL);
  EXPECT_GT(pointValues(without.output(), "Elevation")[lake], dem.z[lake]);
  // Streams: 1 exactly where at least 40 cells drain through.
  const std::vector<double> streams = pointValues(filled.output(), "Streams");
  const std::vector<double> accumulation = pointValues(filled.output(), "FlowAccumulation");
  ASSERT_EQ(streams.size(), dem.size());
  std::size_t streamCells = 0;
  for (std::size_t k = 0; k < dem.size(); ++k)
  {
    EXPECT_EQ(streams[k], accumulation[k] >= 40 ? 1.0 : 0.0);
    streamCells += streams[k] != 0.0 ? 1 : 0;
  }
  EXPECT_GT(streamCells, 0u);
  EXPECT_LT(streamCells, dem.size() / 4);
}

TEST(TerrainPitRemovalFilter, AFlatDemOrASinkMaskOfAnotherSizeFailsTheRequest)
{
  Heightfield flat(32, 32);
  flat.cellX = flat.cellY = 30.0;
  flat.z.assign(flat.size(), 500.0f);
  PitRun r;
  run(r, flat, vtkTerrainPitRemoval::BREACH);
  EXPECT_NE(r.errors.text.find("flat"), std::string::npos) << r.errors.text;

  const Heightfield dem = test::roughDem(40, 30, false);
  Heightfield sinks(20, 30);
  sinks.cellX = sinks.cellY = 30.0;
  PitRun mismatched;
  run(mismatched, dem, vtkTerrainPitRemoval::BREACH, &sinks);
  EXPECT_NE(mismatched.errors.text.find("20 x 30"), std::string::npos) << mismatched.errors.text;
}

} // namespace tsynth
