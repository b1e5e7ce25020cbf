// Tests of Kernels/Synthesis/Tiling.cxx.
// Tiled synthesis (Synthesis/Tiling.h): the schedule keeps the tiles of a
// colour class apart, every cell belongs to one tile, and a tiled synthesis
// of a real exemplar is deterministic, fills every cell, and leaves no
// straight step along the tiles' edges.
#include "Core/Error.h"
#include "Core/HeightfieldIO.h"
#include "Synthesis/Setup.h"
#include "Synthesis/Synthesiser.h"
#include "Synthesis/Tiling.h"
#include "TestData.h"
#include "YOverColorado.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <condition_variable>
#include <mutex>
#include <numeric>
#include <set>
#include <thread>
#include <tuple>

using namespace tsynth;

namespace
{

bool overlap(const SynthesisTile& a, const SynthesisTile& b)
{
  return a.regionX0 < b.regionX0 + b.regionWidth && b.regionX0 < a.regionX0 + a.regionWidth &&
    a.regionY0 < b.regionY0 + b.regionHeight && b.regionY0 < a.regionY0 + a.regionHeight;
}

// That terrain in tiles of `tile` cells (0: one piece).
SynthesisResult yOverColorado(int tile)
{
  const SynthesisSetup& setup = test::yOverColoradoSetup();
  SynthesisOptions o;
  o.patchSize = test::kYPatch;
  o.backend = Backend::Cpu;
  o.pool = setup.pool;
  o.tileSize = tile;
  return synthesise(setup, o);
}

// Stands in for ParaView's MPI ranks: `ranks` threads, each running the same
// tiled synthesis with its share of the tiles, gathering through memory.
class Ranks
{
public:
  explicit Ranks(int ranks)
    : slots_(static_cast<std::size_t>(ranks))
  {
  }

  std::vector<std::string> allGather(int rank, const std::string& mine)
  {
    std::unique_lock<std::mutex> lock(mutex_);
    const std::size_t round = round_;
    slots_[static_cast<std::size_t>(rank)] = mine;
    if (++arrived_ == slots_.size())
    {
      gathered_ = slots_;
      arrived_ = 0;
      ++round_;
      ready_.notify_all();
    }
    else
    {
      ready_.wait(lock, [&] { return round_ != round; });
    }
    return gathered_;
  }

private:
  std::mutex mutex_;
  std::condition_variable ready_;
  std::vector<std::string> slots_, gathered_;
  std::size_t arrived_ = 0;
  std::size_t round_ = 0;
};

// yOverColorado(tile) shared among `ranks` processes: every rank's terrain
// (or, where a rank failed, its sentence in `failures`). `failingRank`'s
// progress reports throw once its fill begins.
std::vector<SynthesisResult> yOverColoradoOnRanks(int tile,
  int ranks,
  int failingRank = -1,
  std::vector<std::string>* failures = nullptr)
{
  const SynthesisSetup& setup = test::yOverColoradoSetup();
  Ranks world(ranks);
  std::vector<SynthesisResult> results(static_cast<std::size_t>(ranks));
  std::vector<std::thread> threads;
  for (int r = 0; r < ranks; ++r)
  {
    threads.emplace_back(
      [&, r]
      {
        SynthesisOptions o;
        o.patchSize = test::kYPatch;
        o.backend = Backend::Cpu;
        o.pool = setup.pool;
        o.tileSize = tile;
        o.sharing.rank = r;
        o.sharing.ranks = ranks;
        o.sharing.allGather = [&world, r](const std::string& mine)
        { return world.allGather(r, mine); };
        if (r == failingRank)
        {
          o.progress = [](double, const std::string& stage)
          {
            if (stage == "fill")
            {
              throw Error("the disk is on fire.");
            }
          };
        }
        try
        {
          results[static_cast<std::size_t>(r)] = synthesise(setup, o);
        }
        catch (const Error& e)
        {
          (*failures)[static_cast<std::size_t>(r)] = e.what();
        }
      });
  }
  for (std::thread& t : threads)
  {
    t.join();
  }
  return results;
}

// The largest ratio, over the columns (or rows) of `hf`, of the mean height
// step across a line to the median of the 8 lines beside it: a straight seam
// or step along a tile's edge stands out as a line steeper than its neighbours.
double steepestLineRatio(const Heightfield& hf, bool columns)
{
  const int lines = (columns ? hf.width : hf.height) - 1;
  const int along = columns ? hf.height : hf.width;
  std::vector<double> step(static_cast<std::size_t>(lines), 0.0);
  for (int l = 0; l < lines; ++l)
  {
    for (int k = 0; k < along; ++k)
    {
      step[static_cast<std::size_t>(l)] +=
        columns ? std::abs(hf.at(l + 1, k) - hf.at(l, k)) : std::abs(hf.at(k, l + 1) - hf.at(k, l));
    }
  }
  double worst = 0.0;
  for (int l = 4; l < lines - 4; ++l)
  {
    std::vector<double> beside;
    for (int d = -4; d <= 4; ++d)
    {
      if (d != 0)
      {
        beside.push_back(step[static_cast<std::size_t>(l + d)]);
      }
    }
    std::nth_element(beside.begin(), beside.begin() + 4, beside.end());
    worst = std::max(worst, step[static_cast<std::size_t>(l)] / beside[4]);
  }
  return worst;
}

} // namespace

