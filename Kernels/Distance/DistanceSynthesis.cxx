#include "DistanceSynthesis.h"

#include "../Core/Error.h"
#include "../Core/Grid.h"
#include "../Core/Random.h"
#include "../Features/FeatureGraph.h"
#include "DistanceMemory.h"
#include "LatticeSearch.h"

#include <omp.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <mutex>
#include <sstream>

namespace tsynth
{
namespace
{

using detail::Field;
using detail::kNone;
using detail::kUnreached;
using detail::run;
using detail::Search;
using detail::Source;

// Above this bias the powers of small heights underflow double precision.
constexpr double kMaxBlendBias = 64.0;
constexpr int kMaxProfileBins = 1 << 20;
constexpr std::uint64_t kRidgeStream = 0x5249444745534545ULL;
// Random cells tried per requested ridge before giving up (unreached cells are skipped).
constexpr int kRidgeAttemptsPerRidge = 8;
// Features searched in parallel between two deterministic blends (bounds memory).
constexpr std::size_t kFeaturesPerBatch = 128;
constexpr std::uint16_t kMaxContributors = std::numeric_limits<std::uint16_t>::max();
// Progress shares of the stages.
constexpr double kProgressApproximate = 0.1;
constexpr double kProgressRidges = 0.2;

void require(bool ok, const std::string& message)
{
  if (!ok)
  {
    throw Error(message);
  }
}

// Whether int id `id` (a cell, profile, feature) is one of `count`.
bool validId(std::int32_t id, std::size_t count)
{
  return id >= 0 && static_cast<std::size_t>(id) < count;
}

// This OpenMP thread's slot in per-thread arrays (omp_get_thread_num() is an int from 0).
std::size_t threadSlot()
{
  return static_cast<std::size_t>(omp_get_thread_num());
}

std::string number(double v)
{
  std::ostringstream s;
  s << v;
  return s.str();
}

void validateOptions(const DistanceOptions& o)
{
  require(std::isfinite(o.seaLevelScale) && o.seaLevelScale >= 0.0,
    "The sea-level scale s must be a number >= 0 (got " + number(o.seaLevelScale) + ").");
  require(o.blendBias >= 0.0 && o.blendBias <= kMaxBlendBias,
    "The blending bias b must be from 0 to 64 (got " + number(o.blendBias) + ").");
  require(o.seaLevelEpsilon >= 0.0 && std::isfinite(o.seaLevelEpsilon),
    "The sea-level threshold eps_s must be >= 0.");
  require(o.approximateFraction >= 0.0 && o.approximateFraction <= 1.0,
    "The approximate-terrain threshold p_f must be from 0 to 1.");
  require(o.minScaling > 0.0 && std::isfinite(o.minScaling),
    "The minimum scaling min t_s must be positive, so that every step raises the cost.");
  require(o.profileBins >= 2 && o.profileBins <= kMaxProfileBins,
    "The profile table needs from 2 to 2^20 bins.");
  require(o.profileScale > 0.0 && std::isfinite(o.profileScale),
    "The profile scale (cells per profile unit) must be positive.");
  require(o.ridgeCount >= 0, "The ridge count must be 0 or more.");
  require(
    o.ridgeFraction > 0.0 && o.ridgeFraction <= 1.0, "The ridge cost fraction must be in (0, 1].");
  require(o.cellSize > 0.0 && std::isfinite(o.cellSize), "The cell size must be positive metres.");
  require(o.heightScale > 0.0 && std::isfinite(o.heightScale),
    "The height scale must be positive metres per cost unit.");
}

// Every generator node with its feature, costs filled from fBm where NaN.
std::vector<std::vector<Source>> gatherSources(const DistanceInputs& in, const DistanceOptions& o)
{
  const std::size_t n = cellCount(in.width, in.height);
  bool needFbm = false;
  std::size_t count = 0;
  for (std::size_t f = 0; f < in.features.size(); ++f)
  {
    for (const GeneratorNode& node : in.features[f].nodes)
    {
      require(validId(node.cell, n),
        "Feature " + std::to_string(f) + " has a generator outside the " +
          std::to_string(in.width) + "x" + std::to_string(in.height) + " grid.");
      require(node.profile == kNoProfile || validId(node.profile, in.profiles.size()),
        "Feature " + std::to_string(f) + " asks for profile " + std::to_string(node.profile) +
          " but there are " + std::to_string(in.profiles.size()) + " profiles.");
      require(!std::isinf(node.cost),
        "Feature " + std::to_string(f) + " has an infinite generator cost; give finite costs.");
      needFbm = needFbm || std::isnan(node.cost);
      ++count;
    }
  }
  require(
    count > 0, "There are no generators: draw at least one ridge stroke, poly-line or point.");
  const std::vector<float> fbm =
    needFbm ? fbmCosts(in.width, in.height, o.fbm, o.seed) : std::vector<float>();
  std::vector<std::vector<Source>> sources(in.features.size());
  for (std::size_t f = 0; f < in.features.size(); ++f)
  {
    for (const GeneratorNode& node : in.features[f].nodes)
    {
      const float cost = std::isnan(node.cost) ? byId(fbm, node.cell) : node.cost;
      sources[f].push_back({ node.cell, cost, node.profile, static_cast<std::int32_t>(f) });
    }
  }
  return sources;
}

// Region index per cell: the smallest region wins where they nest.
std::vector<std::int32_t> regionMap(const DistanceInputs& in)
{
  const std::size_t n = cellCount(in.width, in.height);
  std::vector<std::int32_t> regionOf(n, kNone);
  std::vector<std::size_t> order(in.regions.size());
  for (std::size_t r = 0; r < order.size(); ++r)
  {
    const DistanceRegion& region = in.regions[r];
    require(validId(region.feature, in.features.size()),
      "Region " + std::to_string(r) + " belongs to feature " + std::to_string(region.feature) +
        ", which does not exist.");
    require(region.profile == kNoProfile || validId(region.profile, in.profiles.size()),
      "Region " + std::to_string(r) + " asks for profile " + std::to_string(region.profile) +
        " but there are " + std::to_string(in.profiles.size()) + " profiles.");
    order[r] = r;
  }
  std::stable_sort(order.begin(),
    order.end(),
    [&](std::size_t a, std::size_t b)
    { return in.regions[a].cells.size() > in.regions[b].cells.size(); });
  for (const std::size_t r : order) // largest first, so smaller ones overwrite
  {
    for (const std::int32_t k : in.regions[r].cells)
    {
      require(validId(k, n), "Region " + std::to_string(r) + " has a cell outside the grid.");
      byId(regionOf, k) = static_cast<std::int32_t>(r);
    }
  }
  return regionOf;
}

std::vector<Source> flatten(const std::vector<std::vector<Source>>& perFeature,
  std::vector<std::size_t>& begin)
{
  std::vector<Source> flat;
  begin.assign(1, 0);
  for (const auto& feature : perFeature)
  {
    flat.insert(flat.end(), feature.begin(), feature.end());
    begin.push_back(flat.size());
  }
  return flat;
}

void reportProgress(const DistanceOptions& o, double fraction)
{
  tsynth::reportProgress(o.progress, fraction, "distance");
}

Lattice buildLattice(const DistanceInputs& in, const DistanceOptions& o)
{
  if (!in.nodeWeights.empty())
  {
    require(in.nodeWeights.size() == cellCount(in.width, in.height),
      "The edge-weight image has " + std::to_string(in.nodeWeights.size()) +
        " cells but the generators' grid is " + std::to_string(in.width) + "x" +
        std::to_string(in.height) + "; give an image of the same size.");
    return Lattice::fromNodeWeights(in.width, in.height, in.nodeWeights, o.sqrt2Diagonals);
  }
  LatticeOptions lo;
  lo.meanWeight = o.meanWeight;
  lo.roughness = o.roughness;
  lo.sqrt2Diagonals = o.sqrt2Diagonals;
  lo.seed = o.seed;
  return Lattice::random(in.width, in.height, lo);
}

// Drops generators at or above c_s (s < 1 clips them, §3.5); returns how many.
std::size_t clipGenerators(std::vector<std::vector<Source>>& sources, float seaCost)
{
  std::size_t clipped = 0;
  for (auto& feature : sources)
  {
    const std::size_t before = feature.size();
    feature.erase(
      std::remove_if(
        feature.begin(), feature.end(), [&](const Source& g) { return !(g.cost < seaCost); }),
      feature.end());
    clipped += before - feature.size();
  }
  return clipped;
}

// The smallest step a search can take must survive float rounding at the
// largest cost magnitude, or costs stop growing and flat sheets spread.
void requirePrecision(double largestCost, double smallestStep)
{
  if (!(largestCost * FLT_EPSILON < smallestStep) || !(largestCost < FLT_MAX))
  {
    throw Error("Costs up to " + number(largestCost) + " would swallow the smallest edge step " +
      number(smallestStep) +
      " in float precision; lower the generator costs or s, or raise mu_w - r or min t_s.");
  }
}

// Dendritic ridges (§4.1): random reached cells traced back along the least-cost
// path to their generator; the path joins that generator's feature. Cells inside
// regions are not started from, so crater bowls keep their own profile's shape.
std::size_t traceRidges(const DistanceOptions& o,
  const Field& approx,
  const std::vector<Source>& flat,
  const std::vector<std::int32_t>& regionOf,
  std::vector<std::vector<Source>>& perFeature,
  std::vector<std::vector<std::int32_t>>& ridges)
{
  const std::size_t n = approx.cost.size();
  std::vector<std::uint8_t> isGenerator(n, 0);
  for (const Source& g : flat)
  {
    byId(isGenerator, g.cell) = 1;
  }
  std::size_t added = 0;
  int traced = 0;
  const auto attempts = static_cast<std::uint64_t>(o.ridgeCount) * kRidgeAttemptsPerRidge;
  const auto fraction = static_cast<float>(o.ridgeFraction);
  for (std::uint64_t a = 0; a < attempts && traced < o.ridgeCount; ++a)
  {
    // A uniform draw in [0, 1) scaled to a cell: a double truncated to an index.
    const auto start = std::min(n - 1,
      static_cast<std::size_t>(seededUniform(o.seed, kRidgeStream, a) * static_cast<double>(n)));
    if (approx.cost[start] == kUnreached || isGenerator[start] || regionOf[start] != kNone)
    {
      continue;
    }
    ++traced;
    ridges.emplace_back();
    const Source& g = byId(flat, approx.source[start]);
    std::vector<Source>& feature = byId(perFeature, g.feature);
    for (std::int32_t k = static_cast<std::int32_t>(start); k != kNone && !byId(isGenerator, k);
         k = byId(approx.pred, k))
    {
      const float ca = byId(approx.cost, k);
      const float cost =
        o.ridgeCost == RidgeCost::ScaledRise ? g.cost + fraction * (ca - g.cost) : fraction * ca;
      feature.push_back({ k, cost, g.profile, g.feature });
      byId(isGenerator, k) = 1;
      ridges.back().push_back(k);
      ++added;
    }
  }
  return added;
}

// x^b by squaring when b is a whole number (the thesis's 3, 4, 8, 15), else pow.
class BiasPower
{
public:
  explicit BiasPower(double b)
    : b_(b)
    , whole_(b == std::floor(b))
  {
  }
  double operator()(double x) const
  {
    if (!whole_)
    {
      return std::pow(x, b_);
    }
    double result = 1.0;
    for (auto e = static_cast<unsigned>(b_); e != 0; e >>= 1)
    {
      if ((e & 1u) != 0)
      {
        result *= x;
      }
      x *= x;
    }
    return result;
  }

private:
  double b_;
  bool whole_;
};

struct Blend
{
  std::vector<double> num;
  std::vector<double> den;
  std::vector<std::uint16_t> contributors;
};

struct Visit
{
  std::uint32_t cell;
  float height; // (c_s - c) / c_s
  double power; // height^b
};

// One feature's bounded search (step 7a): halted within eps_s of c_s, or where
// the feature's height is below p_f of the approximate height. Returns true if
// the radix heap searched in the bucket queue's place.
bool featurePass(const Search& s,
  const DistanceOptions& o,
  const std::vector<float>& approxHeight,
  std::size_t first,
  std::size_t last,
  Field& field,
  std::vector<Visit>& visits)
{
  const float sea = s.seaCost;
  const auto haltCost = static_cast<float>(sea - o.seaLevelEpsilon);
  const auto pf = static_cast<float>(o.approximateFraction);
  const BiasPower power(o.blendBias);
  visits.clear();
  auto halt = [&](std::size_t u, float c)
  { return c >= haltCost || (sea - c) < pf * approxHeight[u]; };
  auto settle = [&](std::size_t u, float c)
  {
    const double hn = (static_cast<double>(sea) - c) / sea;
    visits.push_back({ static_cast<std::uint32_t>(u), static_cast<float>(hn), power(hn) });
  };
  const bool radix = run(o.queue, s, first, last, field, halt, settle, [&] { visits.clear(); });
  field.reset();
  return radix;
}

// Adds finished features to the blend in feature order (so the same sums on
// any thread count), each as soon as all before it are in, on whichever thread
// finished it: the blend overlaps the searches, and the visit buffers go back
// to a pool for later features while they are still in the cache.
class OrderedBlend
{
public:
  OrderedBlend(Blend& blend, DistanceTerrain& out)
    : blend_(blend)
    , out_(out)
  {
  }
  // A batch of count features follows, handed in by their index in it.
  void startBatch(std::size_t count)
  {
    next_ = 0;
    ready_.assign(count, {});
    done_.assign(count, 0);
    radix_.assign(count, 0);
  }
  std::vector<Visit> buffer()
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (pool_.empty())
    {
      return {};
    }
    std::vector<Visit> v = std::move(pool_.back());
    pool_.pop_back();
    return v;
  }
  // Hands in feature first + i, then blends whatever is ready in order, unless
  // another thread is at it (it will find feature i when it gets there).
  void finish(std::size_t i, std::vector<Visit>&& visits, bool radix)
  {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      ready_[i] = std::move(visits);
      radix_[i] = radix ? 1 : 0;
      done_[i] = 1;
    }
    while (readyToBlend() && blending_.try_lock())
    {
      blendReady();
      blending_.unlock(); // then look again: a feature may have come in meanwhile
    }
  }
  // After the batch's threads have joined: anything left (there should be none).
  void endBatch()
  {
    std::lock_guard<std::mutex> lock(blending_);
    blendReady();
    if (next_ != done_.size())
    {
      throw Error("Internal error: a feature's search did not finish.");
    }
  }

private:
  bool readyToBlend()
  {
    std::lock_guard<std::mutex> lock(mutex_);
    return next_ < done_.size() && done_[next_] != 0;
  }
  void blendReady()
  {
    while (true)
    {
      std::vector<Visit> visits;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        if (next_ == done_.size() || done_[next_] == 0)
        {
          return;
        }
        visits = std::move(ready_[next_]);
        out_.radixSearches += radix_[next_];
      }
      add(visits);
      std::lock_guard<std::mutex> lock(mutex_);
      pool_.push_back(std::move(visits));
      ++next_;
    }
  }
  void add(const std::vector<Visit>& visits)
  {
    for (const Visit& v : visits)
    {
      blend_.num[v.cell] += v.power * v.height;
      blend_.den[v.cell] += v.power;
      blend_.contributors[v.cell] = static_cast<std::uint16_t>(
        std::min<int>(blend_.contributors[v.cell] + 1, kMaxContributors));
    }
    out_.featureVisits += visits.size();
  }

  Blend& blend_;
  DistanceTerrain& out_;
  std::mutex mutex_;     // guards all below but the blend itself
  std::mutex blending_;  // held by the thread adding to the blend
  std::size_t next_ = 0; // the next feature of the batch to add
  std::vector<std::vector<Visit>> ready_;
  std::vector<std::uint8_t> done_;
  std::vector<std::uint8_t> radix_;
  std::vector<std::vector<Visit>> pool_;
};

