#include "Target.h"

#include "../Core/Error.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tsynth
{
namespace
{

double percentile(std::vector<float> v, double p)
{
  if (v.empty())
  {
    return 0.0;
  }
  const std::size_t k =
    std::min(v.size() - 1, static_cast<std::size_t>(p * static_cast<double>(v.size() - 1)));
  std::nth_element(v.begin(), v.begin() + static_cast<long>(k), v.end());
  return v[k];
}

// One dimension of the squared distance transform (lower envelope of parabolas).
void transform1d(const std::vector<float>& f, std::vector<float>& d, int n)
{
  std::vector<int> v(static_cast<std::size_t>(n));
  std::vector<float> z(static_cast<std::size_t>(n + 1));
  const float inf = std::numeric_limits<float>::infinity();
  int k = -1;
  for (int q = 0; q < n; ++q)
  {
    if (!(f[static_cast<std::size_t>(q)] < inf))
    {
      continue;
    }
    while (k >= 0)
    {
      const int p = v[static_cast<std::size_t>(k)];
      const float s = ((f[static_cast<std::size_t>(q)] + static_cast<float>(q) * q) -
                        (f[static_cast<std::size_t>(p)] + static_cast<float>(p) * p)) /
        (2.0f * static_cast<float>(q - p));
      if (s <= z[static_cast<std::size_t>(k)])
      {
        --k;
      }
      else
      {
        break;
      }
    }
    ++k;
    v[static_cast<std::size_t>(k)] = q;
    z[static_cast<std::size_t>(k)] = k == 0
      ? -inf
      : ((f[static_cast<std::size_t>(q)] + static_cast<float>(q) * q) -
          (f[static_cast<std::size_t>(v[static_cast<std::size_t>(k - 1)])] +
            static_cast<float>(v[static_cast<std::size_t>(k - 1)]) *
              v[static_cast<std::size_t>(k - 1)])) /
        (2.0f * static_cast<float>(q - v[static_cast<std::size_t>(k - 1)]));
    z[static_cast<std::size_t>(k + 1)] = inf;
  }
  if (k < 0)
  {
    std::fill(d.begin(), d.begin() + n, inf);
    return;
  }
  int j = 0;
  for (int q = 0; q < n; ++q)
  {
    while (z[static_cast<std::size_t>(j + 1)] < static_cast<float>(q))
    {
      ++j;
    }
    const int p = v[static_cast<std::size_t>(j)];
    d[static_cast<std::size_t>(q)] =
      static_cast<float>(q - p) * (q - p) + f[static_cast<std::size_t>(p)];
  }
}

// Cells of the chains of one type (or all), drawn between consecutive points.
std::vector<std::uint8_t> rasterise(const FeatureGraph& g, const FeatureType* type, int w, int h)
{
  std::vector<std::uint8_t> seeds(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), 0);
  for (const FeatureChain& c : g.chains)
  {
    if (type != nullptr && c.type != *type)
    {
      continue;
    }
    for (std::size_t k = 1; k < c.points.size(); ++k)
    {
      const Point2& a = c.points[k - 1];
      const Point2& b = c.points[k];
      const int steps =
        std::max(1, static_cast<int>(std::ceil(2.0 * std::hypot(b.x - a.x, b.y - a.y))));
      for (int s = 0; s <= steps; ++s)
      {
        const double t = static_cast<double>(s) / steps;
        const int i = static_cast<int>(std::lround(a.x + t * (b.x - a.x)));
        const int j = static_cast<int>(std::lround(a.y + t * (b.y - a.y)));
        if (i >= 0 && j >= 0 && i < w && j < h)
        {
          seeds[static_cast<std::size_t>(j) * static_cast<std::size_t>(w) +
            static_cast<std::size_t>(i)] = 1;
        }
      }
    }
  }
  return seeds;
}

} // namespace

std::vector<std::uint8_t> rasteriseChains(const FeatureGraph& graph, int width, int height)
{
  return rasterise(graph, nullptr, width, height);
}

std::vector<float> distanceTransform(const std::vector<std::uint8_t>& seeds, int w, int h)
{
  const float inf = std::numeric_limits<float>::infinity();
  std::vector<float> d(seeds.size(), inf);
  std::vector<float> f(static_cast<std::size_t>(std::max(w, h)));
  std::vector<float> out(static_cast<std::size_t>(std::max(w, h)));
  for (int i = 0; i < w; ++i)
  {
    for (int j = 0; j < h; ++j)
    {
      f[static_cast<std::size_t>(j)] =
        seeds[static_cast<std::size_t>(j) * static_cast<std::size_t>(w) +
          static_cast<std::size_t>(i)] != 0
        ? 0.0f
        : inf;
    }
    transform1d(f, out, h);
    for (int j = 0; j < h; ++j)
    {
      d[static_cast<std::size_t>(j) * static_cast<std::size_t>(w) + static_cast<std::size_t>(i)] =
        out[static_cast<std::size_t>(j)];
    }
  }
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      f[static_cast<std::size_t>(i)] =
        d[static_cast<std::size_t>(j) * static_cast<std::size_t>(w) + static_cast<std::size_t>(i)];
    }
    transform1d(f, out, w);
    for (int i = 0; i < w; ++i)
    {
      d[static_cast<std::size_t>(j) * static_cast<std::size_t>(w) + static_cast<std::size_t>(i)] =
        std::sqrt(out[static_cast<std::size_t>(i)]);
    }
  }
  return d;
}

