#include "LandformMetrics.h"

#include "../Core/Error.h"
#include "../Features/ChainPath.h"
#include "../Features/Profiles.h"
#include "../Hydrology/Flow.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <utility>

namespace tsynth
{
namespace
{

// Samples every cell along the lines ("every cell" in the measures' definitions).
constexpr double kSampleSpacing = 1.0;
// Floor samples for the descent are a quarter patch apart.
constexpr double kDescentSpacingPatches = 0.25;
// A reference prominence below a centimetre is no relief (a plane's rounding
// error is micrometres): the ratios would divide by noise.
constexpr double kMinReferenceMetres = 0.01;

double featureSign(FeatureType type)
{
  return type == FeatureType::Ridge ? 1.0 : -1.0;
}

bool hasChains(const FeatureGraph& g, FeatureType type)
{
  return std::any_of(g.chains.begin(),
    g.chains.end(),
    [type](const FeatureChain& c) { return c.type == type && c.points.size() >= 2; });
}

// Calls f(point, normalOk, normal) every kSampleSpacing cells along each chain of `type`.
template<typename F>
void forEachSample(const FeatureGraph& g, FeatureType type, F&& f)
{
  for (const FeatureChain& c : g.chains)
  {
    if (c.type != type || c.points.size() < 2)
    {
      continue;
    }
    const ChainPath path(c.points);
    for (double s = 0.0; s <= path.length(); s += kSampleSpacing)
    {
      Point2 n;
      const bool ok = path.normal(s, n);
      f(path.at(s), ok, n);
    }
  }
}

void appendProminence(const Heightfield& hf,
  const FeatureGraph& g,
  FeatureType type,
  double distance,
  std::vector<double>& out)
{
  const double sign = featureSign(type);
  forEachSample(g,
    type,
    [&](const Point2& p, bool ok, const Point2& n)
    {
      if (!ok)
      {
        return;
      }
      const double centre = sampleBilinear(hf, p.x, p.y);
      const double left = sampleBilinear(hf, p.x + distance * n.x, p.y + distance * n.y);
      const double right = sampleBilinear(hf, p.x - distance * n.x, p.y - distance * n.y);
      if (!std::isnan(centre) && !std::isnan(left) && !std::isnan(right))
      {
        out.push_back(sign * (centre - 0.5 * (left + right)));
      }
    });
}

double median(std::vector<double> v)
{
  if (v.empty())
  {
    return LandformMeasures::kNaN;
  }
  const std::size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(mid), v.end());
  const double upper = v[mid];
  if (v.size() % 2 != 0)
  {
    return upper;
  }
  const double lower = *std::max_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(mid));
  return 0.5 * (lower + upper);
}

void checkGrid(const FeatureGraph& g, const Heightfield& hf, const char* what)
{
  if (g.width > 0 && (g.width != hf.width || g.height != hf.height))
  {
    throw Error(std::string("The ") + what + " lines are on a " + std::to_string(g.width) + " x " +
      std::to_string(g.height) + " grid but their heightfield is " + std::to_string(hf.width) +
      " x " + std::to_string(hf.height) + "; give the lines in the heightfield's cells.");
  }
}

void checkOptions(const LandformOptions& o)
{
  if (!(o.patchSize > 0.0) || !(o.tolerance >= 0.0) || !(o.drainageStripFraction >= 0.0) ||
    !(o.sheddingPatchWidths > 0.0) || !(o.descentSlack >= 0.0) || std::isnan(o.distance))
  {
    throw Error("Landform options out of range: the patch size and shedding bar must be "
                "positive, the tolerance, strip fraction and descent slack zero or more.");
  }
}

// Calls f(cell index) for the valid cells within `radius` of p (always the nearest cell).
template<typename F>
void forEachCellNear(const Heightfield& hf, const Point2& p, double radius, F&& f)
{
  const int ci = static_cast<int>(std::lround(p.x));
  const int cj = static_cast<int>(std::lround(p.y));
  const int i0 = std::max(0, static_cast<int>(std::floor(p.x - radius)));
  const int i1 = std::min(hf.width - 1, static_cast<int>(std::ceil(p.x + radius)));
  const int j0 = std::max(0, static_cast<int>(std::floor(p.y - radius)));
  const int j1 = std::min(hf.height - 1, static_cast<int>(std::ceil(p.y + radius)));
  for (int j = j0; j <= j1; ++j)
  {
    for (int i = i0; i <= i1; ++i)
    {
      const bool near = (i - p.x) * (i - p.x) + (j - p.y) * (j - p.y) <= radius * radius;
      const std::size_t k = hf.index(i, j);
      if ((near || (i == ci && j == cj)) && isUsableCell(hf, k))
      {
        f(k);
      }
    }
  }
}

