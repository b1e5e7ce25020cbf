// Tests of Kernels/Synthesis/TileRecord.cxx.
// Local re-synthesis (Synthesis/TileRecord.h): a tiled synthesis of an edited
// sketch that takes unchanged tiles from the previous run's record is the same
// bits as a full synthesis of the edited sketch, and takes over the tiles the
// edit does not reach; the record survives its bytes, and a damaged record or
// one of another run is refused.
#include "Core/Error.h"
#include "Core/HeightfieldIO.h"
#include "Synthesis/Setup.h"
#include "Synthesis/Synthesiser.h"
#include "Synthesis/TileRecord.h"
#include "Synthesis/Tiling.h"
#include "TestData.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>
#include <memory>

using namespace tsynth;

namespace
{

// Two ridges drawn far apart on a terrain of kWidth x kHeight cells, one
// pixel per cell; the east one shifted by `shift` pixels.
constexpr int kWidth = 384;
constexpr int kHeight = 256;
constexpr int kPatch = 32;
constexpr int kTile = 64; // two patches: the smallest tile, so the edit's reach spans few
constexpr int kEastShift = 10;

void drawRidge(ColourImage& image, double x0, double y0, double x1, double y1)
{
  constexpr double kHalfWidth = 1.5;
  const std::uint8_t red[3] = { 230, 20, 20 };
  for (int row = 0; row < image.height; ++row)
  {
    for (int column = 0; column < image.width; ++column)
    {
      const double dx = x1 - x0;
      const double dy = y1 - y0;
      const double t =
        std::clamp(((column - x0) * dx + (row - y0) * dy) / (dx * dx + dy * dy), 0.0, 1.0);
      if (std::hypot(column - (x0 + t * dx), row - (y0 + t * dy)) <= kHalfWidth)
      {
        std::memcpy(
          image.data.data() + (static_cast<std::size_t>(row) * image.width + column) * 3, red, 3);
      }
    }
  }
}

ColourImage twoRidges(int shift)
{
  ColourImage image;
  image.width = kWidth;
  image.height = kHeight;
  image.channels = 3;
  image.data.assign(static_cast<std::size_t>(kWidth) * kHeight * 3, 255);
  drawRidge(image, 50, 40, 60, 215);
  drawRidge(image, 320 + shift, 40, 330 + shift, 215);
  return image;
}

const SynthesisSetup& setupOf(int shift)
{
  static std::map<int, std::unique_ptr<SynthesisSetup>> setups;
  auto& s = setups[shift];
  if (!s)
  {
    SetupInputs in;
    in.exemplars.push_back(readHeightfield(test::realDem("colorado.png")));
    in.sketch = twoRidges(shift);
    in.grid.width = kWidth;
    in.grid.height = kHeight;
    in.patchSize = kPatch;
    in.matcherBackend = Backend::Cpu;
    s = std::make_unique<SynthesisSetup>(prepareSynthesis(in));
  }
  return *s;
}

SynthesisResult tiled(int shift,
  bool keepRecord,
  std::shared_ptr<const PlacementRecord> previous = nullptr,
  std::uint64_t seed = 0)
{
  const SynthesisSetup& setup = setupOf(shift);
  SynthesisOptions o;
  o.patchSize = kPatch;
  o.backend = Backend::Cpu;
  o.tileSize = kTile;
  o.seed = seed;
  o.keepRecord = keepRecord;
  o.previous = std::move(previous);
  o.pool = setup.pool;
  return synthesise(setup.target, setup.exemplarPointers(), setup.graphPointers(), o);
}

// Heights compared bit for bit (NaN where both are NaN counts as the same).
std::size_t differingCells(const Heightfield& a, const Heightfield& b)
{
  std::size_t n = 0;
  for (std::size_t c = 0; c < a.size(); ++c)
  {
    n += std::memcmp(&a.z[c], &b.z[c], sizeof(float)) != 0 ? 1 : 0;
  }
  return n;
}

} // namespace

TEST(TileRecord, ReSynthesisOfAnEditIsAFullSynthesisAndKeepsTheTilesItDoesNotReach)
{
  const SynthesisResult before = tiled(0, true);
  ASSERT_NE(before.record, nullptr);
  EXPECT_EQ(before.tilesTakenOver, 0u);
  const SynthesisResult full = tiled(kEastShift, false);
  const SynthesisResult edited = tiled(kEastShift, true, before.record);

  ASSERT_EQ(full.terrain.size(), edited.terrain.size());
  EXPECT_EQ(differingCells(full.patches, edited.patches), 0u);
  EXPECT_EQ(differingCells(full.terrain, edited.terrain), 0u);
  EXPECT_EQ(full.patchId, edited.patchId);
  EXPECT_EQ(full.seam, edited.seam);
  EXPECT_EQ(full.placements.size(), edited.placements.size());
  // The edit moved the east ridge; the west third of the terrain lies past its
  // reach. Tiles are taken over there and placed again near the ridge.
  const std::size_t passes = edited.tiles.size();
  EXPECT_GE(edited.tilesTakenOver, passes / 3);
  EXPECT_LT(edited.tilesTakenOver, passes);
  for (const TileTiming& t : edited.tiles)
  {
    if (t.column >= 4) // the ridge lies in tile columns 4 and 5 (x 256..383) before and after
    {
      EXPECT_FALSE(t.takenOver) << "tile " << t.column << ", " << t.row;
    }
    if (t.column == 0 && !t.fill)
    {
      EXPECT_TRUE(t.takenOver) << "tile " << t.column << ", " << t.row;
    }
  }
  // The sketch unchanged: every tile is taken over, the same bits.
  const SynthesisResult again = tiled(kEastShift, false, edited.record);
  EXPECT_EQ(again.tilesTakenOver, again.tiles.size());
  EXPECT_EQ(differingCells(full.terrain, again.terrain), 0u);
}

