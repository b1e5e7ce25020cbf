#include "Tiling.h"

#include "../Core/Error.h"
#include "../Core/Grid.h"

#include <algorithm>
#include <string>

namespace tsynth
{

namespace
{

// The region's part of a per-cell array over the whole output (empty stays empty).
template<class T>
std::vector<T> regionCells(const std::vector<T>& all, int width, const SynthesisTile& t)
{
  if (all.empty())
  {
    return {};
  }
  std::vector<T> part;
  part.reserve(cellCount(t.regionWidth, t.regionHeight));
  for (int j = 0; j < t.regionHeight; ++j)
  {
    const auto row =
      all.begin() + static_cast<std::ptrdiff_t>(rowMajor(t.regionX0, t.regionY0 + j, width));
    part.insert(part.end(), row, row + t.regionWidth);
  }
  return part;
}

Point2 moved(Point2 p, double dx, double dy)
{
  return { p.x - dx, p.y - dy };
}

} // namespace

void checkTileSize(int tileSize, int patchSize)
{
  const int smallest = kSmallestTileInPatches * patchSize;
  if (tileSize < smallest)
  {
    throw Error("Tiles of " + std::to_string(tileSize) + " cells are too small for patches of " +
      std::to_string(patchSize) + ": a tile must be at least two patches wide (" +
      std::to_string(smallest) +
      " cells) so that the halos of tiles synthesised together stay apart.");
  }
}

std::vector<SynthesisTile> tileSchedule(int width, int height, int tileSize, int patchSize)
{
  checkTileSize(tileSize, patchSize);
  const int columns = (width + tileSize - 1) / tileSize;
  const int rows = (height + tileSize - 1) / tileSize;
  const int halo = kTileHaloInPatches * patchSize;
  std::vector<SynthesisTile> tiles;
  for (int colour = 0; colour < kTileColourSide * kTileColourSide; ++colour)
  {
    for (int r = colour / kTileColourSide; r < rows; r += kTileColourSide)
    {
      for (int c = colour % kTileColourSide; c < columns; c += kTileColourSide)
      {
        SynthesisTile t;
        t.column = c;
        t.row = r;
        t.colour = colour;
        t.index = rowMajor(c, r, columns);
        t.x0 = c * tileSize;
        t.y0 = r * tileSize;
        t.width = std::min(tileSize, width - t.x0);
        t.height = std::min(tileSize, height - t.y0);
        // The halo, within the output; a region never narrower than a patch
        // (a thin last tile reaches back into its neighbour instead).
        t.regionX0 = std::max(0, std::min(t.x0 - halo, width - patchSize));
        t.regionY0 = std::max(0, std::min(t.y0 - halo, height - patchSize));
        t.regionWidth = std::min(width, t.x0 + t.width + halo) - t.regionX0;
        t.regionHeight = std::min(height, t.y0 + t.height + halo) - t.regionY0;
        tiles.push_back(t);
      }
    }
  }
  return tiles;
}

std::vector<std::uint8_t> innerBorder(const SynthesisTile& t, int width, int height, int patchSize)
{
  const int m = static_cast<int>(kTileBorderInPatches * patchSize);
  const bool west = t.regionX0 > 0;
  const bool south = t.regionY0 > 0;
  const bool east = t.regionX0 + t.regionWidth < width;
  const bool north = t.regionY0 + t.regionHeight < height;
  std::vector<std::uint8_t> border(cellCount(t.regionWidth, t.regionHeight), 0);
  for (int j = 0; j < t.regionHeight; ++j)
  {
    for (int i = 0; i < t.regionWidth; ++i)
    {
      const int x = t.regionX0 + i;
      const int y = t.regionY0 + j;
      const bool own = x >= t.x0 && x < t.x0 + t.width && y >= t.y0 && y < t.y0 + t.height;
      const bool edge = (west && i < m) || (east && i >= t.regionWidth - m) || (south && j < m) ||
        (north && j >= t.regionHeight - m);
      border[rowMajor(i, j, t.regionWidth)] = edge && !own ? 1 : 0;
    }
  }
  return border;
}

FeatureGraph shiftedGraph(const FeatureGraph& graph, double dx, double dy, int width, int height)
{
  FeatureGraph g = graph;
  g.width = width;
  g.height = height;
  for (FeatureNode& n : g.nodes)
  {
    n.position = moved(n.position, dx, dy);
    for (ControlPoint& p : n.controls)
    {
      p.position = moved(p.position, dx, dy);
    }
  }
  for (FeatureChain& c : g.chains)
  {
    for (Point2& p : c.points)
    {
      p = moved(p, dx, dy);
    }
  }
  return g;
}

SynthesisTarget regionTarget(const SynthesisTarget& target, const SynthesisTile& tile)
{
  const int width = target.field.width;
  SynthesisTarget part;
  Heightfield& f = part.field;
  f.width = tile.regionWidth;
  f.height = tile.regionHeight;
  f.cellX = target.field.cellX;
  f.cellY = target.field.cellY;
  f.cellSizeKnown = target.field.cellSizeKnown;
  f.z = regionCells(target.field.z, width, tile);
  f.valid = regionCells(target.field.valid, width, tile);
  part.graph =
    shiftedGraph(target.graph, tile.regionX0, tile.regionY0, tile.regionWidth, tile.regionHeight);
  part.lineHalfSpacing = target.lineHalfSpacing;
  part.weight = regionCells(target.weight, width, tile);
  part.halfWidth = regionCells(target.halfWidth, width, tile);
  part.ridgeRaise = target.ridgeRaise;
  part.valleyRaise = target.valleyRaise;
  part.downstream = regionCells(target.downstream, width, tile);
  part.detailed = target.detailed;
  return part;
}

} // namespace tsynth