double floorNear(const Heightfield& hf, const Point2& p, double radius)
{
  double lowest = std::numeric_limits<double>::infinity();
  forEachCellNear(
    hf, p, radius, [&](std::size_t k) { lowest = std::min<double>(lowest, hf.z[k]); });
  return lowest;
}

// Mann-Whitney AUC: P(ridge > valley) + P(ridge == valley) / 2.
double aboveProbability(const std::vector<double>& ridges, std::vector<double> valleys)
{
  std::sort(valleys.begin(), valleys.end());
  double wins = 0.0;
  for (const double r : ridges)
  {
    const auto lo = std::lower_bound(valleys.begin(), valleys.end(), r);
    const auto hi = std::upper_bound(lo, valleys.end(), r);
    wins += static_cast<double>(lo - valleys.begin()) + 0.5 * static_cast<double>(hi - lo);
  }
  return wins / (static_cast<double>(ridges.size()) * static_cast<double>(valleys.size()));
}

std::vector<double> lineHeights(const Heightfield& hf, const FeatureGraph& g, FeatureType type)
{
  std::vector<double> out;
  forEachSample(g,
    type,
    [&](const Point2& p, bool, const Point2&)
    {
      const double z = sampleBilinear(hf, p.x, p.y);
      if (!std::isnan(z))
      {
        out.push_back(z);
      }
    });
  return out;
}

// ----- Valley networks oriented downstream -----

// A stretch of a valley chain traversed downstream, between arc positions
// `from` (upstream) and `to` on chain `chain`.
struct Run
{
  std::size_t chain = 0;
  double from = 0.0;
  double to = 0.0;
  int upNode = -1; // -1: starts mid-chain (the top of a closed loop)
  int downNode = -1;
  double length() const { return std::abs(to - from); }
  double arcAt(double t) const { return to >= from ? from + t : from - t; }
};

struct ValleyNetwork
{
  std::vector<ChainPath> paths; // per chain of the graph (empty for non-valleys)
  std::vector<Run> runs;
  std::vector<double> headDistance; // per node: longest sketched path from a head, cells
  std::vector<int> outgoing;        // per node: the run leaving it downstream, -1 at outlets
  Point2 at(const Run& r, double t) const { return paths[r.chain].at(r.arcAt(t)); }
  double upstreamLength(const Run& r, double t) const
  {
    return (r.upNode >= 0 ? headDistance[static_cast<std::size_t>(r.upNode)] : 0.0) + t;
  }
};

std::vector<std::size_t> valleyChains(const FeatureGraph& g)
{
  std::vector<std::size_t> out;
  for (std::size_t c = 0; c < g.chains.size(); ++c)
  {
    const FeatureChain& ch = g.chains[c];
    if (ch.type != FeatureType::Valley || ch.points.size() < 2)
    {
      continue;
    }
    const int n = static_cast<int>(g.nodes.size());
    if (ch.from < 0 || ch.to < 0 || ch.from >= n || ch.to >= n)
    {
      throw Error("Feature chain " + std::to_string(c) +
        " refers to a node that does not exist; "
        "build the graph with the feature tools.");
    }
    out.push_back(c);
  }
  return out;
}

// Floor height of every node (lowest valid height within
// `tolerance`; +infinity if none), which orders nodes downstream.
std::vector<double> nodeFloors(const FeatureGraph& g, const Heightfield& terrain, double tolerance)
{
  std::vector<double> floors(g.nodes.size(), std::numeric_limits<double>::infinity());
  for (std::size_t v = 0; v < g.nodes.size(); ++v)
  {
    floors[v] = floorNear(terrain, g.nodes[v].position, tolerance);
  }
  return floors;
}

