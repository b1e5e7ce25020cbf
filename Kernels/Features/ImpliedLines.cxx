#include "ImpliedLines.h"

#include "../Core/Grid.h"
#include "../Distance/DistanceField.h"
#include "Sketch.h"

#include <algorithm>
#include <vector>

namespace tsynth
{
namespace
{

// A medial cell lies between two strokes of one kind when every stroke of the
// other kind is at least this much farther than they are: between a valley
// and a ridge the two distances are equal, and one slope joins them.
constexpr float kOtherKindFarther = 1.5f;

using Mask = std::vector<std::uint8_t>;

Mask linesOfType(const FeatureGraph& g, FeatureType type)
{
  FeatureGraph ofType = g;
  ofType.chains.erase(std::remove_if(ofType.chains.begin(),
                        ofType.chains.end(),
                        [&](const FeatureChain& c) { return c.type != type; }),
    ofType.chains.end());
  return rasteriseChains(ofType, g.width, g.height);
}

// The mask grown by one cell (8-neighbours): the medial axis, one cell thin
// and broken where it steps diagonally, becomes one stroke to thin again.
Mask grown(const Mask& m, int w, int h)
{
  Mask out(m.size(), 0);
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      const std::size_t k = rowMajor(i, j, w);
      if (m[k] == 0)
      {
        continue;
      }
      for (int y = std::max(0, j - 1); y <= std::min(h - 1, j + 1); ++y)
      {
        for (int x = std::max(0, i - 1); x <= std::min(w - 1, i + 1); ++x)
        {
          out[rowMajor(x, y, w)] = 1;
        }
      }
    }
  }
  return out;
}

// Keeps the 8-connected pieces of `grownMask` that hold at least `minCells`
// cells of `axis` (the medial axis is about a cell thick: cells ~ length).
Mask withoutShortPieces(const Mask& grownMask, const Mask& axis, int w, int h, double minCells)
{
  Mask out(grownMask.size(), 0);
  std::vector<std::uint8_t> seen(grownMask.size(), 0);
  std::vector<std::size_t> piece;
  for (std::size_t start = 0; start < grownMask.size(); ++start)
  {
    if (grownMask[start] == 0 || seen[start] != 0)
    {
      continue;
    }
    piece.assign(1, start);
    seen[start] = 1;
    double cells = 0.0;
    for (std::size_t n = 0; n < piece.size(); ++n)
    {
      const std::size_t k = piece[n];
      cells += axis[k] != 0 ? 1.0 : 0.0;
      const auto [i, j] = cellOf(k, w);
      for (int y = std::max(0, j - 1); y <= std::min(h - 1, j + 1); ++y)
      {
        for (int x = std::max(0, i - 1); x <= std::min(w - 1, i + 1); ++x)
        {
          const std::size_t q = rowMajor(x, y, w);
          if (grownMask[q] != 0 && seen[q] == 0)
          {
            seen[q] = 1;
            piece.push_back(q);
          }
        }
      }
    }
    if (cells >= minCells)
    {
      for (std::size_t k : piece)
      {
        out[k] = 1;
      }
    }
  }
  return out;
}

} // namespace

FeatureGraph impliedLines(const FeatureGraph& drawn,
  const StrokeSpacing& spacing,
  const ImpliedLineOptions& o)
{
  const int w = drawn.width;
  const int h = drawn.height;
  FeatureGraph implied;
  implied.width = w;
  implied.height = h;
  implied.cellX = drawn.cellX;
  implied.cellY = drawn.cellY;
  const std::size_t n = cellCount(std::max(0, w), std::max(0, h));
  if (n == 0 || drawn.chains.empty() || spacing.medial.size() != n)
  {
    return implied;
  }
  const Mask ridges = linesOfType(drawn, FeatureType::Ridge);
  const Mask valleys = linesOfType(drawn, FeatureType::Valley);
  Mask strokes(ridges.size());
  for (std::size_t k = 0; k < strokes.size(); ++k)
  {
    strokes[k] = ridges[k] | valleys[k];
  }
  const std::vector<float> toRidge = distanceTransform(ridges, w, h);
  const std::vector<float> toValley = distanceTransform(valleys, w, h);
  SketchOptions so;
  so.controlRadius = o.controlRadius;
  for (FeatureType type : { FeatureType::Ridge, FeatureType::Valley })
  {
    if (type == FeatureType::Valley && !o.troughs)
    {
      continue;
    }
    // An implied ridge parts two valleys; an implied valley two ridges.
    const std::vector<float>& toParted = type == FeatureType::Ridge ? toValley : toRidge;
    const std::vector<float>& toOther = type == FeatureType::Ridge ? toRidge : toValley;
    Mask axis(strokes.size(), 0);
    bool any = false;
    for (std::size_t k = 0; k < axis.size(); ++k)
    {
      const float d = toParted[k];
      if (spacing.medial[k] != 0 && strokes[k] == 0 && d >= o.minDistance && d <= o.maxDistance &&
        toOther[k] >= kOtherKindFarther * d)
      {
        axis[k] = 1;
        any = true;
      }
    }
    if (!any)
    {
      continue;
    }
    Mask lines = withoutShortPieces(grown(axis, w, h), axis, w, h, o.minLength);
    if (std::find(lines.begin(), lines.end(), 1) == lines.end())
    {
      continue;
    }
    FeatureGraph g = centreLines(std::move(lines), w, h, type, so);
    g.cellX = drawn.cellX;
    g.cellY = drawn.cellY;
    appendGraph(implied, g);
  }
  computeControlPoints(implied, o.controlRadius);
  return implied;
}

} // namespace tsynth
