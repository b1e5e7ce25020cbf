#include "Landform.h"

#include "../Core/Cancellation.h"
#include "../Core/Constants.h"
#include "../Core/Error.h"
#include "../Core/Grid.h"
#include "../Core/Memory.h"
#include "../Core/Random.h"
#include "../Core/Smoothing.h"
#include "../Distance/DistanceField.h"
#include "../Features/StrokeSpacing.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>
#include <numeric>
#include <queue>

namespace tsynth
{
namespace
{

// The nearest seed of cell k, an int32 cell (-1: none, which the caller has ruled out).
std::size_t nearestSeed(const NearestSeeds& near, std::size_t k)
{
  return static_cast<std::size_t>(near.nearest[k]);
}

// Column and row of element k of a row-major grid `width` wide, as coordinates
// (rowMajor's inverse).
Point2 cellPoint(std::size_t k, int width)
{
  const GridCell c = cellOf(k, width);
  return { static_cast<double>(c.i), static_cast<double>(c.j) };
}

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Every so many cells of an exemplar are enough for its height percentiles.
constexpr std::size_t kHeightSampleStep = 7;
// Sketched landforms keep within the exemplars' heights but for this share at
// each end (LandformStatistics::lowest, highest).
constexpr double kLandExtremeShare = 0.005;
// Fewer cells than this at one distance say nothing about a cross-section.
constexpr std::size_t kMinCellsPerDistance = 32;
// Samples along valley lines for their floor gradient, a quarter patch apart:
// far enough that a cell's noise does not dominate the difference.
constexpr double kGradientSpacingInPatches = 0.25;
// When no exemplar valley can be measured: a gentle mountain-valley descent.
constexpr double kFallbackFloorGradient = 0.01;
// A river's long profile is concave (steep at its heads, gentle at its outlet):
// floor rise = share * (kOutletSlope t + (1 - kOutletSlope) t^2), t = distance / longest.
constexpr double kOutletSlope = 0.3;
// Where one line's influence gives way to another's: inverse squared distance
// weights, softened within these many cells of a ridge and of a valley (the
// smaller for valleys, so a valley's floor is never lifted by a crossing ridge).
constexpr double kRidgeSoftening = 2.0;
constexpr double kValleySoftening = 0.5;
// A valley crossing a ridge cuts a gorge: within a quarter patch of the valley
// the land may rise above its floor by at most the whole relief.
constexpr double kGorgeReachInPatches = 0.25;
// Confidence in the target is full where the cross-section has made this share
// of its relief (its tail is often the exemplar's regional slope, not the
// landform) and fades from there over half a patch.
constexpr double kConfidentReach = 0.75;
constexpr double kConfidenceFadeInPatches = 0.5;
// Strokes closer than this are drawn as if this far apart (cells of half
// spacing): a crest a cell or two from the next valley would be a cliff.
constexpr double kNarrowestHalfWidthCells = 4.0;
// A landform is seen out to this far from its line at most (in patches; the
// legibility measure's loneHalfWidth at 80-cell patches).
constexpr double kSeenHalfWidthInPatches = 0.5;
// A valley whose outlet end is a closed basin takes its raised relief (on its
// rims) from this many patches upstream of that end on.
constexpr double kOutletTaperInPatches = 0.5;
// An end within this share of a patch of the border drains out of the map.
constexpr double kBorderReachInPatches = 0.125;
// Outlet candidates whose flow paths differ by less than this share are
// equally good: the seed picks one.
constexpr double kOutletTie = 0.02;
// A line's values (crest, floor and rim heights) reach the land beside it
// smoothed at this share of the distance to the line (lineValueField), at
// most kLineValueSmoothingInPatches of a patch (farther out the target is no
// longer followed), on levels a factor kLineValueLevelStep apart (a factor 2
// cost 1.4 s of a 1024 x 1024 synthesis; the values are smooth either way).
constexpr double kLineValueSmoothingShare = 0.5;
constexpr double kLineValueSmoothingInPatches = 0.5;
constexpr double kLineValueLevelStep = 4.0;

// ---------------------------------------------------------------------------
// Measuring the exemplars.

// Median height difference to the nearest major line, per distance bin.
struct SectionBins
{
  std::vector<double> median;
  std::vector<std::size_t> count;
};

struct LineMeasure
{
  SectionBins bins;
  std::vector<float> majorHeights;
  double majorLength = 0.0; // metres
  std::vector<double> gradients;
};

LineMeasure measureLines(const Heightfield& ex,
  const FeatureGraph& graph,
  FeatureType type,
  const LandformMeasureOptions& o)
{
  LineMeasure m;
  const std::size_t n = ex.size();
  std::vector<std::uint8_t> line(n, 0);
  for (const FeatureChain& c : graph.chains)
  {
    if (c.type == type)
    {
      forEachChainCell(c,
        ex.width,
        ex.height,
        [&](int i, int j, std::size_t, double) { line[ex.index(i, j)] = 1; });
    }
  }
  std::vector<float> heights;
  for (std::size_t k = 0; k < n; ++k)
  {
    if (line[k] != 0 && ex.isValid(k))
    {
      heights.push_back(ex.z[k]);
    }
  }
  if (heights.empty())
  {
    return m;
  }
  const bool ridge = type == FeatureType::Ridge;
  const double threshold = percentile(heights, ridge ? 1.0 - o.majorShare : o.majorShare);
  std::vector<std::uint8_t> major(n, 0);
  for (std::size_t k = 0; k < n; ++k)
  {
    if (line[k] != 0 && ex.isValid(k) && (ridge ? ex.z[k] >= threshold : ex.z[k] <= threshold))
    {
      major[k] = 1;
      m.majorHeights.push_back(ex.z[k]);
    }
  }
  const double cell = std::min(ex.cellX, ex.cellY);
  m.majorLength = static_cast<double>(m.majorHeights.size()) * cell;
  const NearestSeeds near = nearestSeeds(major, ex.width, ex.height, ex.cellX, ex.cellY);
  // A reach in cells, rounded up, as a count of one-cell bins.
  const std::size_t bins = static_cast<std::size_t>(std::ceil(o.reachInPatches * o.patchSize));
  std::vector<std::vector<float>> differences(bins);
  for (std::size_t k = 0; k < n; ++k)
  {
    if (!ex.isValid(k) || near.nearest[k] < 0)
    {
      continue;
    }
    const std::size_t bin = static_cast<std::size_t>(near.distance[k] / cell); // whole cells
    if (bin < bins)
    {
      differences[bin].push_back(ex.z[k] - ex.z[nearestSeed(near, k)]);
    }
  }
  m.bins.median.assign(bins, 0.0);
  m.bins.count.assign(bins, 0);
  for (std::size_t b = 0; b < bins; ++b)
  {
    m.bins.count[b] = differences[b].size();
    m.bins.median[b] = percentile(std::move(differences[b]), 0.5);
  }
  // Floor (or crest) gradients along the major lines.
  const double spacing = kGradientSpacingInPatches * o.patchSize;
  for (const FeatureChain& c : graph.chains)
  {
    if (c.type != type || c.points.size() < 2 || c.elevation.size() != c.points.size())
    {
      continue;
    }
    double along = 0.0;
    double lastAlong = 0.0;
    float lastZ = c.elevation.front();
    for (std::size_t k = 1; k < c.points.size(); ++k)
    {
      along += std::hypot((c.points[k].x - c.points[k - 1].x) * ex.cellX,
        (c.points[k].y - c.points[k - 1].y) * ex.cellY);
      if (along - lastAlong < spacing * cell)
      {
        continue;
      }
      const float z = c.elevation[k];
      const bool majorPair =
        ridge ? std::min(z, lastZ) >= threshold : std::max(z, lastZ) <= threshold;
      if (!std::isnan(z) && !std::isnan(lastZ) && majorPair)
      {
        m.gradients.push_back(std::abs(z - lastZ) / (along - lastAlong));
      }
      lastAlong = along;
      lastZ = z;
    }
  }
  return m;
}

// The pooled cross-section of one kind of line over every exemplar.
LandformProfile poolProfile(const std::vector<LineMeasure>& measures, FeatureType type, double cell)
{
  LandformProfile p;
  if (measures.empty())
  {
    return p;
  }
  const std::size_t bins = measures.front().bins.median.size();
  std::vector<double> distance, value, weight;
  std::vector<float> levels;
  for (std::size_t b = 0; b < bins; ++b)
  {
    double sum = 0.0;
    std::size_t count = 0;
    for (const LineMeasure& m : measures)
    {
      if (b < m.bins.count.size())
      {
        sum += m.bins.median[b] * static_cast<double>(m.bins.count[b]);
        count += m.bins.count[b];
      }
    }
    if (count >= kMinCellsPerDistance)
    {
      distance.push_back((static_cast<double>(b) + 0.5) * cell);
      value.push_back(sum / static_cast<double>(count));
      weight.push_back(static_cast<double>(count));
    }
  }
  for (const LineMeasure& m : measures)
  {
    levels.insert(levels.end(), m.majorHeights.begin(), m.majorHeights.end());
    p.lineLength += m.majorLength;
  }
  if (distance.size() < 2 || levels.empty())
  {
    return p;
  }
  // The section starts at the line itself.
  distance.insert(distance.begin(), 0.0);
  value.insert(value.begin(), 0.0);
  weight.insert(weight.begin(), weight.front());
  p.section = MonotoneProfile::fit(distance,
    value,
    weight,
    type == FeatureType::Ridge ? Monotonicity::NonIncreasing : Monotonicity::NonDecreasing);
  p.level = percentile(levels, 0.5);
  p.relief = std::abs(p.section.back() - p.section.front());
  p.width = p.section.reach(0.9);
  return p;
}

// The section rescaled to a given relief (sign by type), same shape.
MonotoneProfile withRelief(const LandformProfile& p, double relief, FeatureType type)
{
  const MonotoneProfile s = p.section.normalised();
  std::vector<double> v = s.values();
  for (double& x : v)
  {
    x *= type == FeatureType::Ridge ? -relief : relief;
  }
  return MonotoneProfile::fromPoints(s.distances(), v);
}

// A ramp over half a patch, when nothing can be measured.
LandformProfile fallbackProfile(double level,
  double relief,
  FeatureType type,
  double cell,
  int patch)
{
  LandformProfile p;
  p.level = level;
  p.relief = relief;
  p.width = 0.5 * patch * cell;
  const double sign = type == FeatureType::Ridge ? -1.0 : 1.0;
  p.section = MonotoneProfile::fromPoints({ 0.0, p.width }, { 0.0, sign * relief });
  return p;
}

// Makes ridge and valley meet the same base, and fills in what is missing.
void reconcile(LandformStatistics& s, const std::vector<const Heightfield*>& exemplars, int patch)
{
  const double cell = std::min(exemplars.front()->cellX, exemplars.front()->cellY);
  const bool ridge = !s.ridge.section.empty() && s.ridge.relief > 0.0;
  const bool valley = !s.valley.section.empty() && s.valley.relief > 0.0;
  if (ridge && valley)
  {
    s.base = 0.5 * ((s.ridge.level - s.ridge.relief) + (s.valley.level + s.valley.relief));
    const double ridgeRelief = s.ridge.level - s.base;
    const double valleyRelief = s.base - s.valley.level;
    if (ridgeRelief > 0.0 && valleyRelief > 0.0)
    {
      s.ridge.section = withRelief(s.ridge, ridgeRelief, FeatureType::Ridge);
      s.valley.section = withRelief(s.valley, valleyRelief, FeatureType::Valley);
      s.ridge.relief = ridgeRelief;
      s.valley.relief = valleyRelief;
    }
    return;
  }
  if (ridge || valley)
  {
    // Mirror the kind that was measured.
    LandformProfile& known = ridge ? s.ridge : s.valley;
    LandformProfile& other = ridge ? s.valley : s.ridge;
    const FeatureType otherType = ridge ? FeatureType::Valley : FeatureType::Ridge;
    s.base = ridge ? known.level - known.relief : known.level + known.relief;
    other = known;
    other.level = ridge ? s.base - known.relief : s.base + known.relief;
    other.section = withRelief(known, known.relief, otherType);
    other.lineLength = 0.0;
    s.warnings.push_back(std::string("The exemplars have no major ") +
      (ridge ? "valleys" : "ridges") + " to measure: their cross-section mirrors the " +
      (ridge ? "ridges'." : "valleys'."));
    return;
  }
  std::vector<float> all;
  for (const Heightfield* ex : exemplars)
  {
    for (std::size_t k = 0; k < ex->size(); k += kHeightSampleStep)
    {
      if (ex->isValid(k))
      {
        all.push_back(ex->z[k]);
      }
    }
  }
  const double low = percentile(all, 0.05);
  const double high = percentile(all, 0.95);
  s.base = percentile(all, 0.5);
  const double relief = std::max(1e-3, 0.5 * (high - low));
  s.ridge = fallbackProfile(s.base + relief, relief, FeatureType::Ridge, cell, patch);
  s.valley = fallbackProfile(s.base - relief, relief, FeatureType::Valley, cell, patch);
  s.warnings.push_back("The exemplars have no ridges or valleys to measure: sketched features get "
                       "half their height range over half a patch.");
}

} // namespace

LandformStatistics measureLandforms(const std::vector<const Heightfield*>& exemplars,
  const std::vector<const FeatureGraph*>& graphs,
  const LandformMeasureOptions& o)
{
  if (exemplars.empty())
  {
    throw Error("No exemplar: give at least one DEM to measure landforms on.");
  }
  std::vector<LineMeasure> ridges, valleys;
  std::vector<double> gradients;
  for (std::size_t e = 0; e < exemplars.size(); ++e)
  {
    if (e >= graphs.size())
    {
      break;
    }
    ridges.push_back(measureLines(*exemplars[e], *graphs[e], FeatureType::Ridge, o));
    valleys.push_back(measureLines(*exemplars[e], *graphs[e], FeatureType::Valley, o));
    gradients.insert(
      gradients.end(), valleys.back().gradients.begin(), valleys.back().gradients.end());
  }
  const double cell = std::min(exemplars.front()->cellX, exemplars.front()->cellY);
  LandformStatistics s;
  s.ridge = poolProfile(ridges, FeatureType::Ridge, cell);
  s.valley = poolProfile(valleys, FeatureType::Valley, cell);
  reconcile(s, exemplars, o.patchSize);
  s.land = LandRelief(exemplars);
  std::vector<float> all;
  for (const Heightfield* ex : exemplars)
  {
    for (std::size_t k = 0; k < ex->size(); k += kHeightSampleStep)
    {
      if (ex->isValid(k))
      {
        all.push_back(ex->z[k]);
      }
    }
  }
  s.lowest = percentile(all, kLandExtremeShare);
  s.highest = percentile(all, 1.0 - kLandExtremeShare);
  if (gradients.empty())
  {
    s.floorGradient = kFallbackFloorGradient;
  }
  else
  {
    std::nth_element(gradients.begin(),
      gradients.begin() + static_cast<long>(gradients.size() / 2),
      gradients.end());
    s.floorGradient = gradients[gradients.size() / 2];
  }
  return s;
}

LandformStatistics withReliefScaled(const LandformStatistics& statistics, double factor)
{
  LandformStatistics s = statistics;
  s.ridge.relief *= factor;
  s.valley.relief *= factor;
  s.ridge.level = s.base + s.ridge.relief;
  s.valley.level = s.base - s.valley.relief;
  s.ridge.section = withRelief(statistics.ridge, s.ridge.relief, FeatureType::Ridge);
  s.valley.section = withRelief(statistics.valley, s.valley.relief, FeatureType::Valley);
  return s;
}

// ---------------------------------------------------------------------------
// Building the target.

namespace
{

// The points of a graph's chains of one type as a weighted graph: node ids
// first, then chain interiors; edges carry their length in metres.
class LineNetwork
{
public:
  // The chains of `type` among chains [firstChain, lastChain) of g.
  LineNetwork(const FeatureGraph& g,
    FeatureType type,
    double cellX,
    double cellY,
    std::size_t firstChain = 0,
    std::size_t lastChain = std::numeric_limits<std::size_t>::max())
    : graph_(g)
    , vertexOf_(g.chains.size())
  {
    std::size_t next = g.nodes.size();
    position_.resize(next);
    for (std::size_t v = 0; v < g.nodes.size(); ++v)
    {
      position_[v] = g.nodes[v].position;
    }
    edges_.resize(next);
    degree_.assign(next, 0);
    used_.assign(next, 0);
    for (std::size_t c = firstChain; c < std::min(lastChain, g.chains.size()); ++c)
    {
      const FeatureChain& ch = g.chains[c];
      if (ch.type != type || ch.points.size() < 2 || ch.from < 0 || ch.to < 0)
      {
        continue;
      }
      std::vector<std::size_t>& ids = vertexOf_[c];
      for (std::size_t k = 0; k < ch.points.size(); ++k)
      {
        if (k == 0 || k + 1 == ch.points.size())
        {
          // A node's vertex is its int id (valid: a chain's ends), held as a size.
          ids.push_back(static_cast<std::size_t>(k == 0 ? ch.from : ch.to));
        }
        else
        {
          ids.push_back(next++);
          position_.push_back(ch.points[k]);
          edges_.emplace_back();
          degree_.push_back(0);
          used_.push_back(0);
        }
      }
      for (std::size_t k = 1; k < ids.size(); ++k)
      {
        const double len = std::hypot((ch.points[k].x - ch.points[k - 1].x) * cellX,
          (ch.points[k].y - ch.points[k - 1].y) * cellY);
        edges_[ids[k - 1]].push_back({ ids[k], len });
        edges_[ids[k]].push_back({ ids[k - 1], len });
        used_[ids[k - 1]] = used_[ids[k]] = 1;
        ++edgeCount_;
      }
      ++degree_[ids.front()];
      ++degree_[ids.back()];
    }
  }