ValleyNetwork orientValleys(const FeatureGraph& g, const Heightfield& terrain, double tolerance)
{
  ValleyNetwork net;
  const std::vector<std::size_t> chains = valleyChains(g);
  net.paths.reserve(g.chains.size());
  for (std::size_t c = 0; c < g.chains.size(); ++c)
  {
    net.paths.emplace_back(
      g.chains[c].type == FeatureType::Valley ? g.chains[c].points : std::vector<Point2>{});
  }
  // Downstream means towards the lower (floor, id): a strict order, so no cycle.
  const std::vector<double> floors = nodeFloors(g, terrain, tolerance);
  auto lower = [&](int a, int b)
  {
    const double fa = floors[static_cast<std::size_t>(a)];
    const double fb = floors[static_cast<std::size_t>(b)];
    return fa < fb || (fa == fb && a < b);
  };
  for (const std::size_t c : chains)
  {
    const FeatureChain& ch = g.chains[c];
    const double len = net.paths[c].length();
    if (ch.from == ch.to) // a closed loop drains both ways from its far side
    {
      net.runs.push_back({ c, 0.5 * len, 0.0, -1, ch.from });
      net.runs.push_back({ c, 0.5 * len, len, -1, ch.to });
    }
    else if (lower(ch.from, ch.to))
    {
      net.runs.push_back({ c, len, 0.0, ch.to, ch.from });
    }
    else
    {
      net.runs.push_back({ c, 0.0, len, ch.from, ch.to });
    }
  }
  // Longest path from a head, upstream nodes first.
  std::vector<int> order(g.nodes.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return lower(b, a); });
  std::vector<std::vector<std::size_t>> incoming(g.nodes.size());
  net.outgoing.assign(g.nodes.size(), -1);
  for (std::size_t r = 0; r < net.runs.size(); ++r)
  {
    incoming[static_cast<std::size_t>(net.runs[r].downNode)].push_back(r);
    const int up = net.runs[r].upNode;
    if (up >= 0 && net.outgoing[static_cast<std::size_t>(up)] < 0)
    {
      net.outgoing[static_cast<std::size_t>(up)] = static_cast<int>(r);
    }
  }
  net.headDistance.assign(g.nodes.size(), 0.0);
  for (const int v : order)
  {
    double& head = net.headDistance[static_cast<std::size_t>(v)];
    for (const std::size_t r : incoming[static_cast<std::size_t>(v)])
    {
      head = std::max(head, net.upstreamLength(net.runs[r], net.runs[r].length()));
    }
  }
  return net;
}

// The point `delta` cells downstream of position t on run r, following the
// network; false if the outlet comes first.
bool pointDownstream(const ValleyNetwork& net, std::size_t r, double t, double delta, Point2& out)
{
  for (;;)
  {
    const Run& run = net.runs[r];
    if (t + delta <= run.length())
    {
      out = net.at(run, t + delta);
      return true;
    }
    delta -= run.length() - t;
    const int next = net.outgoing[static_cast<std::size_t>(run.downNode)];
    if (next < 0)
    {
      return false;
    }
    r = static_cast<std::size_t>(next);
    t = 0.0;
  }
}

// ----- Flow on the filled terrain -----

struct Drainage
{
  std::vector<std::uint32_t> accumulation;
  Heightfield usable; // the terrain with every unusable cell masked (for the cell searches)
};

Drainage drainageOf(const Heightfield& terrain)
{
  Drainage d;
  d.usable = fillDepressions(terrain);
  d.usable.valid.assign(terrain.size(), 0);
  for (std::size_t k = 0; k < terrain.size(); ++k)
  {
    d.usable.valid[k] = isUsableCell(terrain, k) ? 1 : 0;
  }
  const std::vector<std::int8_t> dir = flowDirections(d.usable);
  d.accumulation = flowAccumulation(dir, terrain.width, terrain.height, &d.usable.valid);
  return d;
}

std::uint32_t largestNear(const Drainage& d, const Point2& p, double radius, bool& any)
{
  std::uint32_t best = 0;
  any = false;
  forEachCellNear(d.usable,
    p,
    radius,
    [&](std::size_t k)
    {
      any = true;
      best = std::max(best, d.accumulation[k]);
    });
  return best;
}

void measureDrainage(const Drainage& d,
  const ValleyNetwork& net,
  const LandformOptions& o,
  LandformMeasures& m)
{
  const double strip = o.drainageStripFraction * o.patchSize;
  std::size_t drained = 0;
  for (const Run& run : net.runs)
  {
    for (double t = 0.0; t <= run.length(); t += kSampleSpacing)
    {
      bool any = false;
      const double acc = largestNear(d, net.at(run, t), o.tolerance, any);
      if (any)
      {
        ++m.drainageSamples;
        drained += acc >= strip * net.upstreamLength(run, t) ? 1 : 0;
      }
    }
  }
  if (m.drainageSamples > 0)
  {
    m.valleyDrainage = static_cast<double>(drained) / static_cast<double>(m.drainageSamples);
  }
  else
  {
    m.notes["valleyDrainage"] = "no valley sample lies on valid terrain";
  }
}

