// Tests of Kernels/Synthesis/Setup.cxx.
#include "Core/Error.h"
#include "ErrorOf.h"
#include "PreviewTestData.h"
#include "Synthesis/Setup.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <memory>
#include <string>

using namespace tsynth;
using tsynth::test::preview::inputsFor;

namespace
{

constexpr double kCell = 90.0; // the bundled DEMs' cell size
constexpr int kPatch = 32;

Polyline line(std::vector<Point2> points, FeatureType type = FeatureType::Ridge)
{
  Polyline p;
  p.points = std::move(points);
  p.type = type;
  return p;
}

PolylineSketch sketchOf(std::vector<Polyline> lines)
{
  PolylineSketch s;
  s.lines = std::move(lines);
  return s;
}

SetupOptionNames cliNames()
{
  SetupOptionNames n;
  n.size = "--size";
  n.cell = "--cell";
  n.patch = "--patch";
  n.memory = "--max-memory";
  return n;
}

using tsynth::test::errorOf;

OutputGrid gridOf(const PolylineSketch& s, GridRequest request = {})
{
  return outputGrid(polylineExtent(s), request, kCell, kCell, kPatch, cliNames());
}

// A ridge of Gaussian cross-section along x = width / 2, heights in metres.
Heightfield ridgeExemplar(int n, double cell)
{
  Heightfield hf(n, n);
  hf.cellX = hf.cellY = cell;
  hf.cellSizeKnown = true;
  for (int j = 0; j < n; ++j)
  {
    for (int i = 0; i < n; ++i)
    {
      const double d = (i - 0.5 * n) / (0.08 * n);
      hf.at(i, j) = static_cast<float>(1000.0 + 400.0 * std::exp(-0.5 * d * d) + 0.5 * j);
    }
  }
  return hf;
}

} // namespace

TEST(Setup, RasterKindsFollowBandsAndSampleSize)
{
  EXPECT_TRUE(rasterIsDemTarget(1, false)); // Int16, Float32 ...: a DEM
  EXPECT_FALSE(rasterIsDemTarget(1, true)); // an 8-bit grey sketch map
  EXPECT_FALSE(rasterIsDemTarget(3, true)); // a stroke map
  EXPECT_FALSE(rasterIsDemTarget(3, false));
}

TEST(Setup, PolylinesGiveTheGridTheyWereFoundOn)
{
  // A feature tree of a 192 x 160-cell DEM at 90 m, its lines well inside it.
  PolylineSketch s = sketchOf({ line({ { 900, 900 }, { 9000, 7200 } }) });
  s.frameWidth = 192 * kCell;
  s.frameHeight = 160 * kCell;
  const OutputGrid g = gridOf(s);
  EXPECT_EQ(g.width, 192);
  EXPECT_EQ(g.height, 160);
  EXPECT_EQ(g.cellX, kCell);
  EXPECT_EQ(g.cellY, kCell);
  // The same ground at half the cell size: twice the cells.
  GridRequest finer;
  finer.cellX = finer.cellY = 45.0;
  const OutputGrid h = gridOf(s, finer);
  EXPECT_EQ(h.width, 384);
  EXPECT_EQ(h.height, 320);
}

TEST(Setup, PolylinesWithoutAFrameReachAsFarAsTheLines)
{
  // Cell centres at multiples of 90 m: x up to 14310 m is cell 159, y 12600 m cell 140; the
  // output reaches half a patch (16 cells) further, so the last stroke is not on the border.
  const PolylineSketch s = sketchOf({ line({ { 0, 0 }, { 14310, 12600 } }),
    line({ { 4500, 9000 }, { 9000, 9000 } }, FeatureType::Valley) });
  const OutputGrid g = gridOf(s);
  EXPECT_EQ(g.width, 160 + kPatch / 2);
  EXPECT_EQ(g.height, 141 + kPatch / 2);
}

TEST(Setup, PolylinesInCellsAreRefusedWithWhatWasFound)
{
  // Coordinates 10..190 look like cells: at 90 m they make a 3 x 3-cell output.
  const PolylineSketch s = sketchOf({ line({ { 20, 100 }, { 180, 100 } }),
    line({ { 10, 190 }, { 190, 150 } }, FeatureType::Valley) });
  const std::string m = errorOf([&] { gridOf(s); });
  EXPECT_NE(m.find("span 180 x 90 m"), std::string::npos) << m;
  EXPECT_NE(m.find("3 x 3 cells of 90 m"), std::string::npos) << m;
  EXPECT_NE(m.find("are they in cells"), std::string::npos) << m;
  EXPECT_NE(m.find("--size"), std::string::npos) << m;
  EXPECT_NE(m.find("--cell"), std::string::npos) << m;
}