void blendFeatures(const Search& s,
  const DistanceOptions& o,
  const std::vector<float>& approxHeight,
  const std::vector<std::size_t>& begin,
  Blend& blend,
  DistanceTerrain& out)
{
  const std::size_t features = begin.size() - 1;
  const std::size_t n = approxHeight.size();
  const int threads = omp_get_max_threads();
  std::vector<Field> fields;
  for (int t = 0; t < threads; ++t)
  {
    fields.emplace_back(n, o.queue == DijkstraQueue::Bucket);
  }
  OrderedBlend ordered(blend, out);
  for (std::size_t batch = 0; batch < features; batch += kFeaturesPerBatch)
  {
    const std::size_t count = std::min(kFeaturesPerBatch, features - batch);
    ordered.startBatch(count);
#pragma omp parallel for schedule(dynamic, 1)
    for (std::size_t i = 0; i < count; ++i)
    {
      const std::size_t f = batch + i;
      std::vector<Visit> visits = ordered.buffer();
      const bool radix =
        featurePass(s, o, approxHeight, begin[f], begin[f + 1], fields[threadSlot()], visits);
      ordered.finish(i, std::move(visits), radix);
    }
    ordered.endBatch();
    reportProgress(o,
      kProgressRidges +
        (1.0 - kProgressRidges) * static_cast<double>(batch + count) /
          static_cast<double>(features));
  }
}