void measureShedding(const Drainage& d,
  const FeatureGraph& sketch,
  const LandformOptions& o,
  LandformMeasures& m)
{
  const double small = o.sheddingPatchWidths * o.patchSize;
  std::size_t shed = 0;
  forEachSample(sketch,
    FeatureType::Ridge,
    [&](const Point2& p, bool, const Point2&)
    {
      bool any = false;
      const double acc = largestNear(d, p, o.tolerance, any);
      if (any)
      {
        ++m.sheddingSamples;
        shed += acc <= small ? 1 : 0;
      }
    });
  if (m.sheddingSamples > 0)
  {
    m.ridgeShedding = static_cast<double>(shed) / static_cast<double>(m.sheddingSamples);
  }
  else
  {
    m.notes["ridgeShedding"] = "no ridge sample lies on valid terrain";
  }
}

void measureDescent(const Heightfield& terrain,
  const ValleyNetwork& net,
  const LandformOptions& o,
  LandformMeasures& m)
{
  const double spacing = kDescentSpacingPatches * o.patchSize;
  std::size_t descending = 0;
  for (std::size_t r = 0; r < net.runs.size(); ++r)
  {
    for (double t = 0.0; t <= net.runs[r].length(); t += spacing)
    {
      Point2 below;
      if (!pointDownstream(net, r, t, spacing, below))
      {
        break;
      }
      const double up = floorNear(terrain, net.at(net.runs[r], t), o.tolerance);
      const double down = floorNear(terrain, below, o.tolerance);
      if (std::isinf(up) || std::isinf(down))
      {
        continue; // no valid cell near one of them
      }
      ++m.descentPairs;
      descending += down <= up + o.descentSlack ? 1 : 0;
    }
  }
  if (m.descentPairs > 0)
  {
    m.valleyDescent = static_cast<double>(descending) / static_cast<double>(m.descentPairs);
  }
  else
  {
    m.notes["valleyDescent"] = "no valley reaches a quarter patch (" + std::to_string(spacing) +
      " cells) above its outlet on valid terrain";
  }
}

// ----- Prominence and ratios -----

void measureProminence(const Heightfield& terrain,
  const FeatureGraph& sketch,
  FeatureType type,
  double distance,
  double& value,
  std::size_t& samples,
  LandformMeasures& m)
{
  std::vector<double> v;
  appendProminence(terrain, sketch, type, distance, v);
  samples = v.size();
  value = median(std::move(v));
  if (samples == 0)
  {
    m.notes[type == FeatureType::Ridge ? "ridgeProminence" : "valleyDepth"] = std::string("no ") +
      (type == FeatureType::Ridge ? "ridge" : "valley") +
      " sample has valid heights on the line and at distance " + std::to_string(distance) +
      " cells on both sides";
  }
}

void measureRatio(double value,
  const std::vector<const Heightfield*>& exemplars,
  const std::vector<const FeatureGraph*>& lines,
  FeatureType type,
  double distance,
  double& reference,
  double& ratio,
  LandformMeasures& m)
{
  const bool ridge = type == FeatureType::Ridge;
  const std::string field = ridge ? "ridgeProminenceRatio" : "valleyDepthRatio";
  const std::string what = ridge ? "ridge" : "valley";
  if (std::isnan(value))
  {
    m.notes[field] = "no " + what + " figure on the terrain to compare";
    return;
  }
  if (exemplars.empty())
  {
    m.notes[field] = "no exemplar given";
    return;
  }
  reference = typicalProminence(exemplars, lines, type, distance);
  if (std::isnan(reference))
  {
    m.notes[field] = "the exemplars' own lines have no " + what + " sample with valid heights";
  }
  else if (reference < kMinReferenceMetres)
  {
    m.notes[field] = "the exemplars' own " + what + "s stand " + std::to_string(reference) +
      " m from their surroundings: no relief to compare with";
  }
  else
  {
    ratio = value / reference;
  }
}

void noteMissing(LandformMeasures& m,
  const std::vector<std::string>& fields,
  const std::string& why)
{
  for (const std::string& f : fields)
  {
    m.notes[f] = why;
  }
}

} // namespace

