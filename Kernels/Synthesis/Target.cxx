#include "Target.h"

#include "../Core/Error.h"
#include "../Core/Resample.h"
#include "../Distance/DistanceField.h"
#include "../Features/ImpliedLines.h"
#include "../Features/Ppa.h"
#include "../Features/Profiles.h"
#include "../Features/StrokeSpacing.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace tsynth
{
namespace
{

// Every so many cells of a DEM (target or exemplar) are enough for its percentiles.
constexpr std::size_t kPercentileSampleStep = 7;
// A grey sketch's background leaves out cells this close to its strokes (in
// patches: 5 cells for 80-cell patches, wider than a drawn stroke's half width)
// and is smoothed over a quarter patch.
constexpr double kStrokeClearanceInPatches = 1.0 / 16.0;
constexpr double kBackgroundSigmaInPatches = 0.25;

// Length (cells) of the longest connected piece of the graph's lines.
double longestStroke(const FeatureGraph& g)
{
  std::vector<double> length(static_cast<std::size_t>(std::max(1, g.componentCount)), 0.0);
  double longest = 0.0;
  for (const FeatureChain& c : g.chains)
  {
    const int component = c.from >= 0 ? g.nodes[static_cast<std::size_t>(c.from)].component : -1;
    if (component >= 0 && static_cast<std::size_t>(component) < length.size())
    {
      length[static_cast<std::size_t>(component)] += c.length();
      longest = std::max(longest, length[static_cast<std::size_t>(component)]);
    }
    else
    {
      longest = std::max(longest, c.length());
    }
  }
  return longest;
}

// A DEM target's own scale per cell: half the spacing (cells) between its
// ridges and valleys, the width of each slope between a crest and a floor.
std::vector<float> featureHalfWidths(const FeatureGraph& graph, int width, int height)
{
  StrokeSpacing s = strokeSpacing(rasteriseChains(graph, width, height), width, height);
  return std::move(s.halfSpacing);
}

// The implied lines worth shaping: at least half a patch long (shorter, the
// bisector at a junction, or the inside of a meander's bend, which shaped as
// a ridge stood as a small cross in the bend) and within a patch of the
// strokes they part (farther, the land is free); control points at half a
// patch, as the drawn lines'.
ImpliedLineOptions impliedLineOptions(int patchSize)
{
  ImpliedLineOptions o;
  o.minLength = 0.5 * patchSize;
  o.maxDistance = patchSize;
  o.controlRadius = 0.5 * patchSize;
  return o;
}

// What the drawn lines say beyond themselves: the lines they imply, and how
// far apart they are (the median over their cells of half the spacing to the
// facing line, cells; +inf where most face none).
struct DrawnLines
{
  FeatureGraph implied;
  double halfSpacing = 0.0;
};

DrawnLines readDrawnLines(const FeatureGraph& graph, int patchSize)
{
  const std::vector<std::uint8_t> cells = rasteriseChains(graph, graph.width, graph.height);
  const StrokeSpacing spacing = strokeSpacing(cells, graph.width, graph.height);
  DrawnLines d;
  d.implied = impliedLines(graph, spacing, impliedLineOptions(patchSize));
  std::vector<float> half;
  for (std::size_t k = 0; k < cells.size(); ++k)
  {
    if (cells[k] != 0)
    {
      half.push_back(spacing.halfSpacing[k]);
    }
  }
  d.halfSpacing = half.empty() ? 0.0 : percentile(half, 0.5);
  return d;
}

// The drawn lines and the lines they imply, as the landform field shapes
// them: a divide between two drawn valleys is a ridge with a ridge's
// cross-section (left a bare meeting of two slopes, it was lost among the
// exemplars' own knobs). `heights`, per drawn chain, gets an empty entry per
// implied chain (their heights are the field's own).
FeatureGraph withImplied(const FeatureGraph& drawn,
  const FeatureGraph& implied,
  LineHeights* heights)
{
  FeatureGraph all = drawn;
  appendGraph(all, implied);
  if (heights != nullptr)
  {
    heights->resize(all.chains.size());
  }
  return all;
}

} // namespace

double typicalHalfWidth(const SynthesisTarget& t)
{
  if (t.halfWidth.size() != t.field.size())
  {
    return 0.0;
  }
  const std::vector<std::uint8_t> lines = rasteriseChains(t.graph, t.field.width, t.field.height);
  std::vector<float> widths;
  for (std::size_t k = 0; k < lines.size(); ++k)
  {
    if (lines[k] != 0 && std::isfinite(t.halfWidth[k]))
    {
      widths.push_back(t.halfWidth[k]);
    }
  }
  return widths.empty() ? 0.0 : percentile(widths, 0.5);
}

double lineSpacing(const SynthesisTarget& t)
{
  return 2.0 * (t.lineHalfSpacing > 0.0 ? t.lineHalfSpacing : typicalHalfWidth(t));
}

ExemplarStatistics exemplarStatistics(const std::vector<const Heightfield*>& exemplars,
  const std::vector<const FeatureGraph*>& graphs,
  int patchSize)
{
  std::vector<float> all;
  std::vector<float> ridge;
  std::vector<float> valley;
  for (std::size_t e = 0; e < exemplars.size(); ++e)
  {
    const Heightfield& ex = *exemplars[e];
    for (std::size_t k = 0; k < ex.size(); k += kPercentileSampleStep)
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
  LandformMeasureOptions lo;
  lo.patchSize = patchSize;
  s.landform = measureLandforms(exemplars, graphs, lo);
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
  int patchSize,
  std::uint64_t seed)
{
  LineHeights constraints;
  bool constrained = false;
  for (const FeatureChain& c : graph.chains)
  {
    constraints.push_back(
      c.constraint.size() == c.points.size() ? c.constraint : std::vector<float>());
    constrained = constrained || !constraints.back().empty();
  }
  DrawnLines drawn = readDrawnLines(graph, patchSize);
  const FeatureGraph shaped = withImplied(graph, drawn.implied, &constraints);
  LandformFieldOptions lo;
  lo.patchSize = patchSize;
  lo.seed = seed;
  lo.impliedChainsFrom = graph.chains.size();
  LandformField f = landformField(
    shaped, w, h, cellX, cellY, stats.landform, lo, nullptr, constrained ? &constraints : nullptr);
  SynthesisTarget t;
  t.graph = graph;
  t.implied = std::move(drawn.implied);
  t.lineHalfSpacing = drawn.halfSpacing;
  t.field = std::move(f.field);
  t.weight = std::move(f.weight);
  t.halfWidth = std::move(f.halfWidth);
  t.ridgeRaise = f.ridgeRaise;
  t.valleyRaise = f.valleyRaise;
  t.downstream = std::move(f.downstream);
  t.warnings = stats.landform.warnings;
  t.warnings.insert(t.warnings.end(), f.warnings.begin(), f.warnings.end());
  if (graph.chains.empty())
  {
    t.warnings.push_back(
      "The sketch has no features: the terrain is filled without feature placement.");
  }
  else if (longestStroke(graph) < patchSize)
  {
    t.warnings.push_back("Every sketched stroke is shorter than one patch (" +
      std::to_string(patchSize) +
      " cells): each becomes a short landform, tapering at its ends; draw longer strokes or "
      "give a smaller --patch for finer ones.");
  }
  return t;
}

namespace
{

// The heights mapped linearly so that fromLow and fromHigh land on the
// exemplars' 5th and 95th percentiles.
Heightfield mappedOntoExemplars(const Heightfield& heights,
  double fromLow,
  double fromHigh,
  const ExemplarStatistics& stats)
{
  Heightfield out = heights;
  const double span = fromHigh > fromLow ? fromHigh - fromLow : 1.0;
  for (std::size_t k = 0; k < out.size(); ++k)
  {
    if (out.isValid(k))
    {
      out.z[k] =
        static_cast<float>(stats.low + (out.z[k] - fromLow) / span * (stats.high - stats.low));
    }
  }
  return out;
}

SynthesisTarget targetOfField(Heightfield field, const FeatureGraph& graph)
{
  SynthesisTarget t;
  t.graph = graph;
  t.field = std::move(field);
  t.detailed = true;
  t.weight.assign(t.field.size(), 1.0f);
  t.halfWidth = featureHalfWidths(graph, t.field.width, t.field.height);
  t.downstream.assign(t.field.size(), std::numeric_limits<float>::quiet_NaN());
  if (graph.chains.empty())
  {
    t.warnings.push_back(
      "The target has no features: the terrain is filled without feature placement.");
  }
  return t;
}

} // namespace

SynthesisTarget targetFromHeights(const Heightfield& heights,
  const FeatureGraph& graph,
  const ExemplarStatistics& stats)
{
  // Percentile onto percentile: the target's relief keeps its size against
  // the exemplars' (its whole range onto their 5th..95th squeezed a DEM as
  // rugged as theirs to under half its relief, and its valleys with it).
  std::vector<float> valid;
  for (std::size_t k = 0; k < heights.size(); k += kPercentileSampleStep)
  {
    if (heights.isValid(k))
    {
      valid.push_back(heights.z[k]);
    }
  }
  if (valid.empty())
  {
    return targetOfField(heights, graph);
  }
  const double low = percentile(valid, 0.05);
  const double high = percentile(valid, 0.95);
  return targetOfField(mappedOntoExemplars(heights, low, high, stats), graph);
}

namespace
{

// The grey sketch's background: its heights smoothed over a quarter patch with
// the strokes left out, so a stroke does not raise the land it stands on.
Heightfield greyBackground(const Heightfield& mapped, const FeatureGraph& graph, int patchSize)
{
  Heightfield masked = mapped;
  const std::vector<float> d = distanceTransform(
    rasteriseChains(graph, mapped.width, mapped.height), mapped.width, mapped.height);
  masked.valid.assign(masked.size(), 1);
  for (std::size_t k = 0; k < masked.size(); ++k)
  {
    if (!mapped.isValid(k) || d[k] <= kStrokeClearanceInPatches * patchSize)
    {
      masked.valid[k] = 0;
    }
  }
  Heightfield smooth = gaussianSmooth(masked, kBackgroundSigmaInPatches * patchSize);
  for (std::size_t k = 0; k < smooth.size(); ++k)
  {
    if (!(smooth.isValid(k) && std::isfinite(smooth.z[k])))
    {
      smooth.z[k] = mapped.isValid(k) ? mapped.z[k] : 0.0f;
    }
  }
  smooth.valid.clear();
  return smooth;
}

} // namespace

SynthesisTarget targetFromGreySketch(const Heightfield& grey,
  const FeatureGraph& graph,
  const ExemplarStatistics& stats,
  int patchSize,
  std::uint64_t seed)
{
  // The sketch's darkest and brightest grey onto the exemplars' typical
  // extremes: what is drawn at the ends of the scale means low and high land.
  const HeightRange r = computeHeightRange(grey);
  const SynthesisTarget mapped =
    targetOfField(mappedOntoExemplars(grey, r.min, r.max, stats), graph);
  LineHeights heights;
  for (const FeatureChain& c : graph.chains)
  {
    std::vector<float> h;
    for (const Point2& p : c.points)
    {
      h.push_back(sampleBilinear(mapped.field, p.x, p.y));
    }
    heights.push_back(std::move(h));
  }
  const Heightfield background = greyBackground(mapped.field, graph, patchSize);
  DrawnLines drawn = readDrawnLines(graph, patchSize);
  const FeatureGraph shaped = withImplied(graph, drawn.implied, &heights);
  LandformFieldOptions lo;
  lo.patchSize = patchSize;
  lo.seed = seed;
  lo.impliedChainsFrom = graph.chains.size();
  LandformField f = landformField(shaped,
    grey.width,
    grey.height,
    grey.cellX,
    grey.cellY,
    stats.landform,
    lo,
    &background,
    &heights);
  SynthesisTarget t;
  t.graph = graph;
  t.implied = std::move(drawn.implied);
  t.lineHalfSpacing = drawn.halfSpacing;
  t.field = std::move(f.field);
  t.field.georef = grey.georef;
  t.weight = std::move(f.weight);
  t.halfWidth = std::move(f.halfWidth);
  t.ridgeRaise = f.ridgeRaise;
  t.valleyRaise = f.valleyRaise;
  t.downstream = std::move(f.downstream);
  t.warnings = stats.landform.warnings;
  t.warnings.insert(t.warnings.end(), f.warnings.begin(), f.warnings.end());
  t.warnings.insert(t.warnings.end(), mapped.warnings.begin(), mapped.warnings.end());
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
  int patchSize,
  SketchHeights kind,
  std::uint64_t seed,
  double landformRelief)
{
  ExemplarStatistics scaled = stats;
  if (landformRelief != 1.0)
  {
    scaled.landform = withReliefScaled(stats.landform, landformRelief);
  }
  FeatureGraph graph =
    scaleGraph(sketchGraph, sketchWidth, sketchHeight, width, height, cellX, cellY);
  computeControlPoints(graph, 0.5 * patchSize);
  if (sketchHeights == nullptr || kind == SketchHeights::None)
  {
    return targetFromStrokes(graph, width, height, cellX, cellY, scaled, patchSize, seed);
  }
  Heightfield field = resampleNearest(*sketchHeights, width, height);
  field.cellX = cellX;
  field.cellY = cellY;
  field.cellSizeKnown = true;
  return kind == SketchHeights::Grey ? targetFromGreySketch(field, graph, scaled, patchSize, seed)
                                     : targetFromHeights(field, graph, stats);
}

} // namespace tsynth