Heightfield makeField(int width, int height, const DistanceOptions& o)
{
  Heightfield hf(width, height, 0.0f);
  hf.cellX = o.cellSize;
  hf.cellY = o.cellSize;
  hf.cellSizeKnown = true;
  return hf;
}

} // namespace

DistanceTerrain synthesiseByDistance(const DistanceInputs& in, const DistanceOptions& o)
{
  validateOptions(o);
  require(in.width >= 1 && in.height >= 1, "The generators' grid must have at least one cell.");
  checkDistanceMemory(in, o);
  const Lattice lattice = buildLattice(in, o);
  std::vector<std::vector<Source>> perFeature = gatherSources(in, o);
  const std::vector<std::int32_t> regionOf = regionMap(in);

  DistanceTerrain out;
  float maxCost = -std::numeric_limits<float>::infinity();
  float minCost = std::numeric_limits<float>::infinity();
  for (const auto& feature : perFeature)
  {
    for (const Source& g : feature)
    {
      maxCost = std::max(maxCost, g.cost);
      minCost = std::min(minCost, g.cost);
    }
  }
  const double seaCost = o.seaLevelScale * maxCost; // eq. 3.1
  require(seaCost > 0.0,
    "The sea-level cost c_s = s * c_max is " + number(seaCost) +
      "; it must be positive: raise s or give some generator a positive cost.");
  out.seaLevelCost = seaCost;
  out.maxGeneratorCost = maxCost;
  const std::size_t clipped = clipGenerators(perFeature, static_cast<float>(seaCost));
  if (clipped > 0)
  {
    out.warnings.push_back(std::to_string(clipped) +
      " generator nodes cost c_s or more and are clipped (s < 1 hides them, thesis §3.5).");
  }

  std::vector<ScalingFunction> scaling;
  std::vector<detail::ScalingBounds> scalingBounds;
  double smallestScaling = 1.0;
  for (std::size_t p = 0; p < in.profiles.size(); ++p)
  {
    try
    {
      scaling.push_back(ScalingFunction::fromProfile(in.profiles[p],
        seaCost,
        lattice.meanWeight(),
        o.minScaling,
        o.profileBins,
        o.profileScale));
    }
    catch (const Error& e)
    {
      throw Error("Profile " + std::to_string(p) + ": " + e.what());
    }
    smallestScaling = std::min(smallestScaling, static_cast<double>(scaling.back().smallest()));
    scalingBounds.push_back({ scaling.back().smallest(), scaling.back().largest() });
  }
  requirePrecision(std::max(seaCost, std::fabs(static_cast<double>(minCost))),
    lattice.minWeight() * smallestScaling);
  reportProgress(o, 0.0);

  std::vector<std::size_t> begin;
  std::vector<Source> flat = flatten(perFeature, begin);
  const std::size_t n = lattice.size();
  Field approx(n, o.ridgeCount > 0 || o.queue == DijkstraQueue::Bucket);
  auto never = [](std::size_t, float) { return false; };
  auto ignore = [](std::size_t, float) {};
  auto approximatePass = [&]()
  {
    const Search s{
      lattice, scaling, scalingBounds, flat, regionOf, in.regions, static_cast<float>(seaCost)
    };
    out.radixSearches += run(o.queue, s, 0, flat.size(), approx, never, ignore, [] {}) ? 1 : 0;
  };
  approximatePass();
  reportProgress(o, kProgressApproximate);
  if (o.ridgeCount > 0)
  {
    out.ridgeNodes = traceRidges(o, approx, flat, regionOf, perFeature, out.ridges);
    flat = flatten(perFeature, begin);
    approx.reset();
    approximatePass();
  }
  reportProgress(o, kProgressRidges);
  for (std::size_t f = 0; f + 1 < begin.size(); ++f)
  {
    out.features += begin[f + 1] > begin[f] ? 1 : 0;
  }
  require(
    out.features > 0, "Every generator costs c_s or more, so nothing is above sea level; raise s.");
  out.generators = flat.size();

  std::vector<float> approxHeight(n, 0.0f); // c_s - C_a, 0 where unreached
  out.approximate = makeField(in.width, in.height, o);
  for (std::size_t k = 0; k < n; ++k)
  {
    approxHeight[k] =
      approx.cost[k] == kUnreached ? 0.0f : static_cast<float>(seaCost) - approx.cost[k];
    out.approximate.z[k] = static_cast<float>(approxHeight[k] * o.heightScale);
  }
  out.heights = makeField(in.width, in.height, o);
  if (o.approximateOnly)
  {
    out.heights.z = out.approximate.z;
    out.contributors.assign(n, 0);
    reportProgress(o, 1.0);
    return out;
  }
  Blend blend{
    std::vector<double>(n, 0.0), std::vector<double>(n, 0.0), std::vector<std::uint16_t>(n, 0)
  };
  const Search s{
    lattice, scaling, scalingBounds, flat, regionOf, in.regions, static_cast<float>(seaCost)
  };
  blendFeatures(s, o, approxHeight, begin, blend, out);
  for (std::size_t k = 0; k < n; ++k)
  {
    const double h = blend.den[k] > 0.0 ? blend.num[k] / blend.den[k] * seaCost : 0.0; // eq. 3.7
    out.heights.z[k] = static_cast<float>(h * o.heightScale);
  }
  out.contributors = std::move(blend.contributors);
  return out;
}

} // namespace tsynth