double typicalProminence(const Heightfield& heights,
  const FeatureGraph& lines,
  FeatureType type,
  double distance)
{
  return typicalProminence(std::vector<const Heightfield*>{ &heights },
    std::vector<const FeatureGraph*>{ &lines },
    type,
    distance);
}

double typicalProminence(const std::vector<const Heightfield*>& exemplars,
  const std::vector<const FeatureGraph*>& lines,
  FeatureType type,
  double distance)
{
  if (exemplars.size() != lines.size())
  {
    throw Error("Give one feature graph per exemplar (" + std::to_string(exemplars.size()) +
      " exemplars, " + std::to_string(lines.size()) + " graphs).");
  }
  std::vector<double> v;
  for (std::size_t e = 0; e < exemplars.size(); ++e)
  {
    checkGrid(*lines[e], *exemplars[e], "exemplar's");
    appendProminence(*exemplars[e], *lines[e], type, distance, v);
  }
  return median(std::move(v));
}

FeatureGraph ownFeatureLines(const Heightfield& dem, const PpaOptions& options)
{
  FeatureGraph lines = extractFeatures(dem, FeatureType::Ridge, options).graph;
  appendGraph(lines, extractFeatures(dem, FeatureType::Valley, options).graph);
  return lines;
}

LandformMeasures evaluateLandforms(const Heightfield& terrain,
  const FeatureGraph& sketch,
  const std::vector<const Heightfield*>& exemplars,
  const std::vector<const FeatureGraph*>& exemplarLines,
  const LandformOptions& o)
{
  checkOptions(o);
  checkGrid(sketch, terrain, "sketch");
  if (exemplars.size() != exemplarLines.size())
  {
    throw Error("Give one feature graph per exemplar (" + std::to_string(exemplars.size()) +
      " exemplars, " + std::to_string(exemplarLines.size()) + " graphs).");
  }
  for (std::size_t e = 0; e < exemplars.size(); ++e)
  {
    checkGrid(*exemplarLines[e], *exemplars[e], "exemplar's");
  }
  LandformMeasures m;
  const double distance = o.crossDistance();
  const bool ridges = hasChains(sketch, FeatureType::Ridge);
  const bool valleys = hasChains(sketch, FeatureType::Valley);
  if (!ridges)
  {
    noteMissing(m,
      { "ridgeProminence", "ridgeProminenceRatio", "ridgeOverValley", "ridgeShedding" },
      "the sketch has no ridge line");
  }
  if (!valleys)
  {
    noteMissing(m,
      { "valleyDepth", "valleyDepthRatio", "ridgeOverValley", "valleyDrainage", "valleyDescent" },
      "the sketch has no valley line");
  }
  if (ridges)
  {
    measureProminence(
      terrain, sketch, FeatureType::Ridge, distance, m.ridgeProminence, m.ridgeSamples, m);
    measureRatio(m.ridgeProminence,
      exemplars,
      exemplarLines,
      FeatureType::Ridge,
      distance,
      m.referenceRidgeProminence,
      m.ridgeProminenceRatio,
      m);
  }
  if (valleys)
  {
    measureProminence(
      terrain, sketch, FeatureType::Valley, distance, m.valleyDepth, m.valleySamples, m);
    measureRatio(m.valleyDepth,
      exemplars,
      exemplarLines,
      FeatureType::Valley,
      distance,
      m.referenceValleyDepth,
      m.valleyDepthRatio,
      m);
  }
  if (ridges && valleys)
  {
    const std::vector<double> r = lineHeights(terrain, sketch, FeatureType::Ridge);
    const std::vector<double> v = lineHeights(terrain, sketch, FeatureType::Valley);
    if (r.empty() || v.empty())
    {
      m.notes["ridgeOverValley"] = "no ridge or no valley sample lies on valid terrain";
    }
    else
    {
      m.ridgeOverValley = aboveProbability(r, v);
    }
  }
  if (ridges || valleys)
  {
    const Drainage d = drainageOf(terrain);
    if (ridges)
    {
      measureShedding(d, sketch, o, m);
    }
    if (valleys)
    {
      const ValleyNetwork net = orientValleys(sketch, terrain, o.tolerance);
      measureDrainage(d, net, o, m);
      measureDescent(terrain, net, o, m);
    }
  }
  return m;
}

} // namespace tsynth