TEST(TileRecord, SurvivesItsBytesAndRefusesDamage)
{
  const SynthesisResult r = tiled(0, true);
  const std::string bytes = writeRecord(*r.record);
  const PlacementRecord back = readRecord(bytes, "memory");
  for (std::size_t pass = 0; pass < kTilePasses; ++pass)
  {
    ASSERT_EQ(back.tiles[pass].size(), r.record->tiles[pass].size());
    for (std::size_t k = 0; k < back.tiles[pass].size(); ++k)
    {
      EXPECT_EQ(back.tiles[pass][k].inputs, r.record->tiles[pass][k].inputs);
      EXPECT_EQ(back.tiles[pass][k].outcome, r.record->tiles[pass][k].outcome);
    }
  }
  // A tile's outcome packed keeps every kept cell's values, and only those.
  TileOutcome tile;
  tile.tile = 5;
  tile.kept = { 1, 0, 1, 1 };
  tile.heights = { 1.5f, 2.5f, -3.0f, 4.0f };
  tile.patchId = { 0, 1, -1, 2 };
  tile.seam = { 1, 1, 0, 0 };
  tile.matchCost = { 0.5f, 0.25f, std::nanf(""), 2.0f };
  tile.placements.resize(2);
  tile.placements[1].x0 = 17;
  tile.anchoredMerges = 3;
  const TileOutcome unpacked = unpackOutcome(packOutcome(tile));
  EXPECT_EQ(unpacked.tile, 5u);
  EXPECT_EQ(unpacked.kept, tile.kept);
  EXPECT_EQ(unpacked.heights[0], 1.5f);
  EXPECT_TRUE(std::isnan(unpacked.heights[1]));
  EXPECT_EQ(unpacked.heights[3], 4.0f);
  EXPECT_EQ(unpacked.patchId, (std::vector<std::int32_t>{ 0, -1, -1, 2 }));
  EXPECT_EQ(unpacked.seam, (std::vector<std::uint8_t>{ 1, 0, 0, 0 }));
  EXPECT_EQ(unpacked.matchCost[3], 2.0f);
  ASSERT_EQ(unpacked.placements.size(), 2u);
  EXPECT_EQ(unpacked.placements[1].x0, 17);
  EXPECT_EQ(unpacked.anchoredMerges, 3u);
  // Re-synthesis from the record read back gives the same bits.
  const SynthesisResult again = tiled(0, false, std::make_shared<PlacementRecord>(back));
  EXPECT_EQ(again.tilesTakenOver, again.tiles.size());
  EXPECT_EQ(differingCells(r.terrain, again.terrain), 0u);

  std::string flipped = bytes;
  flipped[bytes.size() / 2] = static_cast<char>(flipped[bytes.size() / 2] ^ 0x10);
  EXPECT_THROW(readRecord(flipped, "memory"), Error);
  EXPECT_THROW(readRecord(bytes.substr(0, bytes.size() - 9), "memory"), Error);
  EXPECT_THROW(readRecord("not a record", "memory"), Error);
}

TEST(TileRecord, RefusesARecordOfAnotherRun)
{
  const SynthesisResult r = tiled(0, true);
  try
  {
    tiled(0, false, r.record, 7);
    FAIL() << "a record of seed 0 served seed 7";
  }
  catch (const Error& e)
  {
    EXPECT_NE(std::string(e.what()).find("seed 0"), std::string::npos) << e.what();
  }
  PlacementRecord other = *r.record;
  other.width += 1;
  EXPECT_THROW(tiled(0, false, std::make_shared<PlacementRecord>(other)), Error);
  other = *r.record;
  other.exemplars ^= 1;
  EXPECT_THROW(tiled(0, false, std::make_shared<PlacementRecord>(other)), Error);
  // Untiled, a record has nothing to serve.
  const SynthesisSetup& setup = setupOf(0);
  SynthesisOptions o;
  o.patchSize = kPatch;
  o.backend = Backend::Cpu;
  o.pool = setup.pool;
  o.previous = r.record;
  EXPECT_THROW(synthesise(setup.target, setup.exemplarPointers(), setup.graphPointers(), o), Error);
}

