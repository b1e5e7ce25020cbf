#include "StrokeSpacing.h"

#include "../Core/Error.h"
#include "../Core/Grid.h"
#include "../Distance/DistanceField.h"
#include "FeatureGraph.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

namespace tsynth
{
namespace
{

constexpr float kInfinity = std::numeric_limits<float>::infinity();
// Two neighbouring cells whose nearest stroke points are farther apart than
// this many times their distance to them look at strokes across from each
// other: the points are seen more than about 80 degrees apart. Parallel
// strokes, a ring from its centre and the turns of a spiral give 2; a line's
// own cells, a gentle bend and the outside of any corner well under 1; the
// inside of a right-angle corner (the T's, a blocky S's) 1.41, so a bend of one
// stroke is not taken for two strokes.
constexpr double kFacingRatio = 1.5;
// ... and at least this many cells apart: on a stroke itself neighbouring cells
// have neighbouring nearest points.
constexpr double kMinFacingCells = 3.0;

class MetricGrid
{
public:
  MetricGrid(int w, int h, double cx, double cy)
    : w_(w)
    , h_(h)
    , cx_(cx)
    , cy_(cy)
  {
  }
  std::size_t index(int i, int j) const { return rowMajor(i, j, w_); }
  int column(std::size_t k) const { return cellOf(k, w_).i; }
  int row(std::size_t k) const { return cellOf(k, w_).j; }
  bool inside(int i, int j) const { return i >= 0 && j >= 0 && i < w_ && j < h_; }
  double metres(std::size_t a, std::size_t b) const
  {
    return std::hypot((column(a) - column(b)) * cx_, (row(a) - row(b)) * cy_);
  }
  double step(int di, int dj) const { return std::hypot(di * cx_, dj * cy_); }

private:
  int w_, h_;
  double cx_, cy_;
};

// Cells between strokes that face each other (see kFacingRatio).
std::vector<std::uint8_t> medialAxis(const NearestSeeds& near,
  const MetricGrid& g,
  int w,
  int h,
  double cell)
{
  std::vector<std::uint8_t> medial(near.distance.size(), 0);
  const double minimum = kMinFacingCells * cell;
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      const std::size_t k = g.index(i, j);
      const int a = near.nearest[k];
      const int neighbours[2][2] = { { i + 1, j }, { i, j + 1 } };
      for (const auto& n : neighbours)
      {
        if (!g.inside(n[0], n[1]))
        {
          continue;
        }
        const std::size_t m = g.index(n[0], n[1]);
        const int b = near.nearest[m];
        if (a == b || a < 0 || b < 0)
        {
          continue;
        }
        const double apart = g.metres(static_cast<std::size_t>(a), static_cast<std::size_t>(b));
        // A cell more: near a corner's apex the grid's steps alone make the
        // nearest points of neighbouring cells look farther apart.
        const double reach = std::max(near.distance[k], near.distance[m]) + cell;
        if (apart > minimum && apart > kFacingRatio * reach)
        {
          // The cell nearer the middle carries it.
          medial[near.distance[k] >= near.distance[m] ? k : m] = 1;
        }
      }
    }
  }
  return medial;
}

// Metres from every cell to the nearest medial cell along 8-connected paths
// that do not cross a stroke (stroke cells are walls: they get a distance but
// pass none on; a diagonal step between two stroke cells that touch at a corner
// is blocked too). Raster sweeps, forward then backward, relax each cell from
// its four neighbours already swept until nothing changes: the shortest paths
// of the same graph as a Dijkstra search over it, the same sums, without its
// priority queue (a few sweeps; a path turning many times, round a spiral,
// takes one sweep pair per turn or so).
class MedialDistance
{
public:
  MedialDistance(const std::vector<std::uint8_t>& strokes, const MetricGrid& g, int w, int h)
    : strokes_(strokes)
    , g_(g)
    , w_(w)
    , h_(h)
    , straight_{ g.step(1, 0), g.step(0, 1) }
    , diagonal_(g.step(1, 1))
  {
  }

