// Tiled synthesis (SynthesisOptions::tileSize): the output cut into square
// tiles in a fixed grid from its south-west corner. Each tile is synthesised on
// its own with a halo of one patch round it, the cells that tiles done before
// it wrote held as known, so its patches meet them through the usual graph-cut
// seams. The tiles run in four colour classes of a 2 x 2 pattern (class 0: even
// column, even row; 1: odd column, even row; 2: even column, odd row; 3: odd,
// odd), each class row by row: no two tiles of a class are neighbours, and a
// tile at least two patches wide keeps their halos apart, so a class's tiles
// could run at once in any order and give the same cells. The order, the seeds
// (derived from the tile's place) and so every cell depend only on the tile
// grid, never on how many processes share the work.
#pragma once

#include "Synthesiser.h"
#include "Target.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace tsynth
{

// The halo synthesised round a tile, in patches: a patch reaching across the
// tile's edge still lies wholly in its region.
constexpr int kTileHaloInPatches = 1;
// Tiles of a class are kept apart by one tile, so their halos (one patch each
// side) never meet if a tile is at least this many patches wide.
constexpr int kSmallestTileInPatches = 2 * kTileHaloInPatches;
// The 2 x 2 colour pattern: four classes.
constexpr int kTileColourSide = 2;

struct SynthesisTile
{
  int column = 0; // in the tile grid, from the south-west
  int row = 0;
  int colour = 0; // its class, 0..3
  // The cells it owns: columns x0..x0 + width - 1, rows y0..y0 + height - 1.
  int x0 = 0, y0 = 0, width = 0, height = 0;
  // The cells it synthesises: its own and the halo round them, within the output.
  int regionX0 = 0, regionY0 = 0, regionWidth = 0, regionHeight = 0;
  std::size_t index = 0; // row-major in the grid, from the south-west
};

// Throws tsynth::Error (one sentence with the smallest size that works) unless
// tiles of `tileSize` cells suit patches of `patchSize`.
void checkTileSize(int tileSize, int patchSize);

// The tiles of a width x height output in the order they are synthesised:
// colour class by colour class, each row by row from the south-west.
std::vector<SynthesisTile> tileSchedule(int width, int height, int tileSize, int patchSize);

// A tile's fill keeps its region less this share of a patch along the region's
// edges inside the output: a later tile, whose region holds those cells and
// both sides of them, fills them.
constexpr double kTileBorderInPatches = 0.5;

// Over the tile's region, 1 on its inner border (kTileBorderInPatches wide
// along the edges that lie inside the width x height output), never on the
// tile's own cells.
std::vector<std::uint8_t> innerBorder(const SynthesisTile& tile,
  int width,
  int height,
  int patchSize);

// What one tile's placement made of its region, which the whole output takes
// over: the cells it keeps, the placements that wrote them (numbered and
// placed within the tile's region), and how many merges were anchored.
struct TileOutcome
{
  std::size_t tile = 0;              // its place in tileSchedule()
  std::vector<std::uint8_t> kept;    // per region cell: 1 where taken over
  std::vector<float> heights;        // per region cell
  std::vector<std::int32_t> patchId; // the tile's own placement number (-1: none)
  std::vector<std::uint8_t> seam;
  std::vector<float> matchCost;
  std::vector<Placement> placements;
  std::uint64_t anchoredMerges = 0;
};

// Outcomes as bytes and back, for processes that share a tiled synthesis (all
// of one build: the bytes are the values' own). readOutcomes throws
// tsynth::Error if the bytes are cut short.
std::string writeOutcomes(const std::vector<TileOutcome>& outcomes);
std::vector<TileOutcome> readOutcomes(const std::string& bytes);

// The part of a target a tile synthesises: its cells in the region, and the
// feature graph moved into the region's frame (lines outside it are kept, off
// the grid, so that what lies near the edge is seen whole).
SynthesisTarget regionTarget(const SynthesisTarget& target, const SynthesisTile& tile);

// The graph moved by (-dx, -dy) cells onto a width x height grid.
FeatureGraph shiftedGraph(const FeatureGraph& graph, double dx, double dy, int width, int height);

} // namespace tsynth