  std::size_t size() const { return position_.size(); }
  bool used(std::size_t v) const { return used_[v] != 0; }
  bool isEnd(std::size_t v) const { return v < graph_.nodes.size() && degree_[v] == 1; }
  const Point2& position(std::size_t v) const { return position_[v]; }
  // Vertex of point k of chain c (empty for chains of the other type).
  const std::vector<std::size_t>& chainVertices(std::size_t c) const { return vertexOf_[c]; }
  std::size_t edgeCount() const { return edgeCount_; }

  // Shortest distances along the lines from the sources.
  std::vector<double> distances(const std::vector<std::size_t>& sources) const
  {
    std::vector<double> d(size(), kInfinity);
    using Item = std::pair<double, std::size_t>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> open;
    for (std::size_t s : sources)
    {
      d[s] = 0.0;
      open.push({ 0.0, s });
    }
    while (!open.empty())
    {
      const auto [dist, v] = open.top();
      open.pop();
      if (dist > d[v])
      {
        continue;
      }
      for (const Edge& e : edges_[v])
      {
        if (dist + e.length < d[e.to])
        {
          d[e.to] = dist + e.length;
          open.push({ d[e.to], e.to });
        }
      }
    }
    return d;
  }

  // Connected pieces, as lists of used vertices.
  std::vector<std::vector<std::size_t>> components() const
  {
    std::vector<std::vector<std::size_t>> out;
    std::vector<std::uint8_t> seen(size(), 0);
    for (std::size_t s = 0; s < size(); ++s)
    {
      if (!used(s) || seen[s] != 0)
      {
        continue;
      }
      out.emplace_back();
      std::vector<std::size_t> stack{ s };
      seen[s] = 1;
      while (!stack.empty())
      {
        const std::size_t v = stack.back();
        stack.pop_back();
        out.back().push_back(v);
        for (const Edge& e : edges_[v])
        {
          if (seen[e.to] == 0)
          {
            seen[e.to] = 1;
            stack.push_back(e.to);
          }
        }
      }
      std::sort(out.back().begin(), out.back().end());
    }
    return out;
  }