TEST(Setup, PolylinesInDegreesAreRefused)
{
  const PolylineSketch s = sketchOf({ line({ { -105.2, 39.1 }, { -104.9, 39.3 } }) });
  const std::string m = errorOf([&] { gridOf(s); });
  EXPECT_NE(m.find("west or south of the raster frame"), std::string::npos) << m;
  EXPECT_NE(m.find("degrees"), std::string::npos) << m;
}

TEST(Setup, PolylinesMustMeetARequestedGrid)
{
  GridRequest size;
  size.width = size.height = 160;
  // Shorter than one cell, whatever the output size.
  const std::string tiny = errorOf(
    [&] {
      gridOf(sketchOf({ line({ { 0.1, 0.2 }, { 0.6, 0.5 } }) }), size);
    });
  EXPECT_NE(tiny.find("less than one cell of 90 m"), std::string::npos) << tiny;
  // Projected world coordinates: far outside a 160-cell output.
  const std::string world = errorOf(
    [&] {
      gridOf(sketchOf({ line({ { 500000, 4200000 }, { 510000, 4201000 } }) }), size);
    });
  EXPECT_NE(world.find("outside the output (14400 x 14400 m)"), std::string::npos) << world;
  // Lines inside: the request is the grid.
  const OutputGrid g = gridOf(sketchOf({ line({ { 900, 900 }, { 9000, 900 } }) }), size);
  EXPECT_EQ(g.width, 160);
  EXPECT_EQ(g.height, 160);
}

TEST(Setup, RasterSketchesGiveTheirPixelsAndSmallOutputsAreRefused)
{
  GridRequest none;
  const OutputGrid g = outputGrid(rasterExtent(512, 256), none, 30.0, 31.0, kPatch);
  EXPECT_EQ(g.width, 512);
  EXPECT_EQ(g.height, 256);
  EXPECT_EQ(g.cellX, 30.0);
  EXPECT_EQ(g.cellY, 31.0);
  GridRequest small;
  small.width = 20;
  small.height = 200;
  const std::string m =
    errorOf([&] { outputGrid(rasterExtent(512, 256), small, 30.0, 30.0, kPatch, cliNames()); });
  EXPECT_NE(m.find("20 x 200 cells) is smaller than one patch (32)"), std::string::npos) << m;
  GridRequest oneSide;
  oneSide.width = 100;
  EXPECT_THROW(outputGrid(rasterExtent(512, 256), oneSide, 30.0, 30.0, kPatch), Error);
}

namespace
{

// The ridge exemplar on 45 m cells and a ridge sketched from 600 m to 5400 m
// at y = 3000 m on 30 m cells: cells 20 to 180 of row 100, in an output half
// a patch larger. Seed 5.
SetupInputs ridgeOnThirtyMetreCells()
{
  SetupInputs in;
  in.exemplars.push_back(ridgeExemplar(200, 45.0));
  in.exemplarNames.push_back("ridge.tif");
  in.sketch = sketchOf({ line({ { 600, 3000 }, { 5400, 3000 } }) });
  in.grid.cellX = in.grid.cellY = 30.0;
  in.patchSize = kPatch;
  in.seed = 5;
  return in;
}

} // namespace