ExemplarStatistics exemplarStatistics(const std::vector<const Heightfield*>& exemplars,
  const std::vector<const FeatureGraph*>& graphs)
{
  std::vector<float> all;
  std::vector<float> ridge;
  std::vector<float> valley;
  for (std::size_t e = 0; e < exemplars.size(); ++e)
  {
    const Heightfield& ex = *exemplars[e];
    for (std::size_t k = 0; k < ex.size(); k += 7) // a sample is plenty for percentiles
    {
      if (ex.isValid(k))
      {
        all.push_back(ex.z[k]);
      }
    }
    if (e < graphs.size())
    {
      for (const FeatureChain& c : graphs[e]->chains)
      {
        for (float z : c.elevation)
        {
          if (!std::isnan(z))
          {
            (c.type == FeatureType::Ridge ? ridge : valley).push_back(z);
          }
        }
      }
    }
  }
  ExemplarStatistics s;
  s.low = percentile(all, 0.05);
  s.high = percentile(all, 0.95);
  s.median = percentile(all, 0.5);
  s.ridge = ridge.empty() ? s.high : percentile(ridge, 0.9);
  s.valley = valley.empty() ? s.low : percentile(valley, 0.1);
  return s;
}

FeatureGraph scaleGraph(const FeatureGraph& graph,
  int sketchWidth,
  int sketchHeight,
  int width,
  int height,
  double cellX,
  double cellY)
{
  FeatureGraph g = graph;
  const double sx = sketchWidth > 1 ? static_cast<double>(width - 1) / (sketchWidth - 1) : 1.0;
  const double sy = sketchHeight > 1 ? static_cast<double>(height - 1) / (sketchHeight - 1) : 1.0;
  auto scale = [&](Point2& p)
  {
    p.x *= sx;
    p.y *= sy;
  };
  for (FeatureNode& n : g.nodes)
  {
    scale(n.position);
    for (ControlPoint& c : n.controls)
    {
      scale(c.position);
    }
  }
  for (FeatureChain& c : g.chains)
  {
    for (Point2& p : c.points)
    {
      scale(p);
    }
  }
  g.width = width;
  g.height = height;
  g.cellX = cellX;
  g.cellY = cellY;
  return g;
}

SynthesisTarget targetFromStrokes(const FeatureGraph& graph,
  int w,
  int h,
  double cellX,
  double cellY,
  const ExemplarStatistics& stats,
  double profileWidth)
{
  SynthesisTarget t;
  t.graph = graph;
  t.field = Heightfield(w, h, static_cast<float>(stats.median));
  t.field.cellX = cellX;
  t.field.cellY = cellY;
  t.field.cellSizeKnown = true;
  const double s2 = 2.0 * profileWidth * profileWidth;
  const FeatureType ridge = FeatureType::Ridge;
  const FeatureType valley = FeatureType::Valley;
  const std::vector<float> dr = distanceTransform(rasterise(graph, &ridge, w, h), w, h);
  const std::vector<float> dv = distanceTransform(rasterise(graph, &valley, w, h), w, h);
  for (std::size_t k = 0; k < t.field.size(); ++k)
  {
    const double r = std::isinf(dr[k]) ? 0.0 : std::exp(-static_cast<double>(dr[k]) * dr[k] / s2);
    const double v = std::isinf(dv[k]) ? 0.0 : std::exp(-static_cast<double>(dv[k]) * dv[k] / s2);
    t.field.z[k] = static_cast<float>(
      stats.median + r * (stats.ridge - stats.median) + v * (stats.valley - stats.median));
  }
  if (graph.chains.empty())
  {
    t.warnings.push_back(
      "The sketch has no features: the terrain is filled without feature placement.");
  }
  return t;
}

SynthesisTarget targetFromHeights(const Heightfield& heights,
  const FeatureGraph& graph,
  const ExemplarStatistics& stats)
{
  SynthesisTarget t;
  t.graph = graph;
  t.field = heights;
  const HeightRange r = computeHeightRange(heights);
  const double span = r.max > r.min ? r.max - r.min : 1.0;
  for (std::size_t k = 0; k < t.field.size(); ++k)
  {
    if (t.field.isValid(k))
    {
      t.field.z[k] =
        static_cast<float>(stats.low + (t.field.z[k] - r.min) / span * (stats.high - stats.low));
    }
  }
  if (graph.chains.empty())
  {
    t.warnings.push_back(
      "The target has no features: the terrain is filled without feature placement.");
  }
  return t;
}

SynthesisTarget makeTarget(const FeatureGraph& sketchGraph,
  int sketchWidth,
  int sketchHeight,
  const Heightfield* sketchHeights,
  int width,
  int height,
  double cellX,
  double cellY,
  const ExemplarStatistics& stats,
  int patchSize)
{
  FeatureGraph graph =
    scaleGraph(sketchGraph, sketchWidth, sketchHeight, width, height, cellX, cellY);
  computeControlPoints(graph, 0.5 * patchSize);
  if (sketchHeights == nullptr)
  {
    return targetFromStrokes(
      graph, width, height, cellX, cellY, stats, defaultProfileWidth(patchSize));
  }
  // Nearest-neighbour resampling of the sketch's heights onto the output grid.
  Heightfield field(width, height);
  field.cellX = cellX;
  field.cellY = cellY;
  field.cellSizeKnown = true;
  const Heightfield& in = *sketchHeights;
  for (int j = 0; j < height; ++j)
  {
    for (int i = 0; i < width; ++i)
    {
      const int si =
        std::min(in.width - 1, static_cast<int>(static_cast<double>(i) * in.width / width));
      const int sj =
        std::min(in.height - 1, static_cast<int>(static_cast<double>(j) * in.height / height));
      field.at(i, j) = in.isValid(si, sj) ? in.at(si, sj) : std::numeric_limits<float>::quiet_NaN();
    }
  }
  normaliseMask(field);
  return targetFromHeights(field, graph, stats);
}

} // namespace tsynth