  std::vector<float> from(const std::vector<std::uint8_t>& medial) const
  {
    std::vector<float> d(medial.size(), kInfinity);
    for (std::size_t k = 0; k < medial.size(); ++k)
    {
      if (medial[k] != 0 && strokes_[k] == 0)
      {
        d[k] = 0.0f;
      }
    }
    bool changed = true;
    while (changed)
    {
      changed = sweep(d, 1);
      changed = sweep(d, -1) || changed;
    }
    return d;
  }

private:
  // One raster sweep in direction `dir` (1: rows and columns ascending);
  // true when a distance fell. Each row takes the three cells of the row
  // before beside each cell, then the cell behind it in the row, in the
  // sweep's order: each cell's distance is the least of the same sums a
  // cell-by-cell sweep takes, so the sweeps and their result are the same.
  bool sweep(std::vector<float>& d, int dir) const
  {
    bool changed = false;
    for (int r = 0; r < h_; ++r)
    {
      const int j = dir > 0 ? r : h_ - 1 - r;
      if (r > 0)
      {
        changed = fromRowBefore(d, j, j - dir) || changed;
      }
      changed = alongRow(d, j, dir) || changed;
    }
    return changed;
  }

  // Relaxes row j from the cells of row y (the row before it in the sweep)
  // straight and diagonally across.
  bool fromRowBefore(std::vector<float>& d, int j, int y) const
  {
    float* row = d.data() + g_.index(0, j);
    const float* before = d.data() + g_.index(0, y);
    const std::uint8_t* rowStroke = strokes_.data() + g_.index(0, j);
    const std::uint8_t* beforeStroke = strokes_.data() + g_.index(0, y);
    // A step from column x of row y passes the distance on unless that cell
    // is a stroke, or has none yet.
    const auto passes = [&](int x) { return beforeStroke[x] == 0 && before[x] < kInfinity; };
    bool changed = false;
    for (int i = 0; i < w_; ++i)
    {
      float best = row[i];
      if (passes(i))
      {
        best = std::min(best, static_cast<float>(before[i] + straight_[1]));
      }
      for (const int x : { i - 1, i + 1 })
      {
        // Not between two stroke cells touching at a corner.
        if (x >= 0 && x < w_ && passes(x) && !(rowStroke[x] != 0 && beforeStroke[i] != 0))
        {
          best = std::min(best, static_cast<float>(before[x] + diagonal_));
        }
      }
      if (best < row[i])
      {
        row[i] = best;
        changed = true;
      }
    }
    return changed;
  }

  // Relaxes row j from the cell behind each cell in the sweep's direction.
  bool alongRow(std::vector<float>& d, int j, int dir) const
  {
    float* row = d.data() + g_.index(0, j);
    const std::uint8_t* rowStroke = strokes_.data() + g_.index(0, j);
    bool changed = false;
    for (int c = 1; c < w_; ++c)
    {
      const int i = dir > 0 ? c : w_ - 1 - c;
      const int x = i - dir;
      if (rowStroke[x] != 0 || !(row[x] < kInfinity))
      {
        continue;
      }
      const float next = static_cast<float>(row[x] + straight_[0]);
      if (next < row[i])
      {
        row[i] = next;
        changed = true;
      }
    }
    return changed;
  }

  const std::vector<std::uint8_t>& strokes_;
  const MetricGrid& g_;
  int w_, h_;
  double straight_[2]; // along a row, along a column
  double diagonal_;
};

} // namespace