  std::size_t edgesWithin(const std::vector<std::size_t>& component) const
  {
    std::size_t twice = 0;
    for (std::size_t v : component)
    {
      twice += edges_[v].size();
    }
    return twice / 2;
  }

private:
  struct Edge
  {
    std::size_t to;
    double length;
  };
  const FeatureGraph& graph_;
  std::vector<std::vector<std::size_t>> vertexOf_;
  std::vector<Point2> position_;
  std::vector<std::vector<Edge>> edges_;
  std::vector<int> degree_;
  std::vector<std::uint8_t> used_;
  std::size_t edgeCount_ = 0;
};

// Per vertex, from per chain point values (NaN where not given).
std::vector<double> vertexValues(const LineNetwork& net,
  const FeatureGraph& g,
  const LineHeights* heights)
{
  std::vector<double> v(net.size(), std::numeric_limits<double>::quiet_NaN());
  if (heights == nullptr)
  {
    return v;
  }
  for (std::size_t c = 0; c < g.chains.size() && c < heights->size(); ++c)
  {
    const std::vector<std::size_t>& ids = net.chainVertices(c);
    const std::vector<float>& h = (*heights)[c];
    for (std::size_t k = 0; k < ids.size() && k < h.size(); ++k)
    {
      if (!std::isnan(h[k]))
      {
        v[ids[k]] = h[k];
      }
    }
  }
  return v;
}

double borderDistance(const Point2& p, int w, int h)
{
  return std::min({ p.x, p.y, (w - 1) - p.x, (h - 1) - p.y });
}

// Among candidate vertices with scores, the best (highest), near-ties by the
// seed: decision `key` of the outlet stream (Random.h).
std::size_t pickBest(const std::vector<std::size_t>& candidates,
  const std::vector<double>& scores,
  std::uint64_t seed,
  std::uint64_t key)
{
  const double best = *std::max_element(scores.begin(), scores.end());
  std::vector<std::size_t> tied;
  for (std::size_t k = 0; k < candidates.size(); ++k)
  {
    if (scores[k] >= best - kOutletTie * std::abs(best))
    {
      tied.push_back(candidates[k]);
    }
  }
  return tied[seededIndex(seed, kStreamOutlet, key, tied.size())];
}

// Where a piece of the valley network drains: the lowest end when heights are
// known; else an end at the border, preferring the one with the longest flow
// path (the trunk's mouth); else the end of the longest path nearer the
// border; a network without ends drains at its point nearest the border.
std::size_t chooseOutlet(const LineNetwork& net,
  const std::vector<std::size_t>& component,
  const std::vector<double>& given,
  int w,
  int h,
  int patch,
  std::uint64_t seed)
{
  // The component's first vertex names its decision, whatever order the
  // components come in.
  const std::uint64_t key = *std::min_element(component.begin(), component.end());
  std::vector<std::size_t> ends;
  for (std::size_t v : component)
  {
    if (net.isEnd(v))
    {
      ends.push_back(v);
    }
  }
  std::vector<std::size_t> known;
  std::vector<double> score;
  for (std::size_t v : ends)
  {
    if (!std::isnan(given[v]))
    {
      known.push_back(v);
      score.push_back(-given[v]);
    }
  }
  if (!known.empty())
  {
    return pickBest(known, score, seed, key);
  }
  auto farthest = [&](std::size_t from)
  {
    const std::vector<double> d = net.distances({ from });
    double far = 0.0;
    for (std::size_t v : component)
    {
      far = std::max(far, d[v]);
    }
    return far;
  };
  std::vector<std::size_t> atBorder;
  score.clear();
  for (std::size_t v : ends)
  {
    if (borderDistance(net.position(v), w, h) <= kBorderReachInPatches * patch)
    {
      atBorder.push_back(v);
      score.push_back(farthest(v));
    }
  }
  if (!atBorder.empty())
  {
    return pickBest(atBorder, score, seed, key);
  }
  std::vector<std::size_t> candidates = ends.empty() ? component : ends;
  if (!ends.empty())
  {
    // The two ends of the longest path.
    std::vector<double> d = net.distances({ ends.front() });
    auto farEnd = [&](const std::vector<double>& dist)
    {
      return *std::max_element(
        ends.begin(), ends.end(), [&](std::size_t a, std::size_t b) { return dist[a] < dist[b]; });
    };
    const std::size_t a = farEnd(d);
    const std::size_t b = farEnd(net.distances({ a }));
    candidates = a == b ? std::vector<std::size_t>{ a } : std::vector<std::size_t>{ a, b };
  }
  score.clear();
  for (std::size_t v : candidates)
  {
    score.push_back(-borderDistance(net.position(v), w, h));
  }
  return pickBest(candidates, score, seed, key);
}

// Crest height per ridge vertex: the ridge's relief over the base, tapering
// towards free ends; given heights win.
std::vector<double> crestHeights(const LineNetwork& net,
  const std::vector<double>& given,
  const std::vector<double>& baseAt,
  const LandformStatistics& s,
  const LandformFieldOptions& o,
  double cell,
  int w,
  int h)
{
  // Free ends taper; an end at the border is where the ridge leaves the map.
  std::vector<std::size_t> ends;
  for (std::size_t v = 0; v < net.size(); ++v)
  {
    if (net.used(v) && net.isEnd(v) &&
      borderDistance(net.position(v), w, h) > kBorderReachInPatches * o.patchSize)
    {
      ends.push_back(v);
    }
  }
  const std::vector<double> fromEnd =
    ends.empty() ? std::vector<double>(net.size(), kInfinity) : net.distances(ends);
  const double taper = 0.5 * o.patchSize * cell;
  std::vector<double> crest(net.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t v = 0; v < net.size(); ++v)
  {
    if (!net.used(v))
    {
      continue;
    }
    if (!std::isnan(given[v]))
    {
      crest[v] = given[v];
      continue;
    }
    const double t = std::min(1.0, fromEnd[v] / taper);
    const double smooth = t * t * (3.0 - 2.0 * t);
    crest[v] = baseAt[v] + s.ridge.relief * (o.endRelief + (1.0 - o.endRelief) * smooth);
  }
  return crest;
}

struct ValleyFloors
{
  std::vector<double> floor;      // per vertex, metres
  std::vector<double> rim;        // per vertex: where the valley's sides end, metres
  std::vector<double> downstream; // per vertex: flow distance to the outlet, metres
};

// `raised`: the statistics with the relief raised to stand out; a network
// that drains out through the border takes them, and so does a loop (a moat
// with no outlet at all). One whose outlet end lies inside the map keeps the
// `measured` floor and, at that end, the measured depth, raised only upstream
// (its rim rising to the raised depth over kOutletTaperInPatches): the end is
// a closed basin (the land beyond it is the base), and a deeper one filled to
// a lake that drowned the lower valley (drainage along the meander's valley
// on Colorado 0.54 raised all along, 0.72 not at all).
ValleyFloors valleyFloors(const LineNetwork& net,
  const std::vector<double>& given,
  const std::vector<double>& baseAt,
  const LandformStatistics& raised,
  const LandformStatistics& measured,
  const LandformFieldOptions& o,
  double cell,
  int w,
  int h,
  std::vector<std::string>& warnings)
{
  ValleyFloors f;
  f.floor.assign(net.size(), std::numeric_limits<double>::quiet_NaN());
  f.rim.assign(net.size(), std::numeric_limits<double>::quiet_NaN());
  f.downstream.assign(net.size(), std::numeric_limits<double>::quiet_NaN());
  bool loop = false;
  for (const std::vector<std::size_t>& component : net.components())
  {
    loop = loop || net.edgesWithin(component) >= component.size();
    const std::size_t outlet = chooseOutlet(net, component, given, w, h, o.patchSize, o.seed);
    const bool drainsOut =
      borderDistance(net.position(outlet), w, h) <= kBorderReachInPatches * o.patchSize;
    const bool endless =
      std::none_of(component.begin(), component.end(), [&](std::size_t v) { return net.isEnd(v); });
    const bool closedOutlet = !drainsOut && !endless;
    const LandformStatistics& s = closedOutlet ? measured : raised;
    const double taper = kOutletTaperInPatches * o.patchSize * cell;
    const std::vector<double> d = net.distances({ outlet });
    double longest = 0.0;
    for (std::size_t v : component)
    {
      longest = std::max(longest, d[v]);
    }
    for (std::size_t v : component)
    {
      f.downstream[v] = d[v];
      const double depth = std::max(0.0, baseAt[v] - s.valley.level);
      const double rise = std::min(s.floorGradient * longest, o.headRise * depth);
      const double t = longest > 0.0 ? d[v] / longest : 0.0;
      f.floor[v] = std::isnan(given[v])
        ? s.valley.level + rise * (kOutletSlope * t + (1.0 - kOutletSlope) * t * t)
        : given[v];
      double rimDepth = depth;
      if (closedOutlet)
      {
        const double u = taper > 0.0 ? std::min(1.0, d[v] / taper) : 1.0;
        const double smooth = u * u * (3.0 - 2.0 * u);
        rimDepth += smooth * std::max(0.0, raised.valley.relief - measured.valley.relief);
      }
      f.rim[v] = f.floor[v] + rimDepth * (1.0 - (1.0 - o.headDepth) * t);
    }
  }
  if (loop)
  {
    warnings.push_back("A sketched valley network has a loop: water cannot run downhill all the "
                       "way round it, so its floor rises both ways from the outlet to a divide.");
  }
  return f;
}

// Per-cell values of a network's vertices along its rasterised chains: seeds
// mask and the value at each seed, interpolated between chain points; and per
// seed the first piece of chain drawn over it, so distances can be taken to the
// drawn line itself rather than to the staircase of its cells (exactLineDistances).
struct RasterLines
{
  std::vector<std::uint8_t> seeds;
  std::vector<float> value;
  std::vector<std::int32_t> piece;         // per cell: into `pieces`; -1 off the lines
  std::vector<std::pair<int, int>> pieces; // (chain, segment k: points k - 1 to k)
};

// The squared distance (square metres) from cell (i, j)'s centre to the
// segment from a to b.
double segmentDistance2(double i,
  double j,
  const Point2& a,
  const Point2& b,
  double cellX,
  double cellY)
{
  const double ux = (b.x - a.x) * cellX;
  const double uy = (b.y - a.y) * cellY;
  const double px = (i - a.x) * cellX;
  const double py = (j - a.y) * cellY;
  const double length2 = ux * ux + uy * uy;
  const double t = length2 > 0.0 ? std::clamp((px * ux + py * uy) / length2, 0.0, 1.0) : 0.0;
  const double dx = px - t * ux;
  const double dy = py - t * uy;
  return dx * dx + dy * dy;
}

// The pieces searched either side of the nearest seed's, at most. Up to 24
// cells from the line, 8 pieces (cells) take in the foot of the perpendicular,
// so the distance is exact; at 50 cells, a foot that lies farther along makes
// it less than a tenth of a cell too long, where the cross-sections change
// slowly.
constexpr int kMostPiecesSearched = 8;
// Cells a thread takes at a time in exactLineDistances (a cell far from its
// line searches more pieces, so the work is dealt out as it goes).
constexpr std::size_t kCellsPerTask = 4096;

// The distance from each cell off the lines to the drawn line through its
// nearest seed: to that seed's piece of chain and the pieces either side of
// it, not to the seed's centre. The line's own cells stay at 0, so its crest
// or floor values hold there exactly. Taken to cell centres, the distance
// rippled by up to half a cell along every slanted line, with the staircase
// of its cells; on the steep flanks next to a crest or floor the landform
// rippled with it, and the finishing copied the corrugation onto the terrain
// (stripes across the flanks, a dotted line along the floor, in a hillshade).
void exactLineDistances(NearestSeeds& near,
  const RasterLines& lines,
  const FeatureGraph& g,
  double cellX,
  double cellY)
{
  if (near.empty())
  {
    return;
  }
  const int w = near.width;
  // Each cell reads its own nearest seed and writes its own distance.
#pragma omp parallel for schedule(dynamic, kCellsPerTask)
  for (std::size_t k = 0; k < near.distance.size(); ++k)
  {
    const std::int32_t piece = lines.piece[nearestSeed(near, k)];
    if (piece < 0 || lines.seeds[k] != 0)
    {
      continue;
    }
    const auto [c, s] = byId(lines.pieces, piece);
    const std::vector<Point2>& points = byId(g.chains, c).points;
    const auto [i, j] = cellPoint(k, w);
    // The nearest seed lies up to sqrt(2 d) cells along the line from the
    // foot of the perpendicular (a seed half a cell nearer the line beats one
    // opposite the cell): the pieces that far either side are searched.
    const double cells = near.distance[k] / std::min(cellX, cellY);
    const int reach =
      std::min(kMostPiecesSearched, 1 + static_cast<int>(std::ceil(std::sqrt(2.0 * cells))));
    const int last = static_cast<int>(points.size()) - 1;
    double d2 = kInfinity;
    for (int m = std::max(1, s - reach); m <= std::min(s + reach, last); ++m)
    {
      d2 = std::min(d2, segmentDistance2(i, j, points[m - 1], points[m], cellX, cellY));
    }
    near.distance[k] = static_cast<float>(std::sqrt(d2));
  }
}

RasterLines rasteriseNetwork(const FeatureGraph& g,
  const LineNetwork& net,
  const std::vector<double>& vertexValue,
  int w,
  int h)
{
  RasterLines r;
  const std::size_t n = cellCount(w, h);
  r.seeds.assign(n, 0);
  r.value.assign(n, kNaN);
  r.piece.assign(n, -1);
  for (std::size_t c = 0; c < g.chains.size(); ++c)
  {
    const std::vector<std::size_t>& ids = net.chainVertices(c);
    if (ids.empty())
    {
      continue;
    }
    forEachChainCell(g.chains[c],
      w,
      h,
      [&](int i, int j, std::size_t k, double t)
      {
        const std::size_t cell = rowMajor(i, j, w);
        const double v = (1.0 - t) * vertexValue[ids[k - 1]] + t * vertexValue[ids[k]];
        // Where lines of the network cross, the lower value (the floor nearer
        // the outlet, or the lower crest) is kept.
        if (r.seeds[cell] == 0 || v < r.value[cell])
        {
          r.value[cell] = static_cast<float>(v);
        }
        r.seeds[cell] = 1;
        // The first piece over a cell is kept: any piece that passes over it
        // lies within a piece or two of the nearest, and exactLineDistances
        // searches the pieces around it.
        if (r.piece[cell] < 0)
        {
          if (r.pieces.empty() ||
            r.pieces.back() != std::pair<int, int>(static_cast<int>(c), static_cast<int>(k)))
          {
            r.pieces.emplace_back(static_cast<int>(c), static_cast<int>(k));
          }
          r.piece[cell] = static_cast<std::int32_t>(r.pieces.size() - 1);
        }
      });
  }
  return r;
}

// A sketch's lines with points at most kVertexSpacing cells apart, and the
// given heights along them (interpolated where both ends of a piece are given,
// NaN elsewhere). Crest tapers, concave floors and flow distances are values
// per point: a poly-line drawn with a few vertices would otherwise only get
// them at its vertices, and a straight two-point ridge would keep its end
// height all along.
struct DenseLines
{
  FeatureGraph graph;
  LineHeights heights;
};

constexpr double kVertexSpacing = 1.0;

// The value at t (0..1] between two given values; NaN unless both are given
// (t = 1 is the point itself).
float lerpGiven(float a, float b, double t)
{
  if (t >= 1.0)
  {
    return b;
  }
  return std::isnan(a) || std::isnan(b) ? kNaN : static_cast<float>(a + t * (b - a));
}

// Only what the target uses is carried over: geometry and given heights (the
// chains' elevation and constraint samples are dropped).
DenseLines densify(const FeatureGraph& g, const LineHeights* heights)
{
  DenseLines d;
  d.graph = g;
  d.heights.resize(heights != nullptr ? g.chains.size() : 0);
  for (std::size_t c = 0; c < g.chains.size(); ++c)
  {
    const std::vector<Point2>& src = g.chains[c].points;
    FeatureChain& dst = d.graph.chains[c];
    const std::vector<float> none;
    const std::vector<float>& given =
      heights != nullptr && c < heights->size() ? (*heights)[c] : none;
    auto givenAt = [&](std::size_t k) { return k < given.size() ? given[k] : kNaN; };
    dst.points.clear();
    dst.elevation.clear();
    dst.constraint.clear();
    for (std::size_t k = 0; k < src.size(); ++k)
    {
      const std::size_t from = k == 0 ? 0 : k - 1;
      const Point2& a = src[from];
      const Point2& b = src[k];
      const double length = std::hypot(b.x - a.x, b.y - a.y);
      const int pieces = std::max(1, static_cast<int>(std::ceil(length / kVertexSpacing)));
      for (int s = 1; s <= pieces; ++s)
      {
        const double t = static_cast<double>(s) / pieces;
        dst.points.push_back({ a.x + t * (b.x - a.x), a.y + t * (b.y - a.y) });
        if (heights != nullptr)
        {
          d.heights[c].push_back(lerpGiven(givenAt(from), givenAt(k), t));
        }
      }
    }
  }
  return d;
}

// One kind of landform's cross-section in the room the drawing leaves it: as
// the exemplars have it where the strokes are farther apart than it is wide;
// squeezed into the half spacing where they are closer, and there turning
// into an even slope from the line to the medial axis (the exemplars' major
// sections rise steeply at the line and slowly after, which squeezed reads as
// a notch in a plateau, not as a valley or a crest). So the whole relief is
// made by the medial axis: two valleys make a divide between them, a ridge and
// a valley one flank.
class CrossSection
{
public:
  CrossSection(const MonotoneProfile& shape, double width, double narrowest)
    : shape_(shape)
    , width_(width)
    , narrowest_(narrowest)
  {
  }