TEST(Setup, PrepareConvertsMetresResamplesExemplarsAndBuildsTheTarget)
{
  const SynthesisSetup s = prepareSynthesis(ridgeOnThirtyMetreCells());
  EXPECT_EQ(s.sketchKind, "poly-lines");
  // What it was prepared for, which the synthesis must then be asked for.
  EXPECT_EQ(s.patchSize, kPatch);
  EXPECT_EQ(s.seed, 5u);
  SynthesisOptions other;
  other.patchSize = kPatch + kPatchSizeStep;
  other.seed = 5;
  EXPECT_EQ(errorOf([&] { synthesise(s, other); }),
    "The synthesis was asked for " + std::to_string(kPatch + kPatchSizeStep) +
      "-cell patches and seed 5, but its set-up was prepared for " + std::to_string(kPatch) +
      "-cell patches and seed 5: prepare it again from the same request.");
  other.patchSize = kPatch;
  other.seed = 6;
  EXPECT_NE(errorOf([&] { synthesise(s, other); }), "");
  EXPECT_EQ(s.grid.width, 181 + kPatch / 2);
  EXPECT_EQ(s.grid.height, 101 + kPatch / 2);
  EXPECT_EQ(s.target.field.width, 181 + kPatch / 2);
  EXPECT_EQ(s.target.field.height, 101 + kPatch / 2);
  EXPECT_EQ(s.target.field.cellX, 30.0);
  // 199 intervals of 45 m on 30 m cells: 299 cells a side.
  ASSERT_EQ(s.exemplars.size(), 1u);
  EXPECT_EQ(s.exemplars[0].width, 299);
  EXPECT_EQ(s.exemplars[0].cellX, 30.0);
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("ridge.tif has 45 m cells; resampled to the output's 30 m"),
    std::string::npos)
    << s.warnings[0];
  EXPECT_FALSE(s.graphs[0].chains.empty()); // the exemplar's ridge was found
  // The sketched ridge on the output grid, in cells.
  ASSERT_EQ(s.target.graph.chains.size(), 1u);
  const auto& points = s.target.graph.chains[0].points;
  const Point2 a = points.front();
  const Point2 b = points.back();
  EXPECT_DOUBLE_EQ(std::min(a.x, b.x), 20.0);
  EXPECT_DOUBLE_EQ(std::max(a.x, b.x), 180.0);
  EXPECT_DOUBLE_EQ(a.y, 100.0);
  EXPECT_DOUBLE_EQ(b.y, 100.0);
  EXPECT_GT(s.memoryEstimate, 0.0);
  EXPECT_LE(s.memoryEstimate, s.memoryBudget);
}

// tsynth synth synthesises from its set-up once: the candidate pool it hands
// over goes as soon as the placement ends, before the finishing's planes are
// made, and the terrain is the one synthesise() makes from a set-up that
// keeps its pool.
TEST(Setup, APoolTakenOverGoesWhenThePlacementEndsAndChangesNothing)
{
  SynthesisSetup taken = prepareSynthesis(ridgeOnThirtyMetreCells());
  const SynthesisSetup kept = prepareSynthesis(ridgeOnThirtyMetreCells());
  const std::weak_ptr<const CandidatePool> pool = taken.pool;
  ASSERT_FALSE(pool.expired());
  SynthesisOptions o;
  o.patchSize = kPatch;
  o.seed = 5;
  o.tileSize = 2 * kPatch; // the tiled run reports its finishing as a stage
  o.backend = Backend::Cpu;
  std::map<std::string, bool> heldWhenFirstReported;
  o.progress = [&](double, const std::string& stage)
  { heldWhenFirstReported.emplace(stage, !pool.expired()); };
  const SynthesisResult r = synthesiseTakingPool(taken, o);
  EXPECT_EQ(taken.pool, nullptr);
  ASSERT_EQ(heldWhenFirstReported.count("fill"), 1u);
  ASSERT_EQ(heldWhenFirstReported.count("finishing"), 1u);
  EXPECT_TRUE(heldWhenFirstReported["fill"]); // the placement matched with it
  EXPECT_FALSE(heldWhenFirstReported["finishing"]);
  EXPECT_TRUE(pool.expired());

  o.progress = nullptr;
  const SynthesisResult same = synthesise(kept, o);
  EXPECT_NE(kept.pool, nullptr); // synthesise() leaves the set-up its pool
  EXPECT_EQ(same.terrain.z, r.terrain.z);
}

TEST(Setup, ImagesAndDemsAreNamedAndKeepTheirPixels)
{
  ColourImage strokes;
  strokes.width = 96;
  strokes.height = 64;
  strokes.channels = 3;
  strokes.data.assign(static_cast<std::size_t>(96 * 64 * 3), 255);
  for (int i = 10; i < 86; ++i)
  {
    for (int j = 30; j < 34; ++j)
    {
      std::uint8_t* p = strokes.data.data() + (static_cast<std::size_t>(j) * 96 + i) * 3;
      p[0] = 255; // red: a ridge stroke
      p[1] = p[2] = 0;
    }
  }
  const OutputGrid grid{ 96, 64, kCell, kCell };
  const AnalysedSketch a = analyseSketch(strokes, grid, kPatch);
  EXPECT_EQ(a.kind, "stroke map");
  EXPECT_EQ(a.width, 96);
  EXPECT_FALSE(a.hasHeights);
  const AnalysedSketch d = analyseSketch(ridgeExemplar(64, kCell), grid, kPatch);
  EXPECT_EQ(d.kind, "DEM");
  EXPECT_TRUE(d.hasHeights);
  EXPECT_EQ(d.heights.width, 64);
  const std::string m = errorOf([&] { analyseSketch(ridgeExemplar(20, kCell), grid, kPatch); });
  EXPECT_NE(m.find("smaller than one patch"), std::string::npos) << m;
}

