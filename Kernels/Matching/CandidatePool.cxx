#include "CandidatePool.h"

#include "../Core/ContentHash.h"
#include "../Core/Error.h"
#include "../Core/Grid.h"
#include "../Features/Ppa.h"
#include "../Features/Profiles.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

namespace tsynth
{
namespace
{

// Point at arc length s along a polyline, and the index of the segment it is on.
Point2 pointAt(const std::vector<Point2>& pts, const std::vector<double>& arc, double s)
{
  const auto it = std::lower_bound(arc.begin(), arc.end(), s);
  // lower_bound's offset is a signed count, never negative.
  const std::size_t k =
    std::clamp<std::size_t>(static_cast<std::size_t>(it - arc.begin()), 1, pts.size() - 1);
  const double len = arc[k] - arc[k - 1];
  const double t = len > 0.0 ? std::clamp((s - arc[k - 1]) / len, 0.0, 1.0) : 0.0;
  return { pts[k - 1].x + t * (pts[k].x - pts[k - 1].x),
    pts[k - 1].y + t * (pts[k].y - pts[k - 1].y) };
}

// Where a polyline, walked from arc length s in direction dir (+1/-1), first
// lies `radius` away from its point at s (or its end).
ControlPoint armAlong(const std::vector<Point2>& pts,
  const std::vector<double>& arc,
  double s,
  int dir,
  double radius,
  int chain)
{
  const Point2 o = pointAt(pts, arc, s);
  ControlPoint cp;
  cp.chain = chain;
  cp.position = dir > 0 ? pts.back() : pts.front();
  const double step = 0.25;
  for (double t = s + dir * step; t >= 0.0 && t <= arc.back(); t += dir * step)
  {
    const Point2 q = pointAt(pts, arc, t);
    if (std::hypot(q.x - o.x, q.y - o.y) >= radius)
    {
      cp.position = q;
      cp.reached = true;
      break;
    }
  }
  cp.angle = std::atan2(cp.position.y - o.y, cp.position.x - o.x);
  return cp;
}

struct SiteProfiles
{
  std::vector<float> angle; // exemplar frame
  std::vector<std::array<float, kAlongSamples>> along;
  std::vector<std::array<float, kAcrossSamples>> across;
};

// Straight-line profiles from the centre to each arm's end and across it there,
// relative to the centre height; NaN where the field is invalid or outside.
SiteProfiles sampleSite(const FeatureSite& site, const Heightfield& hf, int patchSize)
{
  SiteProfiles p;
  const float base = sampleBilinear(hf, site.centre.x, site.centre.y);
  const double half = 0.25 * patchSize;
  const std::size_t n = std::min<std::size_t>(site.arms.size(), kMaxArms);
  for (std::size_t a = 0; a < n; ++a)
  {
    const ControlPoint& cp = site.arms[a];
    p.angle.push_back(static_cast<float>(cp.angle));
    std::array<float, kAlongSamples> al{};
    for (std::size_t k = 0; k < al.size(); ++k)
    {
      const double t = static_cast<double>(k) / (kAlongSamples - 1);
      al[k] = sampleBilinear(hf,
                site.centre.x + t * (cp.position.x - site.centre.x),
                site.centre.y + t * (cp.position.y - site.centre.y)) -
        base;
    }
    std::array<float, kAcrossSamples> ac{};
    const double nx = -std::sin(cp.angle);
    const double ny = std::cos(cp.angle);
    for (std::size_t k = 0; k < ac.size(); ++k)
    {
      const double d = half * (1.0 - 2.0 * static_cast<double>(k) / (kAcrossSamples - 1));
      ac[k] = sampleBilinear(hf, cp.position.x + d * nx, cp.position.y + d * ny) - base;
    }
    p.along.push_back(al);
    p.across.push_back(ac);
  }
  return p;
}

// 1 where a square of half-side r around (x, y) lies inside and on valid cells.
class FootprintCheck
{
public:
  explicit FootprintCheck(const Heightfield& hf)
    : w_(hf.width)
    , h_(hf.height)
    , sat_(cellCount(hf.width + 1, hf.height + 1), 0)
  {
    for (int j = 0; j < h_; ++j)
    {
      long row = 0;
      for (int i = 0; i < w_; ++i)
      {
        row += hf.isValid(i, j) ? 0 : 1;
        sat_[at(i + 1, j + 1)] = sat_[at(i + 1, j)] + row;
      }
    }
  }
  bool clear(double x, double y, int r) const
  {
    const int i0 = static_cast<int>(std::floor(x)) - r;
    const int j0 = static_cast<int>(std::floor(y)) - r;
    const int i1 = static_cast<int>(std::ceil(x)) + r + 1;
    const int j1 = static_cast<int>(std::ceil(y)) + r + 1;
    if (i0 < 0 || j0 < 0 || i1 > w_ || j1 > h_)
    {
      return false;
    }
    return sat_[at(i1, j1)] - sat_[at(i0, j1)] - sat_[at(i1, j0)] + sat_[at(i0, j0)] == 0;
  }

private:
  std::size_t at(int i, int j) const { return rowMajor(i, j, w_ + 1); }
  int w_;
  int h_;
  std::vector<long> sat_;
};

// First cell of the patch window around a centre: windows of side `size`
// start at round(c) - size / 2, for the pool and the queries alike.
int windowStart(double centre, int size)
{
  return static_cast<int>(std::lround(centre)) - size / 2;
}

// Means of valid cells over axis-aligned blocks, from summed-area tables.
class BlockMeans
{
public:
  explicit BlockMeans(const Heightfield& hf)
    : w_(hf.width)
    , h_(hf.height)
    , sum_(cellCount(hf.width + 1, hf.height + 1), 0.0)
    , count_(sum_.size(), 0.0)
  {
    for (int j = 0; j < h_; ++j)
    {
      double rs = 0.0;
      double rc = 0.0;
      for (int i = 0; i < w_; ++i)
      {
        if (hf.isValid(i, j))
        {
          rs += hf.at(i, j);
          rc += 1.0;
        }
        sum_[at(i + 1, j + 1)] = sum_[at(i + 1, j)] + rs;
        count_[at(i + 1, j + 1)] = count_[at(i + 1, j)] + rc;
      }
    }
  }
  // kDescriptorSide^2 block means of the window of side `size` around (cx, cy).
  void summary(double cx, double cy, int size, float* out) const
  {
    const int x0 = windowStart(cx, size);
    const int y0 = windowStart(cy, size);
    for (int b = 0; b < kDescriptorSide; ++b)
    {
      for (int a = 0; a < kDescriptorSide; ++a)
      {
        const int i0 = std::clamp(x0 + a * size / kDescriptorSide, 0, w_);
        const int i1 = std::clamp(x0 + (a + 1) * size / kDescriptorSide, 0, w_);
        const int j0 = std::clamp(y0 + b * size / kDescriptorSide, 0, h_);
        const int j1 = std::clamp(y0 + (b + 1) * size / kDescriptorSide, 0, h_);
        const double n = rect(count_, i0, j0, i1, j1);
        out[b * kDescriptorSide + a] =
          n > 0 ? static_cast<float>(rect(sum_, i0, j0, i1, j1) / n) : std::nanf("");
      }
    }
  }

private:
  std::size_t at(int i, int j) const { return rowMajor(i, j, w_ + 1); }
  double rect(const std::vector<double>& t, int i0, int j0, int i1, int j1) const
  {
    return t[at(i1, j1)] - t[at(i0, j1)] - t[at(i1, j0)] + t[at(i0, j0)];
  }
  int w_;
  int h_;
  std::vector<double> sum_;
  std::vector<double> count_;
};

} // namespace

std::vector<FeatureSite> featureSites(const FeatureGraph& graph,
  int patchSize,
  double spacing,
  const std::vector<double>* phases)
{
  const double radius = 0.5 * patchSize;
  FeatureGraph g = graph;
  computeControlPoints(g, radius);
  std::vector<FeatureSite> sites;
  for (std::size_t n = 0; n < g.nodes.size(); ++n)
  {
    const FeatureNode& node = g.nodes[n];
    if (node.kind == NodeKind::Path)
    {
      continue; // loop anchors are covered by the path points
    }
    FeatureSite s;
    s.centre = node.position;
    s.type = node.type;
    s.kind = node.kind;
    s.node = static_cast<int>(n);
    s.arms = node.controls;
    sites.push_back(std::move(s));
  }
  const double step = spacing > 0.0 ? spacing : 0.5 * radius;
  for (std::size_t c = 0; c < g.chains.size(); ++c)
  {
    const FeatureChain& ch = g.chains[c];
    std::vector<double> arc{ 0.0 };
    for (std::size_t k = 1; k < ch.points.size(); ++k)
    {
      arc.push_back(arc.back() +
        std::hypot(ch.points[k].x - ch.points[k - 1].x, ch.points[k].y - ch.points[k - 1].y));
    }
    const double length = arc.back();
    const double phase = phases != nullptr && c < phases->size() ? (*phases)[c] * step : 0.0;
    for (double s = 0.5 * radius + phase; s <= length - 0.5 * radius + 1e-9; s += step)
    {
      FeatureSite site;
      site.centre = pointAt(ch.points, arc, s);
      site.type = ch.type;
      site.kind = NodeKind::Path;
      site.chain = static_cast<int>(c);
      site.arms.push_back(armAlong(ch.points, arc, s, +1, radius, static_cast<int>(c)));
      site.arms.push_back(armAlong(ch.points, arc, s, -1, radius, static_cast<int>(c)));
      sites.push_back(std::move(site));
    }
  }
  return sites;
}

namespace
{

// Offset (cells) of landform sample k from a placed patch's centre cell.
int landformOffset(int k, int patchSize)
{
  return landformCell(k, patchSize, 1) - patchSize / 2;
}

// The low-passed heights at the landform samples of a patch placed through
// variant v around (x, y) of `smooth` (sample offsets in the placed frame, read
// at v's source offsets), minus the one at (x, y) itself; samples off the image
// count as the centre (no difference).
void landformSamples(const Heightfield& smooth,
  const Variant& v,
  double x,
  double y,
  int patchSize,
  float* out)
{
  const float centre = sampleBilinear(smooth, x, y);
  for (int b = 0; b < kLandformSide; ++b)
  {
    for (int a = 0; a < kLandformSide; ++a)
    {
      double su = 0.0;
      double sv = 0.0;
      v.toSource(landformOffset(a, patchSize), landformOffset(b, patchSize), su, sv);
      const float h = sampleBilinear(smooth, x + su, y + sv);
      out[b * kLandformSide + a] = std::isnan(h) || std::isnan(centre) ? 0.0f : h - centre;
    }
  }
}

// The exemplars' height spread (standard deviation over every valid cell):
// the unit the pool's costs are measured in.
double poolHeightScale(const std::vector<const Heightfield*>& exemplars)
{
  double sum = 0.0;
  double square = 0.0;
  double count = 0.0;
  for (const Heightfield* ex : exemplars)
  {
    for (std::size_t k = 0; k < ex->size(); ++k)
    {
      if (ex->isValid(k))
      {
        sum += ex->z[k];
        square += static_cast<double>(ex->z[k]) * ex->z[k];
        count += 1.0;
      }
    }
  }
  const double mean = count > 0 ? sum / count : 0.0;
  return std::max(1e-6, std::sqrt(std::max(0.0, square / std::max(1.0, count) - mean * mean)));
}

// Exemplar e's entry, once it is known to hold a patch.
ExemplarInfo exemplarInfo(const Heightfield& ex,
  std::size_t e,
  const std::vector<std::string>& names,
  int patchSize,
  std::size_t firstCandidate)
{
  ExemplarInfo info;
  info.name = e < names.size() ? names[e] : "exemplar " + std::to_string(e);
  info.width = ex.width;
  info.height = ex.height;
  info.firstCandidate = firstCandidate;
  if (ex.width < patchSize || ex.height < patchSize)
  {
    const std::string patch = std::to_string(patchSize);
    throw Error(info.name + " is " + std::to_string(ex.width) + " x " + std::to_string(ex.height) +
      " cells, smaller than one patch (" + patch + " x " + patch + ").");
  }
  return info;
}

// One candidate's row: the site seen through variant k, its arms in
// counter-clockwise order of their placed angles (a mirror swaps the two
// sides of an arm), and the site's noise.
void addCandidate(CandidatePool& pool,
  std::size_t e,
  int siteIndex,
  const FeatureSite& site,
  const SiteProfiles& prof,
  const std::array<float, kNoiseLevels>& noise,
  int k)
{
  const Variant v = variant(k);
  pool.exemplar.push_back(static_cast<int>(e));
  pool.site.push_back(siteIndex);
  pool.variant.push_back(k);
  pool.kind.push_back(static_cast<int>(site.kind));
  pool.type.push_back(static_cast<int>(site.type));
  pool.arms.push_back(static_cast<int>(prof.angle.size()));
  pool.centreX.push_back(static_cast<float>(site.centre.x));
  pool.centreY.push_back(static_cast<float>(site.centre.y));
  std::vector<std::size_t> order(prof.angle.size());
  std::iota(order.begin(), order.end(), std::size_t{ 0 });
  std::vector<double> placed(prof.angle.size());
  for (std::size_t a = 0; a < placed.size(); ++a)
  {
    placed[a] = v.placedAngle(prof.angle[a]);
  }
  std::sort(order.begin(),
    order.end(),
    [&](std::size_t x, std::size_t y) { return placed[x] < placed[y]; });
  for (std::size_t slot = 0; slot < kMaxArms; ++slot)
  {
    const bool used = slot < order.size();
    const std::size_t a = used ? order[slot] : 0;
    pool.angles.push_back(used ? static_cast<float>(placed[a]) : 0.0f);
    for (std::size_t s = 0; s < kAlongSamples; ++s)
    {
      pool.along.push_back(used ? prof.along[a][s] : 0.0f);
    }
    for (std::size_t s = 0; s < kAcrossSamples; ++s)
    {
      const std::size_t src = v.mirrored ? kAcrossSamples - 1 - s : s;
      pool.across.push_back(used ? prof.across[a][src] : 0.0f);
    }
  }
  pool.noise.insert(pool.noise.end(), noise.begin(), noise.end());
}

// Summaries of the candidates from `first` on (all of exemplar ex): block
// means of the exemplar as seen through each variant, one oriented copy at a
// time (summed-area table: four reads a block), and the landform samples of
// the low-passed exemplar seen the same way.
void addSummaries(CandidatePool& pool,
  const Heightfield& ex,
  std::size_t first,
  const PoolOptions& options)
{
  const int P = options.patchSize;
  pool.descriptor.resize(pool.size() * kDescriptorSize);
  pool.landform.resize(pool.size() * kLandformStride, 0.0f);
  const Heightfield smooth = landformImage(ex, P);
  for (int k = 0; k < kVariantCount; ++k)
  {
    if (!byId(options.variants, k))
    {
      continue;
    }
    const Variant v = variant(k);
    double cu = 0.0;
    double cv = 0.0;
    const BlockMeans means(orientExemplar(ex, v, &cu, &cv));
    for (std::size_t c = first; c < pool.size(); ++c)
    {
      if (pool.variant[c] != k)
      {
        continue;
      }
      // The site's centre in the oriented copy: m^-1 (centre - exemplar centre).
      const double dx = pool.centreX[c] - 0.5 * (ex.width - 1);
      const double dy = pool.centreY[c] - 0.5 * (ex.height - 1);
      const double det = v.m[0] * v.m[3] - v.m[1] * v.m[2];
      const double px = cu + (v.m[3] * dx - v.m[1] * dy) / det;
      const double py = cv + (-v.m[2] * dx + v.m[0] * dy) / det;
      means.summary(px, py, P, pool.descriptor.data() + c * kDescriptorSize);
      landformSamples(
        smooth, v, pool.centreX[c], pool.centreY[c], P, pool.landform.data() + c * kLandformStride);
    }
  }
}

} // namespace

CandidatePool buildCandidatePool(const std::vector<const Heightfield*>& exemplars,
  const std::vector<const FeatureGraph*>& graphs,
  const PoolOptions& options,
  const std::vector<std::string>& names)
{
  if (exemplars.size() != graphs.size())
  {
    throw Error("Each exemplar needs its feature graph.");
  }
  const int P = options.patchSize;
  CandidatePool pool;
  pool.patchSize = P;
  pool.heightScale = poolHeightScale(exemplars);
  // A square of this half-side contains the patch in every rotation.
  const int footprint = static_cast<int>(std::ceil(0.5 * P * std::sqrt(2.0))) + 1;
  for (std::size_t e = 0; e < exemplars.size(); ++e)
  {
    const Heightfield& ex = *exemplars[e];
    ExemplarInfo info = exemplarInfo(ex, e, names, P, pool.size());
    const FootprintCheck check(ex);
    const NoiseVariance noise(ex);
    for (const FeatureSite& site : featureSites(*graphs[e], P))
    {
      if (site.arms.empty() || !check.clear(site.centre.x, site.centre.y, footprint))
      {
        continue; // too close to an edge or nodata for some rotation
      }
      const SiteProfiles prof = sampleSite(site, ex, P);
      const auto nv = noise.window(site.centre.x, site.centre.y, P);
      const int siteIndex = static_cast<int>(pool.sites.size());
      pool.sites.push_back(site);
      for (int k = 0; k < kVariantCount; ++k)
      {
        if (byId(options.variants, k))
        {
          addCandidate(pool, e, siteIndex, site, prof, nv, k);
        }
      }
    }
    addSummaries(pool, ex, info.firstCandidate, options);
    info.candidateCount = pool.size() - info.firstCandidate;
    if (info.candidateCount == 0)
    {
      pool.warnings.push_back(info.name +
        " has no feature sites at least half a patch from its edges and nodata; only non-feature "
        "matching can use it.");
    }
    pool.exemplars.push_back(info);
  }
  return pool;
}

namespace
{

// Whether every value of a pool's array is finite.
bool allFinite(const std::vector<float>& values)
{
  return std::all_of(values.begin(), values.end(), [](float v) { return std::isfinite(v); });
}

// The pool's arrays hold `perCandidate` values for each of its n candidates.
void checkLength(std::size_t size, std::size_t n, std::size_t perCandidate, const char* what)
{
  if (size != n * perCandidate)
  {
    throw Error("The candidate pool's " + std::string(what) + " hold " + std::to_string(size) +
      " values for " + std::to_string(n) + " candidates, not " + std::to_string(perCandidate) +
      " each: it is not a whole pool.");
  }
}

// Candidate c's own values lie in their ranges, its centre on its exemplar.
void checkCandidate(const CandidatePool& pool, std::size_t c)
{
  const ExemplarInfo& info = byId(pool.exemplars, pool.exemplar[c]);
  const bool inRange = pool.variant[c] >= 0 && pool.variant[c] < kVariantCount &&
    pool.arms[c] >= 0 && pool.arms[c] <= kMaxArms &&
    (pool.type[c] == static_cast<int>(FeatureType::Ridge) ||
      pool.type[c] == static_cast<int>(FeatureType::Valley)) &&
    pool.kind[c] >= static_cast<int>(NodeKind::Path) &&
    pool.kind[c] <= static_cast<int>(NodeKind::Branch);
  const bool onExemplar = pool.centreX[c] >= 0.0f && pool.centreX[c] <= info.width - 1 &&
    pool.centreY[c] >= 0.0f && pool.centreY[c] <= info.height - 1;
  if (!inRange || !onExemplar)
  {
    throw Error("Candidate " + std::to_string(c) +
      " of the candidate pool has a variant, arm "
      "count, feature type, kind or centre no pool builder makes: it was not built here.");
  }
}

} // namespace

void checkGivenPool(const CandidatePool& pool,
  const std::vector<const Heightfield*>& exemplars,
  int patchSize)
{
  if (pool.patchSize != patchSize)
  {
    throw Error("The candidate pool was built for patches of " + std::to_string(pool.patchSize) +
      " cells, not " + std::to_string(patchSize) + ": build it with the patch size it is used at.");
  }
  if (pool.exemplars.size() != exemplars.size())
  {
    throw Error("The candidate pool was built from " + std::to_string(pool.exemplars.size()) +
      " exemplars, but " + std::to_string(exemplars.size()) +
      " are given: build it from the same exemplars.");
  }
  for (std::size_t e = 0; e < exemplars.size(); ++e)
  {
    const ExemplarInfo& info = pool.exemplars[e];
    if (info.width != exemplars[e]->width || info.height != exemplars[e]->height)
    {
      throw Error("Exemplar " + std::to_string(e) + " of the candidate pool was " +
        std::to_string(info.width) + " x " + std::to_string(info.height) +
        " cells, but the one "
        "given is " +
        std::to_string(exemplars[e]->width) + " x " + std::to_string(exemplars[e]->height) +
        ": build the pool from the same exemplars.");
    }
    if (info.heightsChecksum != 0)
    {
      ContentHasher hasher;
      hashHeightfield(hasher, *exemplars[e]);
      if (hasher.digest() != info.heightsChecksum)
      {
        throw Error("The candidate pool was cut from other heights than exemplar " +
          std::to_string(e) +
          " (at the cell size it is used at): build it from the same "
          "exemplars, on the output's cells.");
      }
    }
  }
  const std::size_t n = pool.size();
  for (const std::vector<int>* column :
    { &pool.exemplar, &pool.site, &pool.kind, &pool.type, &pool.arms })
  {
    checkLength(column->size(), n, 1, "columns");
  }
  checkLength(pool.centreX.size(), n, 1, "centres");
  checkLength(pool.centreY.size(), n, 1, "centres");
  checkLength(pool.angles.size(), n, kMaxArms, "arm angles");
  checkLength(pool.along.size(), n, kMaxArms * kAlongSamples, "profiles along the arms");
  checkLength(pool.across.size(), n, kMaxArms * kAcrossSamples, "profiles across the arms");
  checkLength(pool.noise.size(), n, kNoiseLevels, "noise variances");
  checkLength(pool.descriptor.size(), n, kDescriptorSize, "overlap summaries");
  checkLength(pool.landform.size(), n, kLandformStride, "landform samples");
  if (!(std::isfinite(pool.heightScale) && pool.heightScale > 0.0) || !allFinite(pool.centreX) ||
    !allFinite(pool.centreY) || !allFinite(pool.angles) || !allFinite(pool.along) ||
    !allFinite(pool.across) || !allFinite(pool.noise) || !allFinite(pool.descriptor) ||
    !allFinite(pool.landform))
  {
    throw Error("The candidate pool holds values that are not finite numbers: it was not built "
                "here, or was changed since.");
  }
  // Each exemplar's candidates in one run, in exemplar order, as the builder
  // lays them and the matcher's per-exemplar searches read them.
  for (std::size_t e = 0; e < exemplars.size(); ++e)
  {
    const ExemplarInfo& info = pool.exemplars[e];
    const bool inside = info.firstCandidate <= n && info.candidateCount <= n - info.firstCandidate;
    const bool follows = e == 0 ? info.firstCandidate == 0
                                : info.firstCandidate ==
        pool.exemplars[e - 1].firstCandidate + pool.exemplars[e - 1].candidateCount;
    const auto first = pool.exemplar.begin() + static_cast<std::ptrdiff_t>(info.firstCandidate);
    if (!inside || !follows ||
      !std::all_of(first,
        first + static_cast<std::ptrdiff_t>(info.candidateCount),
        [e](int x) { return x == static_cast<int>(e); }))
    {
      throw Error("The candidate pool's candidates of exemplar " + std::to_string(e) +
        " are not where its exemplar list says: it is not a whole pool.");
    }
  }
  const ExemplarInfo& last = pool.exemplars.empty() ? ExemplarInfo{} : pool.exemplars.back();
  if (last.firstCandidate + last.candidateCount != n)
  {
    throw Error("The candidate pool has candidates of no exemplar: it is not a whole pool.");
  }
  for (std::size_t c = 0; c < n; ++c)
  {
    checkCandidate(pool, c);
  }
}

void mergePools(CandidatePool& a, const CandidatePool& b)
{
  const int exemplarOffset = static_cast<int>(a.exemplars.size());
  const int siteOffset = static_cast<int>(a.sites.size());
  const std::size_t candidateOffset = a.size();
  const double na = static_cast<double>(a.size());
  const double nb = static_cast<double>(b.size());
  a.heightScale = na + nb > 0
    ? std::sqrt(
        (na * a.heightScale * a.heightScale + nb * b.heightScale * b.heightScale) / (na + nb))
    : a.heightScale;
  for (ExemplarInfo info : b.exemplars)
  {
    info.firstCandidate += candidateOffset;
    a.exemplars.push_back(info);
  }
  for (int e : b.exemplar)
  {
    a.exemplar.push_back(e + exemplarOffset);
  }
  for (int s : b.site)
  {
    a.site.push_back(s + siteOffset);
  }
  auto append = [](auto& x, const auto& y) { x.insert(x.end(), y.begin(), y.end()); };
  append(a.variant, b.variant);
  append(a.kind, b.kind);
  append(a.type, b.type);
  append(a.arms, b.arms);
  append(a.centreX, b.centreX);
  append(a.centreY, b.centreY);
  append(a.angles, b.angles);
  append(a.along, b.along);
  append(a.across, b.across);
  append(a.noise, b.noise);
  append(a.descriptor, b.descriptor);
  append(a.landform, b.landform);
  append(a.sites, b.sites);
  append(a.warnings, b.warnings);
}

FeatureQuery makeFeatureQuery(const FeatureSite& site,
  const Heightfield& target,
  const NoiseVariance& targetNoise,
  const Heightfield* output,
  const std::vector<std::uint8_t>* known,
  int patchSize,
  const Heightfield* lowTarget,
  const std::vector<float>* confidence)
{
  FeatureQuery q;
  q.type = static_cast<int>(site.type);
  q.kind = static_cast<int>(site.kind);
  const SiteProfiles prof = sampleSite(site, target, patchSize);
  q.arms = static_cast<int>(prof.angle.size());
  std::vector<std::size_t> order(prof.angle.size());
  std::iota(order.begin(), order.end(), std::size_t{ 0 });
  std::sort(order.begin(),
    order.end(),
    [&](std::size_t x, std::size_t y) { return prof.angle[x] < prof.angle[y]; });
  for (std::size_t slot = 0; slot < order.size(); ++slot)
  {
    const std::size_t a = order[slot];
    q.angles[slot] = prof.angle[a];
    std::copy(prof.along[a].begin(), prof.along[a].end(), q.along.begin() + slot * kAlongSamples);
    std::copy(
      prof.across[a].begin(), prof.across[a].end(), q.across.begin() + slot * kAcrossSamples);
  }
  q.noise = targetNoise.window(site.centre.x, site.centre.y, patchSize);

  if (output != nullptr && known != nullptr)
  {
    const int x0 = windowStart(site.centre.x, patchSize);
    const int y0 = windowStart(site.centre.y, patchSize);
    for (int b = 0; b < kDescriptorSide; ++b)
    {
      for (int a = 0; a < kDescriptorSide; ++a)
      {
        double s = 0.0;
        double n = 0.0;
        double total = 0.0;
        const int i0 = x0 + a * patchSize / kDescriptorSide;
        const int i1 = x0 + (a + 1) * patchSize / kDescriptorSide;
        const int j0 = y0 + b * patchSize / kDescriptorSide;
        const int j1 = y0 + (b + 1) * patchSize / kDescriptorSide;
        for (int j = j0; j < j1; ++j)
        {
          for (int i = i0; i < i1; ++i)
          {
            total += 1.0;
            if (i >= 0 && j >= 0 && i < output->width && j < output->height &&
              (*known)[output->index(i, j)] != 0 && output->isValid(i, j))
            {
              s += output->at(i, j);
              n += 1.0;
            }
          }
        }
        const std::size_t k = rowMajor(a, b, kDescriptorSide);
        q.weight[k] = total > 0 ? static_cast<float>(n / total) : 0.0f;
        q.descriptor[k] = n > 0 ? static_cast<float>(s / n) : 0.0f;
      }
    }
  }
  if (lowTarget != nullptr && confidence != nullptr)
  {
    landformSamples(
      *lowTarget, variant(0), site.centre.x, site.centre.y, patchSize, q.landform.data());
    for (int b = 0; b < kLandformSide; ++b)
    {
      for (int a = 0; a < kLandformSide; ++a)
      {
        const int i = static_cast<int>(std::lround(site.centre.x)) + landformOffset(a, patchSize);
        const int j = static_cast<int>(std::lround(site.centre.y)) + landformOffset(b, patchSize);
        const bool inside = i >= 0 && j >= 0 && i < lowTarget->width && j < lowTarget->height;
        const std::size_t cell = inside ? lowTarget->index(i, j) : 0;
        const bool done = inside && known != nullptr && (*known)[cell] != 0;
        q.landformWeight[rowMajor(a, b, kLandformSide)] =
          inside && !done ? (*confidence)[cell] : 0.0f;
      }
    }
  }
  return q;
}

} // namespace tsynth