TEST(Tiling, TilesOfAColourClassNeverShareACellOfTheirRegions)
{
  const int width = 1000;
  const int height = 700;
  const std::vector<SynthesisTile> tiles = tileSchedule(width, height, 160, 80);
  ASSERT_EQ(tiles.size(), 7u * 5u);
  std::vector<int> owners(static_cast<std::size_t>(width) * height, 0);
  for (std::size_t a = 0; a < tiles.size(); ++a)
  {
    const SynthesisTile& t = tiles[a];
    if (a > 0)
    {
      EXPECT_GE(t.colour, tiles[a - 1].colour) << "the classes run in order";
    }
    EXPECT_EQ(t.colour, (t.column % 2) + 2 * (t.row % 2));
    for (std::size_t b = a + 1; b < tiles.size(); ++b)
    {
      if (tiles[b].colour == t.colour)
      {
        EXPECT_FALSE(overlap(t, tiles[b]))
          << "tiles " << t.column << "," << t.row << " and " << tiles[b].column << ","
          << tiles[b].row << " of one class share cells";
      }
    }
    for (int y = t.y0; y < t.y0 + t.height; ++y)
    {
      for (int x = t.x0; x < t.x0 + t.width; ++x)
      {
        ++owners[static_cast<std::size_t>(y) * width + x];
      }
    }
    // The region is the tile and a patch round it, within the output.
    EXPECT_EQ(t.regionX0, std::max(0, t.x0 - 80));
    EXPECT_EQ(t.regionX0 + t.regionWidth, std::min(width, t.x0 + t.width + 80));
  }
  EXPECT_TRUE(std::all_of(owners.begin(), owners.end(), [](int n) { return n == 1; }))
    << "every cell belongs to exactly one tile";
}

TEST(Tiling, TheInnerBorderLiesOutsideTheTileAndOnlyInsideTheOutput)
{
  const std::vector<SynthesisTile> tiles = tileSchedule(500, 500, 200, 80);
  for (const SynthesisTile& t : tiles)
  {
    const std::vector<std::uint8_t> border = innerBorder(t, 500, 500, 80);
    for (int j = 0; j < t.regionHeight; ++j)
    {
      for (int i = 0; i < t.regionWidth; ++i)
      {
        const int x = t.regionX0 + i;
        const int y = t.regionY0 + j;
        const bool own = x >= t.x0 && x < t.x0 + t.width && y >= t.y0 && y < t.y0 + t.height;
        const bool onBorder =
          border[static_cast<std::size_t>(j) * static_cast<std::size_t>(t.regionWidth) +
            static_cast<std::size_t>(i)] != 0;
        ASSERT_FALSE(own && onBorder) << "a tile keeps its own cells";
        // Half a patch (40 cells) in from an edge inside the output, not on the output's edge.
        const bool expected = !own &&
          ((t.regionX0 > 0 && i < 40) ||
            (x < 499 && i >= t.regionWidth - 40 && t.regionX0 + t.regionWidth < 500) ||
            (t.regionY0 > 0 && j < 40) ||
            (t.regionY0 + t.regionHeight < 500 && j >= t.regionHeight - 40));
        ASSERT_EQ(onBorder, expected) << "cell " << x << "," << y;
      }
    }
  }
}

TEST(Tiling, ATileNarrowerThanTwoPatchesIsRefusedWithTheSmallestThatWorks)
{
  try
  {
    tileSchedule(1000, 1000, 100, 80);
    FAIL() << "tiles of 100 cells at patch 80 were accepted";
  }
  catch (const Error& e)
  {
    EXPECT_NE(
      std::string(e.what()).find("at least two patches wide (160 cells)"), std::string::npos)
      << e.what();
  }
}

TEST(TiledSynthesis, IsDeterministicFillsEveryCellAndShowsNoTileEdge)
{
  const SynthesisResult a = yOverColorado(64);
  const SynthesisResult b = yOverColorado(64);
  ASSERT_EQ(a.terrain.z.size(), 256u * 256u);
  EXPECT_EQ(a.terrain.z, b.terrain.z) << "the same tiles and seed gave other heights";
  EXPECT_EQ(a.terrain.validCount(), a.terrain.size());
  // Every cell was written by a placement, and every id names one.
  for (int id : a.patchId)
  {
    ASSERT_GE(id, 0);
    ASSERT_LT(static_cast<std::size_t>(id), a.placements.size());
  }
  for (std::size_t p = 0; p < a.placements.size(); ++p)
  {
    EXPECT_EQ(a.placements[p].order, static_cast<int>(p));
  }
  // No line, least of all along the tiles' edges (every 64 cells), is much
  // steeper than those beside it; the same measure on the untiled terrain.
  const SynthesisResult whole = yOverColorado(0);
  const double untiled =
    std::max(steepestLineRatio(whole.terrain, true), steepestLineRatio(whole.terrain, false));
  const double tiled =
    std::max(steepestLineRatio(a.terrain, true), steepestLineRatio(a.terrain, false));
  EXPECT_LT(tiled, 1.5 * untiled) << "tiled " << tiled << ", untiled " << untiled;
  // And another tile grid gives another, equally complete terrain.
  const SynthesisResult c = yOverColorado(96);
  EXPECT_NE(a.terrain.z, c.terrain.z);
  EXPECT_EQ(c.terrain.validCount(), c.terrain.size());
}