TEST(Setup, MemoryOverTheBudgetIsRefusedWithTheEstimate)
{
  const double small = synthesisMemoryEstimate(160, 160, { 200 * 200 });
  EXPECT_GT(synthesisMemoryEstimate(320, 320, { 200 * 200 }), small);
  EXPECT_GT(synthesisMemoryEstimate(160, 160, { 200 * 200, 200 * 200 }), small);
  // The OpenCL matcher's runtime and device pool: 85 MB and 64 bytes per
  // exemplar cell more (measured 110 MB with one 648 x 648 exemplar).
  EXPECT_NEAR(synthesisMemoryEstimate(160, 160, { 648 * 648 }, true) -
      synthesisMemoryEstimate(160, 160, { 648 * 648 }, false),
    110.0e6,
    5.0e6);
  SetupInputs in;
  in.matcherBackend = Backend::Cpu;
  in.exemplars.push_back(ridgeExemplar(200, kCell));
  // To 12870 m, cell 143, and half a patch beyond: 160 x 160 cells.
  in.sketch = sketchOf({ line({ { 900, 900 }, { 12870, 12870 } }) });
  in.patchSize = kPatch;
  in.memoryBudget = 0.5 * small;
  in.names = cliNames();
  const std::string m = errorOf([&] { prepareSynthesis(in); });
  EXPECT_NE(m.find("160 x 160 cells from 1 exemplar(s) needs about " +
              std::to_string(static_cast<int>(std::lround(small / 1e6))) + " MB"),
    std::string::npos)
    << m;
  EXPECT_NE(m.find("raise --max-memory"), std::string::npos) << m;
  in.memoryBudget = 1.01 * small; // just enough
  EXPECT_EQ(prepareSynthesis(in).grid.width, 160);
}

TEST(Setup, NoExemplarOrNoLinesAreRefused)
{
  SetupInputs in;
  in.sketch = sketchOf({ line({ { 900, 900 }, { 9000, 900 } }) });
  EXPECT_NE(errorOf([&] { prepareSynthesis(in); }).find("No exemplar"), std::string::npos);
  EXPECT_NE(errorOf([&] { polylineExtent(PolylineSketch{}); }).find("no lines"), std::string::npos);
}

TEST(Preview, RequestKeyFollowsWhatChangesTheTerrainOnly)
{
  const SetupInputs in = inputsFor(256, 80);
  SynthesisOptions o;
  const std::uint64_t key = synthesisRequestKey(in, o);
  EXPECT_EQ(synthesisRequestKey(inputsFor(256, 80), SynthesisOptions{}), key);

  SynthesisOptions cpu = o; // every backend gives the same bits
  cpu.backend = Backend::Cpu;
  cpu.progress = [](double, const std::string&) {};
  EXPECT_EQ(synthesisRequestKey(in, cpu), key);

  SetupInputs edited = in; // one pixel of the sketch
  std::get<ColourImage>(edited.sketch).data[1000] = 0;
  EXPECT_NE(synthesisRequestKey(edited, o), key);
  SetupInputs moved = in; // one exemplar height
  moved.exemplars[0].at(3, 4) += 1.0f;
  EXPECT_NE(synthesisRequestKey(moved, o), key);
  SetupInputs wider = in;
  wider.grid.width = 300;
  EXPECT_NE(synthesisRequestKey(wider, o), key);
  SynthesisOptions seeded = o;
  seeded.seed = 1;
  EXPECT_NE(synthesisRequestKey(in, seeded), key);
  SynthesisOptions regions = o;
  regions.regionLabels.assign(256 * 128, 0);
  SynthesisOptions otherRegions = regions;
  otherRegions.regionLabels[77] = 1;
  EXPECT_NE(synthesisRequestKey(in, regions), key);
  EXPECT_NE(synthesisRequestKey(in, otherRegions), synthesisRequestKey(in, regions));
  SynthesisOptions spaced = o;
  spaced.fillSpacing = 0.75;
  EXPECT_NE(synthesisRequestKey(in, spaced), key);
  SynthesisOptions tiled = o; // tiles change the terrain (Tiling.h)
  tiled.tileSize = 128;
  EXPECT_NE(synthesisRequestKey(in, tiled), key);
  SynthesisOptions drained = o;
  drained.drainage = PitRemovalMethod::Fill;
  EXPECT_NE(synthesisRequestKey(in, drained), key);
}
