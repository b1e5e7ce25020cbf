#include "PatchPlacement.h"

#include "../Core/Error.h"
#include "../Core/Grid.h"
#include "../Core/Random.h"
#include "../Core/Smoothing.h"
#include "../Distance/DistanceField.h"
#include "../Features/Ppa.h"
#include "FeatureOrder.h"
#include "FillOrder.h"
#include "Finishing.h"
#include "PatchExtraction.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <omp.h>

namespace tsynth
{
namespace
{

// The merge spreads the seam's gradient mismatch this far, in patches: a
// tenth, as Tasse's code does (8 cells at 80; the peer's patch_merging is
// called with bsize / 10). Spread over a quarter (20 cells), the correction
// integrated into ramps a patch wide, and the land between the strokes came
// out half again as rough as the exemplars' at 1-3 km (band-pass G(8) - G(32)
// 192 m against Colorado's 128 m, a tenth: 131 m) and hid the sketch in it;
// over the 24-run seed sweep of the bundled sketches legible share 0.819 to
// 0.870, slope distance 0.071 to 0.048, seam index 0.935 to 0.896. A fixed 20
// cells on smaller patches had tilted them by kilometres on steep exemplars.
constexpr double kShepardRadiusInPatches = 0.1;
// A merged patch whose free border leaves the exemplars' height range by more
// than this share of its span is anchored (MergeOptions::lowestHeight): real
// land a little beyond the exemplars' extremes is plausible, kilometres are a
// runaway.
constexpr double kHeightSlackShare = 0.1;

// The threads an OpenMP region may use (omp_get_max_threads()'s int), at least 1, as a count.
std::size_t maxThreads()
{
  return static_cast<std::size_t>(std::max(1, omp_get_max_threads()));
}

// This OpenMP thread's slot in per-thread arrays (omp_get_thread_num() is an int from 0).
std::size_t threadSlot()
{
  return static_cast<std::size_t>(omp_get_thread_num());
}

// Cell (i, j) of a row-major window `width` wide, no bigger than a patch or a
// merge window: formed in int and widened once, the arithmetic (and machine
// code) of the hot loops that use it.
std::size_t windowCell(int i, int j, int width)
{
  return static_cast<std::size_t>(j * width + i);
}

// Whether int id `id` names an element of v (a negative id converts to past the end).
template<class Vector>
bool hasId(const Vector& v, int id)
{
  return static_cast<std::size_t>(id) < v.size();
}
// Candidates compared per placement are fewer than this (it spaces the
// seed's draws of different placements apart).
constexpr std::size_t kMaxCandidates = 4096;
// Candidates whose seam costs are within this share of each other are equally
// good: the seed picks among them.
constexpr double kNearTie = 0.1;
// Where the sketch leaves the land free the target still holds it, this
// weakly, near the exemplars' level: otherwise patch after patch, each fitted
// to the last, the land would wander off by kilometres.
constexpr float kFreeLandWeight = 0.05f;
// Feature candidates laying their own line more than this many cells (median)
// farther from the drawn one than the best-aligned candidate are passed over:
// a crest a few cells beside the stroke reads as a second line.
constexpr float kLineOffsetSlack = 2.0f;
// Where feature sites crowd (a DEM target's own tree, lines closer than
// patches draw: featureSitesCrowd), the seam decides among the best few of the
// feature candidates that lay their line that well, by the matcher's cost:
// each costs a graph cut, the largest share of a feature placement, and each
// cell lies under several feature patches, the later ones over the earlier.
// On 8 DEM targets (sweep_dem_targets.py), all of them (6.8 on average)
// against the best 4: feature placement 1.74 -> 1.15 s, seam index 0.887 ->
// 0.891, slope distance 0.132 -> 0.134, band-pass correlation and fidelity
// within 0.007; side by side, the hillshades show the same land. The seam's
// pick was among the best 4 in 68% of placements on a Norway target. Drawings
// with room keep every aligned candidate (14 of 16 on the Y): there each
// feature patch's seam shows, and the best 4 raised the seam index of
// letters and a spiral at 40-cell patches from 1.07 and 1.09 to 1.14 and 1.20.
constexpr int kMostFeatureSeamTrials = 4;

// Cells within kLineHalfWidth of the sketched lines: feature patches own them.
// Its own function so that the distance plane goes before the next is made.
std::vector<std::uint8_t> cellsNearLines(const FeatureGraph& sketch, int width, int height)
{
  const std::vector<float> d =
    distanceTransform(rasteriseChains(sketch, width, height), width, height);
  std::vector<std::uint8_t> near(d.size(), 0);
  for (std::size_t c = 0; c < d.size(); ++c)
  {
    near[c] = d[c] <= kLineHalfWidth ? 1 : 0;
  }
  return near;
}

} // namespace

PatchPlacement::PatchPlacement(const SynthesisTarget& target,
  PatchMatcher* matcher,
  const std::vector<const FeatureGraph*>& graphs,
  const SynthesisOptions& o,
  const Heightfield* known)
  : target_(target)
  , matcher_(matcher)
  , graphs_(graphs)
  , o_(o)
  , P_(o.patchSize)
  , crowded_(featureSitesCrowd(target, o.patchSize))
  , out_(known != nullptr ? *known
                          : Heightfield(target.field.width,
                              target.field.height,
                              std::numeric_limits<float>::quiet_NaN()))
  , filled_(out_.size(), 0)
  // Only a detailed target (a DEM) asks for its own roughness; a drawing's
  // queries ask for the exemplars' (typicalNoise_) or none, so its tables
  // (six of doubles over the output: 800 MB at 4096 x 4096) are not built.
  , noise_(matcher != nullptr && target.detailed ? NoiseVariance(target.field) : NoiseVariance())
  , lowTarget_(matcher != nullptr ? landformImage(target.field, o.patchSize) : Heightfield())
  , ownConfidence_(target.weight.size() == target.field.size()
        ? std::vector<float>()
        : std::vector<float>(target.field.size(), 1.0f))
  , confidence_(target.weight.size() == target.field.size() ? target.weight : ownConfidence_)
  , mergers_(maxThreads())
{
  for (std::size_t c = 0; c < out_.size(); ++c)
  {
    filled_[c] = known != nullptr && known->isValid(c) ? 1 : 0;
  }
  out_.valid.clear();
  out_.cellX = target.field.cellX;
  out_.cellY = target.field.cellY;
  out_.cellSizeKnown = true;
  out_.georef = target.field.georef;
  result_.patchId.assign(out_.size(), -1);
  result_.seam.assign(out_.size(), 0);
  result_.matchCost.assign(out_.size(), std::numeric_limits<float>::quiet_NaN());
  if (matcher == nullptr)
  {
    mergers_.clear();
    return;
  }
  for (const FeatureGraph* g : graphs)
  {
    linePoints_.emplace_back(*g, kLineOffsetReachInPatches * P_);
  }
  // Cells within a few cells of the sketched lines: feature patches own them,
  // fill patches may not take them once they are filled.
  line_ = cellsNearLines(target.graph, out_.width, out_.height);
  for (FeatureType type : { FeatureType::Ridge, FeatureType::Valley })
  {
    FeatureGraph ofType = target.graph;
    ofType.chains.erase(std::remove_if(ofType.chains.begin(),
                          ofType.chains.end(),
                          [&](const FeatureChain& c) { return c.type != type; }),
      ofType.chains.end());
    if (!ofType.chains.empty()) // else empty: every cell is infinitely far (lineOffset)
    {
      (type == FeatureType::Ridge ? toRidge_ : toValley_) = distanceTransform(
        rasteriseChains(ofType, out_.width, out_.height), out_.width, out_.height);
    }
  }
}

PatchPlacement::OwnLine PatchPlacement::ownLine(const PatchCandidate& c) const
{
  OwnLine own;
  const CandidatePool& pool = matcher_->pool();
  if (!c.feature || c.poolIndex >= pool.size() || !hasId(linePoints_, c.exemplar))
  {
    return own;
  }
  own.type = pool.type[c.poolIndex];
  const FeatureType type = own.type > 0 ? FeatureType::Ridge : FeatureType::Valley;
  own.cells = ownLineOffsets(byId(linePoints_, c.exemplar), type, c, P_);
  return own;
}

float PatchPlacement::lineOffset(const OwnLine& own, int x0, int y0) const
{
  if (own.type == 0)
  {
    return std::numeric_limits<float>::quiet_NaN();
  }
  const std::vector<float>& toStroke = own.type > 0 ? toRidge_ : toValley_;
  std::vector<float> offsets;
  for (const Point2& q : own.cells)
  {
    const int x = x0 + P_ / 2 + static_cast<int>(std::lround(q.x));
    const int y = y0 + P_ / 2 + static_cast<int>(std::lround(q.y));
    if (x >= 0 && y >= 0 && x < out_.width && y < out_.height)
    {
      offsets.push_back(
        toStroke.empty() ? std::numeric_limits<float>::infinity() : toStroke[out_.index(x, y)]);
    }
  }
  if (offsets.empty())
  {
    return std::numeric_limits<float>::quiet_NaN();
  }
  std::nth_element(offsets.begin(), offsets.begin() + offsets.size() / 2, offsets.end());
  return offsets[offsets.size() / 2];
}

DenseQuery PatchPlacement::window(int x0, int y0) const
{
  DenseQuery q;
  q.heights.assign(cellCount(P_, P_), 0.0f);
  q.known.assign(cellCount(P_, P_), 0);
  for (int j = 0; j < P_; ++j)
  {
    for (int i = 0; i < P_; ++i)
    {
      const int x = x0 + i;
      const int y = y0 + j;
      if (x < 0 || y < 0 || x >= out_.width || y >= out_.height || filled_[out_.index(x, y)] == 0)
      {
        continue;
      }
      const std::size_t c = out_.index(x, y);
      const std::size_t k = windowCell(i, j, P_);
      q.heights[k] = out_.z[c];
      q.known[k] = 1;
    }
  }
  const int f = matcher_->dense().options().coarseFactor;
  for (int b = 0; b < kLandformSide; ++b)
  {
    for (int a = 0; a < kLandformSide; ++a)
    {
      const int x = x0 + landformCell(a, P_, f);
      const int y = y0 + landformCell(b, P_, f);
      const std::size_t k = windowCell(a, b, kLandformSide);
      if (x >= 0 && y >= 0 && x < out_.width && y < out_.height && filled_[out_.index(x, y)] == 0 &&
        lowTarget_.isValid(x, y))
      {
        q.landform.heights[k] = lowTarget_.at(x, y);
        q.landform.weights[k] = std::max(kFreeLandWeight, confidence_[out_.index(x, y)]);
      }
    }
  }
  // The roughness to match: a DEM target's own; a drawing says nothing of
  // it, so the exemplars' typical one.
  q.noise = target_.detailed ? noise_.window(x0 + 0.5 * P_, y0 + 0.5 * P_, P_) : typicalNoise_;
  return q;
}

Heightfield PatchPlacement::extract(const PatchCandidate& c) const
{
  for (const DenseMatcher::Oriented& r : matcher_->dense().oriented())
  {
    if (r.exemplar == c.exemplar && r.variant == c.variant)
    {
      const auto& ex = byId(matcher_->pool().exemplars, c.exemplar);
      Heightfield patch = extractPatch(r.full, r.centreX, r.centreY, ex.width, ex.height, c, P_);
      patch.cellX = out_.cellX;
      patch.cellY = out_.cellY;
      return patch;
    }
  }
  throw Error("Internal error: no oriented exemplar for a candidate.");
}

float PatchPlacement::fitOffset(const Heightfield& patch, int x0, int y0) const
{
  return fitPatchOffset(patch, x0, y0, { out_, filled_, lowTarget_, confidence_ });
}

void PatchPlacement::protectLines(Heightfield& patch, int x0, int y0) const
{
  protectKeptCells(patch, x0, y0, { line_, frozen_, filled_, out_.width, out_.height });
}

const std::vector<int>* PatchPlacement::regionExemplars(int x0, int y0) const
{
  if (o_.regionLabels.empty())
  {
    return nullptr;
  }
  const int x = std::clamp(x0 + P_ / 2, 0, out_.width - 1);
  const int y = std::clamp(y0 + P_ / 2, 0, out_.height - 1);
  const int label = o_.regionLabels[out_.index(x, y)];
  if (label < 0 || !hasId(o_.regionExemplars, label) || byId(o_.regionExemplars, label).empty())
  {
    return nullptr;
  }
  return &byId(o_.regionExemplars, label);
}

std::vector<PatchCandidate> PatchPlacement::allowed(std::vector<PatchCandidate> candidates,
  int x0,
  int y0,
  std::size_t keep) const
{
  if (const std::vector<int>* ok = regionExemplars(x0, y0))
  {
    candidates.erase(std::remove_if(candidates.begin(),
                       candidates.end(),
                       [&](const PatchCandidate& c)
                       { return std::find(ok->begin(), ok->end(), c.exemplar) == ok->end(); }),
      candidates.end());
  }
  if (candidates.size() > keep)
  {
    candidates.resize(keep);
  }
  return candidates;
}

int PatchPlacement::reuses(const PatchCandidate& c) const
{
  const double radius = 0.5 * P_;
  const long bx = static_cast<long>(std::floor(c.centreX / radius));
  const long by = static_cast<long>(std::floor(c.centreY / radius));
  int n = 0;
  for (long y = by - 1; y <= by + 1; ++y)
  {
    for (long x = bx - 1; x <= bx + 1; ++x)
    {
      const auto bucket = sources_.find(sourceKey(c.exemplar, x, y));
      if (bucket == sources_.end())
      {
        continue;
      }
      for (std::size_t i : bucket->second)
      {
        const Placement& p = result_.placements[i];
        if (std::hypot(p.sourceX - c.centreX, p.sourceY - c.centreY) < radius)
        {
          ++n;
        }
      }
    }
  }
  return n;
}

std::int64_t PatchPlacement::sourceKey(int exemplar, long x, long y)
{
  return (static_cast<std::int64_t>(exemplar) << 42) ^
    (static_cast<std::int64_t>(x + (1L << 20)) << 21) ^ static_cast<std::int64_t>(y + (1L << 20));
}

void PatchPlacement::recordSource(std::size_t placement)
{
  const Placement& p = result_.placements[placement];
  const double radius = 0.5 * P_;
  sources_[sourceKey(p.exemplar,
             static_cast<long>(std::floor(p.sourceX / radius)),
             static_cast<long>(std::floor(p.sourceY / radius)))]
    .push_back(placement);
}

std::vector<std::uint8_t> PatchPlacement::strokeCore(int x0, int y0) const
{
  return featureCore(line_, out_.width, out_.height, x0, y0, P_);
}

void PatchPlacement::alignTrial(const PatchCandidate& candidate, int x0, int y0, Trial& t) const
{
  t.own = ownLine(candidate);
  t.lineOffset = lineOffset(t.own, x0, y0);
}

void PatchPlacement::prepareTrial(const PatchCandidate& candidate,
  int x0,
  int y0,
  bool feature,
  const std::vector<std::uint8_t>& strokeCells,
  Trial& t) const
{
  t.patch = extract(candidate);
  if (!feature)
  {
    protectLines(t.patch, x0, y0);
  }
  t.offset = o_.verticalOffset ? fitOffset(t.patch, x0, y0) : 0.0f;
  for (float& z : t.patch.z)
  {
    z += t.offset;
  }
  if (feature)
  {
    // The patch also owns its own ridge or valley near the centre, where it
    // strays from the drawn line: the crest stays one line, not two.
    t.core = strokeCells;
    addOwnLineStrip(t.core, t.own.cells, P_);
  }
}

float PatchPlacement::bestAlignment(const std::vector<Trial>& trials)
{
  float aligned = std::numeric_limits<float>::infinity();
  for (const Trial& t : trials)
  {
    if (!std::isnan(t.lineOffset))
    {
      aligned = std::min(aligned, t.lineOffset);
    }
  }
  return aligned;
}

void PatchPlacement::keepBestAligned(std::vector<Trial>& trials, float aligned)
{
  int kept = 0;
  for (Trial& t : trials)
  {
    if (eligible(t, aligned) && ++kept > kMostFeatureSeamTrials)
    {
      t.lineOffset = std::numeric_limits<float>::infinity();
    }
  }
}

bool PatchPlacement::eligible(const Trial& t, float aligned)
{
  return !std::isfinite(aligned) || t.lineOffset <= aligned + kLineOffsetSlack;
}

std::size_t PatchPlacement::choose(const std::vector<PatchCandidate>& candidates,
  const std::vector<Trial>& trials,
  float aligned,
  double& bestSeam) const
{
  std::size_t best = 0;
  bestSeam = std::numeric_limits<double>::infinity();
  for (std::size_t c = 0; c < candidates.size(); ++c)
  {
    const Trial& t = trials[c];
    if (!eligible(t, aligned))
    {
      continue;
    }
    // Anti-repetition: a source already used nearby costs more, so the same
    // exemplar patch is not copied over and over.
    // Near-ties: the seed's jitter of up to kNearTie decides.
    const double jitter = 1.0 +
      kNearTie *
        seededUniform(o_.seed, kStreamChoice, result_.placements.size() * kMaxCandidates + c);
    const double seam = ((t.dry.overlapCells > 0 ? t.dry.normalisedCost : 0.0) +
                          o_.repetitionPenalty * reuses(candidates[c])) *
      jitter;
    if (seam < bestSeam)
    {
      bestSeam = seam;
      best = c;
    }
  }
  return best;
}

void PatchPlacement::record(const PatchCandidate& chosen,
  const Trial& t,
  const MergeResult& r,
  int x0,
  int y0,
  double seam)
{
  const int id = static_cast<int>(result_.placements.size());
  for (int j = 0; j < r.height; ++j)
  {
    for (int i = 0; i < r.width; ++i)
    {
      const std::size_t w = windowCell(i, j, r.width);
      const std::size_t c = out_.index(r.x0 + i, r.y0 + j);
      if (r.takeNew[w] != 0)
      {
        result_.patchId[c] = id;
        result_.matchCost[c] = chosen.cost;
        result_.seam[c] = 0;
      }
      if (r.seam[w] != 0)
      {
        result_.seam[c] = 1;
      }
    }
  }
  Placement p;
  p.order = id;
  p.feature = chosen.feature;
  p.exemplar = chosen.exemplar;
  p.variant = chosen.variant;
  p.sourceX = chosen.centreX;
  p.sourceY = chosen.centreY;
  p.x0 = x0;
  p.y0 = y0;
  p.matchCost = chosen.cost;
  p.landformMisfit = chosen.landformMisfit;
  p.seamCost = seam;
  p.offset = t.offset;
  p.lineOffset = t.lineOffset;
  result_.placements.push_back(p);
  recordSource(result_.placements.size() - 1);
}

std::size_t PatchPlacement::place(const std::vector<PatchCandidate>& candidates,
  int x0,
  int y0,
  bool feature)
{
  if (candidates.empty())
  {
    return 0;
  }
  const std::vector<std::uint8_t> strokeCells =
    feature ? strokeCore(x0, y0) : std::vector<std::uint8_t>();
  // Every feature candidate's line offset, then the patch and dry run of
  // each that choose() may take, in parallel (one merger workspace per
  // thread); choose() reads them in candidate order, so it does not depend
  // on the thread count. Patches of candidates choose() passes over are
  // never cut out: on a DEM target that was 60% of them.
  std::vector<Trial> trials(candidates.size());
  const int threads = static_cast<int>(std::min(candidates.size(), mergers_.size()));
  if (feature)
  {
#pragma omp parallel for schedule(dynamic) num_threads(threads)
    for (std::size_t c = 0; c < candidates.size(); ++c)
    {
      alignTrial(candidates[c], x0, y0, trials[c]);
    }
  }
  const float aligned = bestAlignment(trials);
  if (feature && crowded_)
  {
    keepBestAligned(trials, aligned);
  }
  auto tryCandidate = [&](std::size_t c, PatchMerger& merger)
  {
    Trial& t = trials[c];
    prepareTrial(candidates[c], x0, y0, feature, strokeCells, t);
    t.dry = merger.seamCost(out_, filled_, t.patch, x0, y0, feature ? &t.core : nullptr);
  };
#pragma omp parallel for schedule(dynamic) num_threads(threads)
  for (std::size_t c = 0; c < candidates.size(); ++c)
  {
    if (eligible(trials[c], aligned))
    {
      tryCandidate(c, mergers_[threadSlot()]);
    }
  }
  double seam = 0.0;
  const std::size_t chosen = choose(candidates, trials, aligned, seam);
  const auto seamTrials = static_cast<int>(std::count_if(
    trials.begin(), trials.end(), [&](const Trial& t) { return eligible(t, aligned); }));
  Trial& t = trials[chosen];
  if (!eligible(t, aligned))
  {
    // No candidate had a finite seam cost and choose() fell back to the first.
    tryCandidate(chosen, mergers_[0]);
  }
  MergeOptions mo;
  mo.mode = o_.merge;
  mo.shepardRadius = kShepardRadiusInPatches * P_;
  mo.lowestHeight = lowest_;
  mo.highestHeight = highest_;
  const MergeResult r =
    mergers_[0].merge(out_, filled_, t.patch, x0, y0, feature ? &t.core : nullptr, mo, &t.dry);
  result_.anchoredMerges += r.anchored ? 1 : 0;
  record(candidates[chosen], t, r, x0, y0, seam);
  result_.placements.back().seamTrials = std::max(1, seamTrials);
  return r.newCells;
}

void PatchPlacement::boundHeights(const std::vector<const Heightfield*>& exemplars)
{
  float lo = std::numeric_limits<float>::infinity();
  float hi = -std::numeric_limits<float>::infinity();
  for (const Heightfield* e : exemplars)
  {
    for (std::size_t c = 0; c < e->size(); ++c)
    {
      if (e->isValid(c) && std::isfinite(e->z[c]))
      {
        lo = std::min(lo, e->z[c]);
        hi = std::max(hi, e->z[c]);
      }
    }
  }
  if (lo <= hi)
  {
    const float slack = static_cast<float>(kHeightSlackShare) * (hi - lo);
    lowest_ = lo - slack;
    highest_ = hi + slack;
  }
}

void PatchPlacement::setTypicalNoise(const std::array<float, kNoiseLevels>& t)
{
  typicalNoise_ = t;
}

void PatchPlacement::placeFeatures()
{
  placeFeatures(sitesInOrder());
}

void PatchPlacement::placeFeatures(const std::vector<FeatureSite>& sites)
{
  for (std::size_t s = 0; s < sites.size() && !placementsDone(); ++s)
  {
    const FeatureSite& site = sites[s];
    const int x0 = windowCorner(site.centre.x, P_);
    const int y0 = windowCorner(site.centre.y, P_);
    FeatureQuery q =
      makeFeatureQuery(site, target_.field, noise_, &out_, &filled_, P_, &lowTarget_, &confidence_);
    if (!target_.detailed)
    {
      // A drawing says nothing of roughness: nothing is asked (the fill asks
      // for the exemplars' typical roughness to undo its SSD's preference for
      // smooth windows; the profiles here have no such bias, and asking
      // raised the seam index, 0.893 -> 0.910 on six Colorado terrains).
      q.noise.fill(0.0f);
    }
    const DenseQuery fallback = window(x0, y0);
    place(allowed(
            matcher_->matchFeature(q, &fallback), x0, y0, o_.k * matcher_->pool().exemplars.size()),
      x0,
      y0,
      true);
    report(0.1 + 0.3 * static_cast<double>(s + 1) / static_cast<double>(sites.size()), "features");
  }
}

void PatchPlacement::fill()
{
  const FillGrid g = fillGrid(out_.width, out_.height, P_, o_.fillSpacing, o_.seed);
  FillSteps steps;
  steps.filledShare = [this](int x0, int y0) { return filledShare(x0, y0); };
  steps.fillWindow = [this](int x0, int y0)
  {
    if (placementsDone())
    {
      return std::size_t{ 0 }; // the window is retired unfilled, at no cost
    }
    return place(
      allowed(matcher_->matchDense(window(x0, y0), regionExemplars(x0, y0)), x0, y0, o_.fillK),
      x0,
      y0,
      false);
  };
  steps.progress = [this](double f) { report(0.4 + 0.6 * f, "fill"); };
  runFill(g, fillDataTerms(target_.field, g, P_), o_.fill, o_.seed, steps);
}

double PatchPlacement::filledShare(int x0, int y0) const
{
  std::size_t known = 0;
  std::size_t cells = 0;
  for (int j = y0; j < std::min(out_.height, y0 + P_); ++j)
  {
    for (int i = x0; i < std::min(out_.width, x0 + P_); ++i)
    {
      known += filled_[out_.index(i, j)];
      ++cells;
    }
  }
  return cells > 0 ? static_cast<double>(known) / static_cast<double>(cells) : 1.0;
}

void PatchPlacement::releasePlacement()
{
  matcher_ = nullptr;
  noise_ = NoiseVariance();
  lowTarget_ = Heightfield();
  std::vector<float>().swap(toRidge_);
  std::vector<float>().swap(toValley_);
  std::vector<std::uint8_t>().swap(line_);
  std::vector<PatchMerger>().swap(mergers_);
  sources_.clear();
}

SynthesisResult PatchPlacement::finish()
{
  std::size_t empty = 0;
  for (std::size_t c = 0; c < out_.size(); ++c)
  {
    if (filled_[c] == 0)
    {
      out_.z[c] =
        target_.field.isValid(c) ? target_.field.z[c] : std::numeric_limits<float>::quiet_NaN();
      ++empty;
    }
  }
  if (empty > 0)
  {
    result_.warnings.push_back(std::to_string(empty) +
      " cells could not be filled from the exemplars and hold the target heights.");
  }
  normaliseMask(out_);
  result_.patches = out_;
  FinishingPlan plan;
  plan.patchSize = P_;
  plan.correctionScale = o_.correctionScale;
  plan.drainValleys = o_.drainValleys;
  plan.drainage = o_.drainage;
  // The bounds the merge kept to are the exemplars' range widened by the slack.
  plan.slack = kHeightSlackShare * (highest_ - lowest_) / (1.0 + 2.0 * kHeightSlackShare);
  plan.lowest = lowest_ + plan.slack;
  plan.highest = highest_ - plan.slack;
  result_.finishing = finishSynthesis(out_, target_, confidence_, plan);
  result_.terrain = std::move(out_);
  return std::move(result_);
}

SynthesisResult PatchPlacement::unfinished()
{
  normaliseMask(out_);
  result_.patches = out_;
  result_.terrain = std::move(out_);
  return std::move(result_);
}

void PatchPlacement::report(double fraction, const char* stage) const
{
  reportProgress(o_.progress, fraction, stage);
}

std::vector<FeatureSite> PatchPlacement::sitesOf(const SynthesisTile& t,
  const std::vector<FeatureSite>& all) const
{
  std::vector<FeatureSite> own;
  for (FeatureSite site : all)
  {
    const long x = std::lround(site.centre.x);
    const long y = std::lround(site.centre.y);
    if (x < t.x0 || y < t.y0 || x >= t.x0 + t.width || y >= t.y0 + t.height)
    {
      continue;
    }
    site.centre = { site.centre.x - t.regionX0, site.centre.y - t.regionY0 };
    for (ControlPoint& arm : site.arms)
    {
      arm.position = { arm.position.x - t.regionX0, arm.position.y - t.regionY0 };
    }
    own.push_back(site);
  }
  return own;
}

std::vector<FeatureSite> PatchPlacement::sitesInOrder() const
{
  return featurePlacementOrder(target_, P_, o_.seed);
}

void PatchPlacement::freeze(std::vector<std::uint8_t> cells)
{
  frozen_ = std::move(cells);
}

Heightfield PatchPlacement::knownIn(const SynthesisTile& t) const
{
  Heightfield known(t.regionWidth, t.regionHeight, std::numeric_limits<float>::quiet_NaN());
  known.valid.assign(known.size(), 0);
  for (int j = 0; j < t.regionHeight; ++j)
  {
    for (int i = 0; i < t.regionWidth; ++i)
    {
      const std::size_t c = out_.index(t.regionX0 + i, t.regionY0 + j);
      if (filled_[c] != 0)
      {
        known.at(i, j) = out_.z[c];
        known.valid[known.index(i, j)] = 1;
      }
    }
  }
  return known;
}

TileOutcome PatchPlacement::outcome(std::size_t tile,
  const std::vector<std::uint8_t>& dropped) const
{
  TileOutcome o;
  o.tile = tile;
  o.kept.resize(out_.size());
  for (std::size_t c = 0; c < out_.size(); ++c)
  {
    o.kept[c] = filled_[c] != 0 && (dropped.empty() || dropped[c] == 0) ? 1 : 0;
  }
  o.heights = out_.z;
  o.patchId.assign(result_.patchId.begin(), result_.patchId.end());
  o.seam = result_.seam;
  o.matchCost = result_.matchCost;
  o.placements = result_.placements;
  o.anchoredMerges = result_.anchoredMerges;
  return o;
}

void PatchPlacement::adopt(const SynthesisTile& t, const TileOutcome& tile)
{
  const int first = static_cast<int>(result_.placements.size());
  for (int j = 0; j < t.regionHeight; ++j)
  {
    for (int i = 0; i < t.regionWidth; ++i)
    {
      const std::size_t from = rowMajor(i, j, t.regionWidth);
      const std::size_t to = out_.index(t.regionX0 + i, t.regionY0 + j);
      if (tile.kept[from] == 0)
      {
        continue;
      }
      out_.z[to] = tile.heights[from];
      filled_[to] = 1;
      if (tile.patchId[from] >= 0)
      {
        result_.patchId[to] = first + tile.patchId[from];
        result_.matchCost[to] = tile.matchCost[from];
        result_.seam[to] = tile.seam[from];
      }
      else if (tile.seam[from] != 0)
      {
        result_.seam[to] = 1;
      }
    }
  }
  for (Placement p : tile.placements)
  {
    p.order += first;
    p.x0 += t.regionX0;
    p.y0 += t.regionY0;
    result_.placements.push_back(p);
  }
  // The tile's count is a fixed-width std::uint64_t (tiles cross processes): a conversion.
  result_.anchoredMerges += static_cast<std::size_t>(tile.anchoredMerges);
}

std::unique_ptr<PatchMatcher> makeSynthesisMatcher(const std::vector<const Heightfield*>& exemplars,
  const std::vector<const FeatureGraph*>& graphs,
  const SynthesisOptions& o)
{
  MatcherOptions mo;
  mo.patchSize = o.patchSize;
  mo.backend = o.backend;
  mo.k = o.k;
  mo.weights.verticalOffset = o.verticalOffset;
  mo.pool = o.pool;
  return std::make_unique<PatchMatcher>(exemplars, graphs, mo);
}

} // namespace tsynth