  // 0 at the line, 1 where the landform has made its relief (0.9 at `width`
  // for an unsqueezed section, as measured).
  double shape(double d, double room) const
  {
    const double q = squeeze(room);
    if (q >= 1.0)
    {
      return shape_(d);
    }
    const double u = std::min(1.0, d / (q * width_));
    return q * shape_(d / q) + (1.0 - q) * u;
  }

  // The distance as the unsqueezed section would see it (for confidence and
  // for weighing one line's influence against another's).
  double distance(double d, double room) const { return d / squeeze(room); }

private:
  // 1 with room to spare; else the share of the section's width there is room for.
  double squeeze(double room) const
  {
    const double r = std::max(narrowest_, room);
    return r < width_ ? r / width_ : 1.0;
  }

  const MonotoneProfile& shape_;
  double width_;
  double narrowest_;
};

double confidence(double d, double width, double fade)
{
  if (d <= width)
  {
    return 1.0;
  }
  if (d >= width + fade)
  {
    return 0.0;
  }
  const double c = std::cos(0.5 * kPi * (d - width) / fade);
  return c * c;
}

} // namespace

namespace
{

// The cells of the chains of one type (or of all types).
std::vector<std::uint8_t> chainCells(const FeatureGraph& g, int w, int h, const FeatureType* type)
{
  std::vector<std::uint8_t> cells(cellCount(w, h), 0);
  for (const FeatureChain& c : g.chains)
  {
    if (type == nullptr || c.type == *type)
    {
      forEachChainCell(
        c, w, h, [&](int i, int j, std::size_t, double) { cells[rowMajor(i, j, w)] = 1; });
    }
  }
  return cells;
}

// The typical room (metres) the drawing leaves one kind of landform: the
// median over its line cells of the half spacing, at most its width; 0 if
// there is no such line.
double typicalRoom(const FeatureGraph& g,
  FeatureType type,
  const StrokeSpacing& spacing,
  double width)
{
  const std::vector<std::uint8_t> cells = chainCells(g, spacing.width, spacing.height, &type);
  std::vector<float> rooms;
  for (std::size_t k = 0; k < cells.size(); ++k)
  {
    if (cells[k] != 0)
    {
      rooms.push_back(static_cast<float>(std::min<double>(width, spacing.halfSpacing[k])));
    }
  }
  return rooms.empty() ? 0.0 : percentile(rooms, 0.5);
}

// How much a landform of this section, relief 1, stands out by
// sectionProminence when squeezed into `room` metres and looked at over
// `half` cells each side.
double unitProminence(const CrossSection& section,
  double room,
  int half,
  double cell,
  FeatureType type)
{
  std::vector<double> z(static_cast<std::size_t>(2 * half + 1)); // a count, for the constructor
  const double sign = type == FeatureType::Ridge ? 1.0 : -1.0;
  int k = -half; // z[0] is offset -half
  for (double& v : z)
  {
    v = sign * (1.0 - section.shape(std::abs(k) * cell, room));
    ++k;
  }
  return sectionProminence(z, sign);
}

// The factor one kind of landform's relief is scaled by: raised so that it
// stands out (LandformFieldOptions::standOut), but never so steep that its
// flank (the relief over the room it has, at most its width) is steeper than
// the exemplars' own land at that scale (LandRelief::steepSlope: a grid of
// ridges and valleys 20 cells apart raised to stand out had 50-degree flanks
// and twice the exemplars' slopes), nor past their highest (lowest) land.
// Below 1 where even the exemplars' relief is too steep for the room.
double reliefFactor(const LandformProfile& p,
  const CrossSection& section,
  FeatureType type,
  double room,
  const LandformStatistics& s,
  const LandformFieldOptions& o,
  double cell)
{
  if (!(room > 0.0) || !(p.relief > 0.0) || s.land.empty())
  {
    return 1.0;
  }
  const double flank = std::min(room, p.width);
  const int half =
    std::max(1, static_cast<int>(std::min(room / cell, kSeenHalfWidthInPatches * o.patchSize)));
  const double unit = unitProminence(section, room, half, cell, type);
  double factor = 1.0;
  if (o.standOut > 0.0 && unit > 0.0)
  {
    factor = std::max(1.0, o.standOut * s.land.at(half) / unit / p.relief);
  }
  const double allowance = type == FeatureType::Ridge ? o.ridgeFlankAllowance : 1.0;
  const double steepest = allowance * s.land.steepSlope(flank / cell) / cell * flank;
  if (steepest > 0.0)
  {
    factor = std::max(1.0, std::min(factor, steepest / p.relief));
  }
  const double pastHighest = o.crestPastHighestShare * (s.highest - s.lowest);
  const double highest =
    type == FeatureType::Ridge ? s.highest + pastHighest - s.base : s.base - s.lowest;
  return std::min(factor, std::max(1.0, highest / p.relief));
}

// Per cell, the value of its nearest line cell (a crest's, floor's or rim's
// height) smoothed at kLineValueSmoothingShare of the distance to that cell:
// exact on the line, continuous where the cells two line cells are nearest to
// meet. Taken from the nearest line cell alone, the value stepped where that
// changed from one arm of a corner to the other or from one network to the
// next, and the landform stepped with it (cliffs of up to 160 m in one cell
// along the inner corners of letters drawn as valleys). Empty when there is
// no line of the kind (near.empty()): the blend reads none of it then.
std::vector<double> lineValueField(const RasterLines& lines,
  const NearestSeeds& near,
  int w,
  int h,
  double cell,
  int patchSize)
{
  checkCancellation();
  if (near.empty())
  {
    return {};
  }
  const std::size_t n = cellCount(w, h);
  std::vector<double> field(n, 0.0);
  Heightfield raw(w, h, 0.0f);
  // Each cell's smoothing (cells), worked out where it is needed rather than
  // held: a plane of doubles at the peak of a large target's set-up.
  const double widestAllowed = kLineValueSmoothingInPatches * patchSize;
  auto sigmaAt = [&](std::size_t k)
  { return std::min(kLineValueSmoothingShare * near.distance[k] / cell, widestAllowed); };
  // Per row, its widest smoothing (a maximum: the same in any order).
  std::vector<double> widestInRow(static_cast<std::size_t>(h), 0.0);
  forRowBands(h,
    [&](int j)
    {
      double& widestHere = widestInRow[static_cast<std::size_t>(j)];
      for (int i = 0; i < w; ++i)
      {
        const std::size_t k = rowMajor(i, j, w);
        raw.z[k] = lines.value[nearestSeed(near, k)];
        widestHere = std::max(widestHere, sigmaAt(k));
      }
    });
  const double widest = *std::max_element(widestInRow.begin(), widestInRow.end());
  // Smoothed at sigmas kLineValueLevelStep apart, interpolated between them in
  // log sigma: each cell between the first level at least its sigma and the
  // one before (the last level is the widest sigma). The levels are made one
  // at a time, each cell blended when its pair is at hand: two smoothed
  // fields are held, not every level (a 4096 x 4096 target's prepare peaked
  // at 7 of them).
  std::vector<double> levels{ 0.0 };
  for (double s = 1.0; levels.back() < widest; s *= kLineValueLevelStep)
  {
    levels.push_back(std::min(s, widest));
  }
  for (std::size_t k = 0; k < n; ++k)
  {
    if (levels.size() == 1 || sigmaAt(k) <= 0.0)
    {
      field[k] = raw.z[k];
    }
  }
  // The level below: the raw values at first (read in place, not copied),
  // then the last smoothed level.
  Heightfield previousSmoothed;
  const Heightfield* previous = &raw;
  for (std::size_t l = 1; l < levels.size(); ++l)
  {
    Heightfield current = smoothLarge(raw, levels[l]);
    const double lo = levels[l - 1];
    const double hi = levels[l];
    const bool last = l + 1 == levels.size();
    const auto blendLevels = [&](std::size_t k)
    {
      const double s = sigmaAt(k);
      if (s <= 0.0 || (l > 1 && !(lo < s)) || !(hi >= s || last))
      {
        return; // done raw, or blended at another pair of levels
      }
      const double t = s >= hi ? 1.0 : lo <= 0.0 ? s / hi : std::log(s / lo) / std::log(hi / lo);
      field[k] = (1.0 - t) * previous->z[k] + t * current.z[k];
    };
    forRowBands(h,
      [&](int j)
      {
        for (int i = 0; i < w; ++i)
        {
          blendLevels(rowMajor(i, j, w));
        }
      });
    previousSmoothed = std::move(current);
    previous = &previousSmoothed;
  }
  return field;
}

// Lets go of a raster's line pieces, which only exactLineDistances reads.
void keepValuesOnly(RasterLines& lines)
{
  std::vector<std::int32_t>().swap(lines.piece);
  std::vector<std::pair<int, int>>().swap(lines.pieces);
}

// Lets go of the whole raster once lineValueField has read its values and seeds,
// and (unless another raster still needs them) the map's nearest cells. The
// map's distances are kept for the blend, unless there is no line of the kind
// (then the blend reads none of them).
void releaseLineValues(RasterLines& lines, NearestSeeds& near, bool nearestToo = true)
{
  keepValuesOnly(lines);
  std::vector<float>().swap(lines.value);
  std::vector<std::uint8_t>().swap(lines.seeds);
  if (near.empty())
  {
    std::vector<float>().swap(near.distance);
  }
  if (nearestToo)
  {
    std::vector<std::int32_t>().swap(near.nearest);
  }
  // At 4096^2 each kind frees hundreds of MB that the next kind's planes,
  // made in another order and size, only partly reuse.
  returnFreedMemory();
}

// Lets go of the distances to the strokes and the medial axis, which only the
// half spacing's making reads.
void keepHalfSpacingOnly(StrokeSpacing& s)
{
  std::vector<float>().swap(s.toStroke);
  std::vector<std::uint8_t>().swap(s.medial);
}

// The statistics with each kind's relief raised by its factor.
LandformStatistics withReliefs(const LandformStatistics& s, double ridge, double valley)
{
  LandformStatistics r = s;
  r.ridge.relief *= ridge;
  r.valley.relief *= valley;
  r.ridge.level = r.base + r.ridge.relief;
  r.valley.level = r.base - r.valley.relief;
  r.ridge.section = withRelief(s.ridge, r.ridge.relief, FeatureType::Ridge);
  r.valley.section = withRelief(s.valley, r.valley.relief, FeatureType::Valley);
  return r;
}

// The output's cells, as the steps of landformField read them.
struct LandGrid
{
  int w = 0;
  int h = 0;
  double cellX = 1.0; // metres
  double cellY = 1.0;
  // The finer side: the unit of the landforms' widths and smoothings.
  double cell() const { return std::min(cellX, cellY); }
};

// The room the drawing leaves each landform, read off its strokes' spacing
// (StrokeSpacing) and held to a share of their length
// (kStrokeLengthPerHalfWidth): all the lines' (a landform's shape reaches up
// to the divide implied beside it) and the drawn lines' alone (its raise, and
// the scale the result follows it at). Only the half spacings are kept.
struct LandformRoom
{
  FeatureGraph drawn;      // the drawn chains alone, on the output grid
  bool implied = false;    // the graph has implied lines past the drawn ones
  StrokeSpacing all;       // every line together
  StrokeSpacing drawnOnly; // the drawn lines alone; empty unless `implied`
  const StrokeSpacing& drawnRoom() const { return implied ? drawnOnly : all; }
};

LandformRoom landformRoom(const FeatureGraph& graph,
  std::size_t impliedChainsFrom,
  const LandGrid& grid)
{
  LandformRoom room;
  checkCancellation(); // each step below takes tens of milliseconds at 1024^2: a stop waits
  room.all = strokeSpacing(
    chainCells(graph, grid.w, grid.h, nullptr), grid.w, grid.h, grid.cellX, grid.cellY);
  checkCancellation(); // for one step at most
  room.drawn = graph;
  room.drawn.chains.resize(std::min(room.drawn.chains.size(), impliedChainsFrom));
  room.drawn.width = grid.w;
  room.drawn.height = grid.h;
  // A short stroke's landform is held to a share of its length, the drawn
  // strokes' alone: an implied divide is as long as the valleys it parts.
  room.implied = room.drawn.chains.size() < graph.chains.size();
  {
    const std::vector<float> drawnLength = nearestStrokeLength(room.drawn, grid.cellX, grid.cellY);
    limitByStrokeLength(room.all, drawnLength);
    checkCancellation();
    if (room.implied)
    {
      room.drawnOnly = strokeSpacing(
        chainCells(room.drawn, grid.w, grid.h, nullptr), grid.w, grid.h, grid.cellX, grid.cellY);
      limitByStrokeLength(room.drawnOnly, drawnLength);
    }
  }
  keepHalfSpacingOnly(room.all);
  keepHalfSpacingOnly(room.drawnOnly);
  return room;
}

// Each kind's relief factor (out.ridgeRaise, out.valleyRaise): raised to stand
// out at the room the drawn lines leave it.
void raiseReliefs(LandformField& out,
  const LandformStatistics& measured,
  const LandformRoom& room,
  const LandformFieldOptions& o,
  double cell,
  double narrowest)
{
  const MonotoneProfile ridgeShape = measured.ridge.section.normalised();
  const MonotoneProfile valleyShape = measured.valley.section.normalised();
  const CrossSection ridgeSection(ridgeShape, measured.ridge.width, narrowest);
  const CrossSection valleySection(valleyShape, measured.valley.width, narrowest);
  out.ridgeRaise = reliefFactor(measured.ridge,
    ridgeSection,
    FeatureType::Ridge,
    typicalRoom(room.drawn, FeatureType::Ridge, room.drawnRoom(), measured.ridge.width),
    measured,
    o,
    cell);
  out.valleyRaise = reliefFactor(measured.valley,
    valleySection,
    FeatureType::Valley,
    typicalRoom(room.drawn, FeatureType::Valley, room.drawnRoom(), measured.valley.width),
    measured,
    o,
    cell);
}

// The land the landforms stand on: `base` where it is given and valid, else `level`.
Heightfield baseField(const LandGrid& grid, double level, const Heightfield* base)
{
  Heightfield field(grid.w, grid.h, static_cast<float>(level));
  field.cellX = grid.cellX;
  field.cellY = grid.cellY;
  field.cellSizeKnown = true;
  if (base != nullptr)
  {
    for (std::size_t k = 0; k < field.size(); ++k)
    {
      field.z[k] = base->isValid(k) ? base->z[k] : static_cast<float>(level);
    }
  }
  return field;
}

// The land's height under each vertex of a network (at its nearest cell).
std::vector<double> baseUnder(const LineNetwork& net, const Heightfield& land)
{
  std::vector<double> b(net.size());
  for (std::size_t v = 0; v < net.size(); ++v)
  {
    const int i = std::clamp(static_cast<int>(std::lround(net.position(v).x)), 0, land.width - 1);
    const int j = std::clamp(static_cast<int>(std::lround(net.position(v).y)), 0, land.height - 1);
    b[v] = land.at(i, j);
  }
  return b;
}

// One kind of line as the blend reads it: each cell's distance to the nearest
// line of the kind, and that line's value spread onto the land
// (lineValueField); `at` is empty when there is no line of the kind.
struct KindLines
{
  NearestSeeds near; // its nearest cells are let go of once `at` is made
  std::vector<double> at;
  bool any = false; // there are lines of the kind
};

// A kind's lines from their raster, which is then let go of, and with it the
// map's nearest cells unless another raster of the same lines still needs them.
KindLines kindLines(RasterLines& cells,
  const FeatureGraph& graph,
  const LandGrid& grid,
  int patchSize,
  bool keepNearest = false)
{
  KindLines lines;
  lines.near = nearestSeeds(cells.seeds, grid.w, grid.h, grid.cellX, grid.cellY);
  exactLineDistances(lines.near, cells, graph, grid.cellX, grid.cellY);
  lines.any = !lines.near.empty();
  lines.at = lineValueField(cells, lines.near, grid.w, grid.h, grid.cell(), patchSize);
  releaseLineValues(cells, lines.near, !keepNearest);
  return lines;
}

// What the blend of the landforms reads besides the land under them (the
// field it writes over).
struct LandformTerms
{
  const LandformStatistics& raised; // the statistics with the reliefs raised
  const LandformRoom& room;
  const KindLines& ridges;
  const KindLines& valleys; // `at`: the floors
  const std::vector<double>& rims;
  const KindLines& troughs;
  const RasterLines& flow; // the valleys' flow distances, on their cells
  double narrowest;        // metres: kNarrowestHalfWidthCells
};

// Each cell's blend of its nearest lines' terms (inverse squared distance
// weights, a valley's gorge cut through a ridge), with the target's confidence,
// half width and flow distance, row by row on every thread (each cell reads
// shared inputs and writes only its own outputs).
void blendLandforms(LandformField& out, const LandformTerms& t, const LandGrid& grid, int patchSize)
{
  const LandformStatistics& s = t.raised;
  const double cell = grid.cell();
  const std::size_t n = out.field.size();
  out.weight.assign(n, 0.0f);
  out.halfWidth.assign(n, 0.0f);
  out.downstream.assign(n, kNaN);
  const MonotoneProfile ridgeShape = s.ridge.section.normalised();
  const MonotoneProfile valleyShape = s.valley.section.normalised();
  const CrossSection ridgeSection(ridgeShape, s.ridge.width, t.narrowest);
  const CrossSection valleySection(valleyShape, s.valley.width, t.narrowest);
  const double fade = kConfidenceFadeInPatches * patchSize * cell;
  const double gorgeSlope =
    (s.ridge.relief + s.valley.relief) / (kGorgeReachInPatches * patchSize * cell);
  const double ridgeConfident = s.ridge.section.reach(kConfidentReach);
  const double valleyConfident = s.valley.section.reach(kConfidentReach);
  const double ridgeSoft2 = std::pow(kRidgeSoftening * cell, 2.0);
  const double valleySoft2 = std::pow(kValleySoftening * cell, 2.0);
  const std::vector<float>& room = t.room.all.halfSpacing;
  const std::vector<float>& drawnRoom = t.room.drawnRoom().halfSpacing;
  const auto blend = [&](std::size_t k)
  {
    const double b = out.field.z[k];
    double sum = 0.0;
    double weights = 0.0;
    double conf = 0.0;
    double nearest = kInfinity;
    double width = 0.0;
    if (t.ridges.any)
    {
      const double toLine = t.ridges.near.distance[k];
      const double d = ridgeSection.distance(toLine, room[k]);
      const double top = t.ridges.at[k];
      const double a = 1.0 / (d * d + ridgeSoft2);
      sum += a * (top - (top - b) * ridgeSection.shape(toLine, room[k]));
      weights += a;
      conf = std::max(conf, confidence(d, ridgeConfident, fade));
      nearest = toLine;
      width = s.ridge.width;
    }
    double gorge = kInfinity;
    if (t.valleys.any)
    {
      const double toLine = t.valleys.near.distance[k];
      const double d = valleySection.distance(toLine, room[k]);
      const double bottom = t.valleys.at[k];
      const double top = t.rims[k];
      const double a = 1.0 / (d * d + valleySoft2);
      sum += a * (bottom + (top - bottom) * valleySection.shape(toLine, room[k]));
      weights += a;
      conf = std::max(conf, confidence(d, valleyConfident, fade));
      gorge = bottom + gorgeSlope * d;
      if (toLine < nearest)
      {
        width = s.valley.width;
      }
    }
    if (t.troughs.any)
    {
      const double toLine = t.troughs.near.distance[k];
      const double d = valleySection.distance(toLine, room[k]);
      const double bottom = t.troughs.at[k];
      const double a = 1.0 / (d * d + valleySoft2);
      sum += a * (bottom + (b - bottom) * valleySection.shape(toLine, room[k]));
      weights += a;
      conf = std::max(conf, confidence(d, valleyConfident, fade));
    }
    if (weights > 0.0)
    {
      out.field.z[k] = static_cast<float>(std::min(gorge, sum / weights));
    }
    out.weight[k] = static_cast<float>(conf);
    out.halfWidth[k] =
      static_cast<float>(std::max(t.narrowest, std::min<double>(width, drawnRoom[k])) / cell);
    if (t.flow.seeds[k] != 0)
    {
      out.downstream[k] = t.flow.value[k];
    }
  };
  forRowBands(grid.h,
    [&](int j)
    {
      for (int i = 0; i < grid.w; ++i)
      {
        blend(rowMajor(i, j, grid.w));
      }
    });
}

} // namespace

LandformField landformField(const FeatureGraph& sketch,
  int w,
  int h,
  double cellX,
  double cellY,
  const LandformStatistics& measured,
  const LandformFieldOptions& o,
  const Heightfield* base,
  const LineHeights* sketchHeights)
{
  const LandGrid grid{ w, h, cellX, cellY };
  const DenseLines dense = densify(sketch, sketchHeights);
  const FeatureGraph& graph = dense.graph;
  const LineHeights* heights = sketchHeights != nullptr ? &dense.heights : nullptr;
  const double cell = grid.cell();
  const double narrowest = kNarrowestHalfWidthCells * cell;
  const LandformRoom room = landformRoom(graph, o.impliedChainsFrom, grid);
  LandformField out;
  raiseReliefs(out, measured, room, o, cell, narrowest);
  const LandformStatistics s = withReliefs(measured, out.ridgeRaise, out.valleyRaise);
  out.field = baseField(grid, s.base, base);

  // Implied troughs (valleys between two drawn ridges) are a term of their
  // own: no outlet, no flow, a floor the valley relief below the base and the
  // base itself for a rim. Sharing the drawn valleys' nearest line, the field
  // jumped where the nearest changed from a drawn valley's rim to a trough's.
  const LineNetwork ridgeNet(graph, FeatureType::Ridge, cellX, cellY);
  const LineNetwork valleyNet(graph, FeatureType::Valley, cellX, cellY, 0, o.impliedChainsFrom);
  const LineNetwork troughNet(graph, FeatureType::Valley, cellX, cellY, o.impliedChainsFrom);
  std::vector<double> troughFloor = baseUnder(troughNet, out.field);
  for (double& z : troughFloor)
  {
    z -= s.valley.relief;
  }
  // Each kind's line values are spread (kindLines) right after its
  // nearest-line map is made, and then the rasters' values and the maps'
  // nearest cells go: the blend reads only the distances. Held for every
  // kind at once they set the peak of a large target's set-up.
  RasterLines troughCells = rasteriseNetwork(graph, troughNet, troughFloor, w, h);
  const KindLines troughs = kindLines(troughCells, graph, grid, o.patchSize);
  checkCancellation();
  const std::vector<double> crest = crestHeights(ridgeNet,
    vertexValues(ridgeNet, graph, heights),
    baseUnder(ridgeNet, out.field),
    s,
    o,
    cell,
    w,
    h);
  const ValleyFloors floors = valleyFloors(valleyNet,
    vertexValues(valleyNet, graph, heights),
    baseUnder(valleyNet, out.field),
    s,
    measured,
    o,
    cell,
    w,
    h,
    out.warnings);
  RasterLines ridgeCells = rasteriseNetwork(graph, ridgeNet, crest, w, h);
  checkCancellation();
  const KindLines ridges = kindLines(ridgeCells, graph, grid, o.patchSize);
  checkCancellation();
  RasterLines valleyCells = rasteriseNetwork(graph, valleyNet, floors.floor, w, h);
  checkCancellation();
  KindLines valleys = kindLines(valleyCells, graph, grid, o.patchSize, true);
  // The rims and the flow lie on the floors' cells: each raster is made when
  // it is read, and only its values are kept.
  RasterLines valleyRims = rasteriseNetwork(graph, valleyNet, floors.rim, w, h);
  keepValuesOnly(valleyRims);
  const std::vector<double> rims =
    lineValueField(valleyRims, valleys.near, w, h, cell, o.patchSize);
  releaseLineValues(valleyRims, valleys.near);
  RasterLines flow = rasteriseNetwork(graph, valleyNet, floors.downstream, w, h);
  keepValuesOnly(flow);
  blendLandforms(
    out, { s, room, ridges, valleys, rims, troughs, flow, narrowest }, grid, o.patchSize);
  return out;
}

} // namespace tsynth