namespace tsynth
{

namespace
{

template<class T>
void put(std::string& out, const std::vector<T>& values)
{
  const std::uint64_t n = values.size();
  out.append(reinterpret_cast<const char*>(&n), sizeof n);
  out.append(reinterpret_cast<const char*>(values.data()), n * sizeof(T));
}

void put(std::string& out, std::uint64_t value)
{
  out.append(reinterpret_cast<const char*>(&value), sizeof value);
}

class Reader
{
public:
  explicit Reader(const std::string& bytes)
    : bytes_(bytes)
  {
  }

  std::uint64_t number()
  {
    std::uint64_t v = 0;
    take(&v, sizeof v);
    return v;
  }

  template<class T>
  std::vector<T> values()
  {
    const std::uint64_t n = number();
    if (n > (bytes_.size() - at_) / sizeof(T))
    {
      throw Error("A shared tile's data is cut short: the processes of this synthesis disagree.");
    }
    std::vector<T> v(n);
    take(v.data(), n * sizeof(T));
    return v;
  }

private:
  void take(void* to, std::size_t n)
  {
    if (n > bytes_.size() - at_)
    {
      throw Error("A shared tile's data is cut short: the processes of this synthesis disagree.");
    }
    std::copy_n(bytes_.data() + at_, n, static_cast<char*>(to));
    at_ += n;
  }

  const std::string& bytes_;
  std::size_t at_ = 0;
};

} // namespace

std::string writeOutcomes(const std::vector<TileOutcome>& outcomes)
{
  std::string out;
  put(out, static_cast<std::uint64_t>(outcomes.size()));
  for (const TileOutcome& o : outcomes)
  {
    put(out, static_cast<std::uint64_t>(o.tile));
    put(out, o.kept);
    put(out, o.heights);
    put(out, o.patchId);
    put(out, o.seam);
    put(out, o.matchCost);
    put(out, o.placements);
    put(out, o.anchoredMerges);
  }
  return out;
}

std::vector<TileOutcome> readOutcomes(const std::string& bytes)
{
  Reader in(bytes);
  const std::uint64_t count = in.number();
  if (count > bytes.size())
  {
    throw Error("A shared tile's data is damaged: the processes of this synthesis disagree.");
  }
  std::vector<TileOutcome> outcomes(count);
  for (TileOutcome& o : outcomes)
  {
    o.tile = in.number();
    o.kept = in.values<std::uint8_t>();
    o.heights = in.values<float>();
    o.patchId = in.values<std::int32_t>();
    o.seam = in.values<std::uint8_t>();
    o.matchCost = in.values<float>();
    o.placements = in.values<Placement>();
    o.anchoredMerges = in.number();
  }
  return outcomes;
}

} // namespace tsynth