TEST(TileRecord, KeysEverythingATilesPlacementReads)
{
  SynthesisTile tile;
  tile.regionWidth = 48;
  tile.regionHeight = 40;
  tile.index = 3;
  SynthesisTarget part;
  part.field = Heightfield(tile.regionWidth, tile.regionHeight, 100.0f);
  part.weight.assign(part.field.size(), 0.5f);
  part.halfWidth.assign(part.field.size(), 8.0f);
  part.downstream.assign(part.field.size(), std::nanf(""));
  FeatureChain ridge;
  ridge.type = FeatureType::Ridge;
  ridge.points = { { 10.0, 5.0 }, { 12.0, 35.0 } };
  part.graph.chains.push_back(ridge);
  Heightfield known(tile.regionWidth, tile.regionHeight, std::nanf(""));
  known.valid.assign(known.size(), 0);
  FeatureSite site;
  site.centre = { 11.0, 20.0 };
  site.arms.push_back({ { 11.0, 36.0 }, 1.5, 0, true });
  const std::vector<FeatureSite> sites = { site };
  const std::vector<int> labels;
  auto key = [&](const SynthesisTarget& p,
               const Heightfield& k,
               const std::vector<FeatureSite>& s,
               TilePass pass = TilePass::Features)
  { return tileInputsKey(pass, tile, p, k, s, labels, kPatch); };
  const std::uint64_t base = key(part, known, sites);
  EXPECT_EQ(key(part, known, sites), base);
  EXPECT_NE(key(part, known, sites, TilePass::Fill), base);

  SynthesisTarget changed = part;
  changed.field.z[100] += 0.01f;
  EXPECT_NE(key(changed, known, sites), base) << "field";
  changed = part;
  changed.weight[100] = 0.6f;
  EXPECT_NE(key(changed, known, sites), base) << "confidence";
  changed = part;
  changed.halfWidth[100] = 9.0f;
  EXPECT_NE(key(changed, known, sites), base) << "half width";
  changed = part;
  changed.graph.chains[0].points[1].x = 20.0;
  EXPECT_NE(key(changed, known, sites), base) << "lines";
  changed = part;
  changed.graph.chains[0].type = FeatureType::Valley;
  EXPECT_NE(key(changed, known, sites), base) << "a line's type";
  changed = part;
  changed.detailed = true;
  EXPECT_NE(key(changed, known, sites), base) << "a DEM's field";
  // A line off the region's grid is not read: the key stays.
  changed = part;
  FeatureChain far = ridge;
  far.points = { { -300.0, 5.0 }, { -290.0, 35.0 } };
  changed.graph.chains.push_back(far);
  EXPECT_EQ(key(changed, known, sites), base) << "a line far off the region";

  Heightfield knownToo = known;
  knownToo.z[7] = 50.0f;
  knownToo.valid[7] = 1;
  EXPECT_NE(key(part, knownToo, sites), base) << "known cells";

  std::vector<FeatureSite> moved = sites;
  moved[0].centre.y += 1.0;
  EXPECT_NE(key(part, known, moved), base) << "a site's place";
  moved = sites;
  moved[0].arms[0].angle += 0.1;
  EXPECT_NE(key(part, known, moved), base) << "an arm";
  // The sketch's numbering of nodes and chains is not read: an edit elsewhere renumbers them.
  moved = sites;
  moved[0].chain = 5;
  moved[0].arms[0].chain = 5;
  EXPECT_EQ(key(part, known, moved), base) << "chain numbers";

  SynthesisTile elsewhere = tile;
  elsewhere.index = 4;
  EXPECT_NE(tileInputsKey(TilePass::Features, elsewhere, part, known, sites, labels, kPatch), base);
  const std::vector<int> styled(part.field.size(), 1);
  EXPECT_NE(tileInputsKey(TilePass::Features, tile, part, known, sites, styled, kPatch), base);
}

TEST(TileRecord, TheMemoryEstimateCountsTheRecordsAsLargeAsTheyAre)
{
  const SynthesisResult r = tiled(0, true);
  const double actual = tileRecordBytes(*r.record);
  const double estimated = tileRecordBytes(kWidth, kHeight, kTile, kPatch);
  EXPECT_GT(estimated, 0.9 * actual);
  EXPECT_LT(estimated, 1.6 * actual);

  SetupInputs in;
  in.exemplars.push_back(readHeightfield(test::realDem("colorado.png")));
  in.sketch = twoRidges(0);
  in.grid.width = kWidth;
  in.grid.height = kHeight;
  in.patchSize = kPatch;
  in.matcherBackend = Backend::Cpu;
  const double without = prepareSynthesis(in).memoryEstimate;
  in.recordedTileSize = kTile;
  in.previousRecordBytes = actual;
  EXPECT_DOUBLE_EQ(prepareSynthesis(in).memoryEstimate, without + estimated + actual);
}