TEST(TiledSynthesis, SharedAmongRanksEveryRankHoldsTheOneProcessTerrain)
{
  const SynthesisResult one = yOverColorado(64);
  for (int ranks : { 2, 3 })
  {
    const std::vector<SynthesisResult> shared = yOverColoradoOnRanks(64, ranks);
    for (std::size_t r = 0; r < shared.size(); ++r)
    {
      EXPECT_EQ(shared[r].terrain.z, one.terrain.z) << "rank " << r << " of " << ranks;
      EXPECT_EQ(shared[r].patchId, one.patchId) << "rank " << r << " of " << ranks;
      EXPECT_EQ(shared[r].placements.size(), one.placements.size());
    }
  }
}

TEST(TiledSynthesis, TimesEveryTileOfEachPassOnTheRankThatPlacedIt)
{
  // 256^2 in tiles of 64: 4 x 4 tiles, each placed once per pass.
  constexpr std::size_t kTiles = 16;
  const SynthesisResult one = yOverColorado(64);
  ASSERT_EQ(one.tiles.size(), 2 * kTiles);
  std::set<std::tuple<int, int, bool>> seen;
  double fill = 0.0;
  for (const TileTiming& t : one.tiles)
  {
    EXPECT_TRUE(seen.insert({ t.column, t.row, t.fill }).second) << "a tile timed twice";
    EXPECT_GT(t.seconds, 0.0);
    EXPECT_GE(t.cpuSeconds, 0.0);
    fill += t.fill ? t.seconds : 0.0;
  }
  // The tiles' fill times make up the run's fill time (less the set-up of each tile).
  EXPECT_LE(fill, one.timings.fill + one.timings.setup + 1e-6);
  EXPECT_GT(fill, 0.5 * one.timings.fill);
  EXPECT_EQ(one.waitedSeconds, 0.0) << "one process waits for no other";
  // Shared by 3 ranks, each times its own share and together they time every
  // tile once. Each colour class holds 4 tiles, of which rank k mod 3 takes
  // tile k: rank 0 two, ranks 1 and 2 one, in each of 4 classes and 2 passes.
  const std::vector<SynthesisResult> shared = yOverColoradoOnRanks(64, 3);
  const std::array<std::size_t, 3> share{ 16, 8, 8 };
  std::set<std::tuple<int, int, bool>> together;
  for (std::size_t rank = 0; rank < shared.size(); ++rank)
  {
    const SynthesisResult& r = shared[rank];
    EXPECT_EQ(r.tiles.size(), share[rank]) << "rank " << rank;
    for (const TileTiming& t : r.tiles)
    {
      EXPECT_TRUE(together.insert({ t.column, t.row, t.fill }).second) << "two ranks placed a tile";
    }
  }
  EXPECT_EQ(together, seen);
}

TEST(TiledSynthesis, SharedTileDataCutShortIsRefused)
{
  TileOutcome o;
  o.tile = 3;
  o.kept = { 1, 0, 1 };
  o.heights = { 1.0f, 2.0f, 3.0f };
  o.patchId = { 0, -1, 0 };
  o.seam = { 0, 0, 1 };
  o.matchCost = { 0.5f, 0.5f, 0.5f };
  o.placements.resize(1);
  o.placements[0].x0 = 17;
  const std::string bytes = writeOutcomes({ o });
  const std::vector<TileOutcome> back = readOutcomes(bytes);
  ASSERT_EQ(back.size(), 1u);
  EXPECT_EQ(back[0].tile, 3u);
  EXPECT_EQ(back[0].heights, o.heights);
  EXPECT_EQ(back[0].placements[0].x0, 17);
  EXPECT_THROW(readOutcomes(bytes.substr(0, bytes.size() - 5)), Error);
}

TEST(TiledSynthesis, ATileThatFailsOnOneRankFailsEveryRankWithOneSentence)
{
  std::vector<std::string> failures(2);
  yOverColoradoOnRanks(64, 2, 1, &failures);
  for (const std::string& f : failures)
  {
    // Every rank stops (none waits for the failed one) and says which tile failed where.
    EXPECT_NE(f.find("(rank 1) failed: the disk is on fire."), std::string::npos) << f;
    EXPECT_EQ(f.rfind("Tile ", 0), 0u) << f;
  }
}