StrokeSpacing strokeSpacing(const std::vector<std::uint8_t>& strokes,
  int width,
  int height,
  double cellX,
  double cellY)
{
  StrokeSpacing s;
  s.width = width;
  s.height = height;
  const std::size_t n = cellCount(width, height);
  s.halfSpacing.assign(n, kInfinity);
  s.medial.assign(n, 0);
  const NearestSeeds near = nearestSeeds(strokes, width, height, cellX, cellY);
  s.toStroke = near.distance;
  if (near.empty())
  {
    return s;
  }
  const MetricGrid g(width, height, cellX, cellY);
  s.medial = medialAxis(near, g, width, height, std::min(cellX, cellY));
  const std::vector<float> toMedial = MedialDistance(strokes, g, width, height).from(s.medial);
  for (std::size_t k = 0; k < n; ++k)
  {
    s.halfSpacing[k] = strokes[k] != 0 ? toMedial[k] : s.toStroke[k] + toMedial[k];
  }
  return s;
}

float strokeHalfSpacing(const StrokeSpacing& s, int i, int j)
{
  float best = kInfinity;
  for (int dj = -1; dj <= 1; ++dj)
  {
    for (int di = -1; di <= 1; ++di)
    {
      const int x = i + di;
      const int y = j + dj;
      if (x >= 0 && y >= 0 && x < s.width && y < s.height)
      {
        best = std::min(best, s.halfSpacing[rowMajor(x, y, s.width)]);
      }
    }
  }
  return best;
}

namespace
{

double chainMetres(const FeatureChain& c, double cellX, double cellY)
{
  double length = 0.0;
  for (std::size_t k = 1; k < c.points.size(); ++k)
  {
    length += std::hypot(
      (c.points[k].x - c.points[k - 1].x) * cellX, (c.points[k].y - c.points[k - 1].y) * cellY);
  }
  return length;
}

} // namespace

std::vector<float> nearestStrokeLength(const FeatureGraph& lines, double cellX, double cellY)
{
  const int w = lines.width;
  const int h = lines.height;
  std::size_t setCount = 0;
  const std::vector<std::size_t> setOf = connectedChainSets(lines, &setCount);
  std::vector<double> setLength(setCount, 0.0);
  for (std::size_t c = 0; c < lines.chains.size(); ++c)
  {
    setLength[setOf[c]] += chainMetres(lines.chains[c], cellX, cellY);
  }
  std::vector<std::uint8_t> seeds(cellCount(w, h), 0);
  std::vector<float> lengthAt(seeds.size(), 0.0f);
  for (std::size_t c = 0; c < lines.chains.size(); ++c)
  {
    const float length = static_cast<float>(setLength[setOf[c]]);
    forEachChainCell(lines.chains[c],
      w,
      h,
      [&](int i, int j, std::size_t, double)
      {
        const std::size_t k = rowMajor(i, j, w);
        seeds[k] = 1;
        lengthAt[k] = std::max(lengthAt[k], length); // where two sets cross, the longer
      });
  }
  const NearestSeeds nearest = nearestSeeds(seeds, w, h, cellX, cellY);
  std::vector<float> out(seeds.size(), kInfinity);
  if (nearest.empty())
  {
    return out;
  }
  for (std::size_t k = 0; k < out.size(); ++k)
  {
    out[k] = lengthAt[static_cast<std::size_t>(nearest.nearest[k])];
  }
  return out;
}

void limitByStrokeLength(StrokeSpacing& s, const FeatureGraph& lines, double cellX, double cellY)
{
  if (lines.width != s.width || lines.height != s.height)
  {
    throw Error("The strokes' spacing and their lines are on different grids.");
  }
  limitByStrokeLength(s, nearestStrokeLength(lines, cellX, cellY));
}

void limitByStrokeLength(StrokeSpacing& s, const std::vector<float>& nearestLength)
{
  if (nearestLength.size() != s.halfSpacing.size())
  {
    throw Error("The strokes' spacing and their lengths are on different grids.");
  }
  for (std::size_t k = 0; k < nearestLength.size(); ++k)
  {
    s.halfSpacing[k] =
      std::min(s.halfSpacing[k], static_cast<float>(nearestLength[k] / kStrokeLengthPerHalfWidth));
  }
}

} // namespace tsynth
