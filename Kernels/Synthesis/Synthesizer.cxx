#include "Synthesizer.h"

#include "../Core/Error.h"
#include "../Features/Ppa.h"
#include "../Merging/Poisson.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <queue>
#include <unordered_map>

#include <omp.h>

namespace tsynth
{
namespace
{

using Clock = std::chrono::steady_clock;

constexpr float kLineHalfWidth = 3.0f; // cells each side of a sketched line
constexpr int kMaxAttempts = 4;        // placements tried at one fill site
// Default shape scale, as a fraction of the patch (6 cells for 80-cell patches):
// finer than the 8-cell flanks the fidelity metric tests a crest against.
constexpr double kShapeFraction = 0.075;

double secondsSince(Clock::time_point t0)
{
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Everything the placement loop shares.
class SynthesisState
{
public:
  SynthesisState(const SynthesisTarget& target, PatchMatcher& matcher, const SynthesisOptions& o)
    : target_(target)
    , matcher_(matcher)
    , o_(o)
    , P_(o.patchSize)
    , out_(target.field.width, target.field.height, std::numeric_limits<float>::quiet_NaN())
    , filled_(out_.size(), 0)
    , noise_(target.field)
  {
    out_.cellX = target.field.cellX;
    out_.cellY = target.field.cellY;
    out_.cellSizeKnown = true;
    out_.georef = target.field.georef;
    result_.patchId.assign(out_.size(), -1);
    result_.seam.assign(out_.size(), 0);
    result_.matchCost.assign(out_.size(), std::numeric_limits<float>::quiet_NaN());
    // Cells within a few cells of the sketched lines: feature patches own them,
    // fill patches may not take them once they are filled.
    const std::vector<float> d = distanceTransform(
      rasteriseChains(target.graph, out_.width, out_.height), out_.width, out_.height);
    line_.assign(out_.size(), 0);
    for (std::size_t c = 0; c < d.size(); ++c)
    {
      line_[c] = d[c] <= kLineHalfWidth ? 1 : 0;
    }
  }

  // The patch-sized window of the output at (x0, y0): known cells, else the target.
  DenseQuery window(int x0, int y0) const
  {
    DenseQuery q;
    q.heights.assign(static_cast<std::size_t>(P_ * P_), 0.0f);
    q.known.assign(static_cast<std::size_t>(P_ * P_), 0);
    std::size_t known = 0;
    for (int j = 0; j < P_; ++j)
    {
      for (int i = 0; i < P_; ++i)
      {
        const int x = x0 + i;
        const int y = y0 + j;
        if (x < 0 || y < 0 || x >= out_.width || y >= out_.height)
        {
          continue;
        }
        const std::size_t c = out_.index(x, y);
        const std::size_t k = static_cast<std::size_t>(j * P_ + i);
        if (filled_[c] != 0)
        {
          q.heights[k] = out_.z[c];
          q.known[k] = 1;
          ++known;
        }
      }
    }
    if (known == 0)
    {
      // Nothing synthesised here yet: match the target's shape instead.
      for (int j = 0; j < P_; ++j)
      {
        for (int i = 0; i < P_; ++i)
        {
          const int x = x0 + i;
          const int y = y0 + j;
          if (x >= 0 && y >= 0 && x < out_.width && y < out_.height && target_.field.isValid(x, y))
          {
            const std::size_t k = static_cast<std::size_t>(j * P_ + i);
            q.heights[k] = target_.field.at(x, y);
            q.known[k] = 1;
          }
        }
      }
    }
    q.noise = noise_.window(x0 + 0.5 * P_, y0 + 0.5 * P_, P_);
    return q;
  }

  // The candidate's patch, read from the exemplar seen through its variant.
  Heightfield extract(const PatchCandidate& c) const
  {
    for (const DenseMatcher::Oriented& r : matcher_.dense().oriented())
    {
      if (r.exemplar != c.exemplar || r.variant != c.variant)
      {
        continue;
      }
      const Variant v = variant(c.variant);
      const auto& ex = matcher_.pool().exemplars[static_cast<std::size_t>(c.exemplar)];
      const double dx = c.centreX - 0.5 * (ex.width - 1);
      const double dy = c.centreY - 0.5 * (ex.height - 1);
      const double det = v.m[0] * v.m[3] - v.m[1] * v.m[2];
      const double px = r.centreX + (v.m[3] * dx - v.m[1] * dy) / det;
      const double py = r.centreY + (-v.m[2] * dx + v.m[0] * dy) / det;
      const int x0 = static_cast<int>(std::lround(px)) - P_ / 2;
      const int y0 = static_cast<int>(std::lround(py)) - P_ / 2;
      Heightfield patch(P_, P_, std::numeric_limits<float>::quiet_NaN());
      patch.cellX = out_.cellX;
      patch.cellY = out_.cellY;
      patch.valid.assign(patch.size(), 0);
      for (int j = 0; j < P_; ++j)
      {
        for (int i = 0; i < P_; ++i)
        {
          const int x = x0 + i;
          const int y = y0 + j;
          if (x >= 0 && y >= 0 && x < r.full.width && y < r.full.height && r.full.isValid(x, y))
          {
            patch.at(i, j) = r.full.at(x, y);
            patch.valid[patch.index(i, j)] = 1;
          }
        }
      }
      normaliseMask(patch);
      return patch;
    }
    throw Error("Internal error: no oriented exemplar for a candidate.");
  }

  // Shift to fit what the patch overlaps (or, with no overlap, the target).
  float fitOffset(const Heightfield& patch, int x0, int y0) const
  {
    double sOverlap = 0.0;
    double nOverlap = 0.0;
    double sTarget = 0.0;
    double nTarget = 0.0;
    for (int j = 0; j < P_; ++j)
    {
      for (int i = 0; i < P_; ++i)
      {
        const int x = x0 + i;
        const int y = y0 + j;
        if (!patch.isValid(i, j) || x < 0 || y < 0 || x >= out_.width || y >= out_.height)
        {
          continue;
        }
        const std::size_t c = out_.index(x, y);
        if (filled_[c] != 0)
        {
          sOverlap += static_cast<double>(out_.z[c]) - patch.at(i, j);
          nOverlap += 1.0;
        }
        if (target_.field.isValid(x, y))
        {
          sTarget += static_cast<double>(target_.field.at(x, y)) - patch.at(i, j);
          nTarget += 1.0;
        }
      }
    }
    if (nOverlap >= 0.05 * P_ * P_)
    {
      return static_cast<float>(sOverlap / nOverlap);
    }
    return nTarget > 0 ? static_cast<float>(sTarget / nTarget) : 0.0f;
  }

  // Fill patches leave the sketched lines that feature patches already hold.
  void protectLines(Heightfield& patch, int x0, int y0) const
  {
    bool any = false;
    for (int j = 0; j < P_; ++j)
    {
      for (int i = 0; i < P_; ++i)
      {
        const int x = x0 + i;
        const int y = y0 + j;
        if (x >= 0 && y >= 0 && x < out_.width && y < out_.height)
        {
          const std::size_t c = out_.index(x, y);
          if (line_[c] != 0 && filled_[c] != 0)
          {
            if (!any)
            {
              patch.valid.resize(patch.size(), 1);
              any = true;
            }
            patch.valid[patch.index(i, j)] = 0;
            patch.at(i, j) = std::numeric_limits<float>::quiet_NaN();
          }
        }
      }
    }
  }

  // Chooses among candidates by seam cost and merges the winner at (x0, y0).
  // The exemplars that may serve the region at the window's centre (null: all).
  const std::vector<int>* regionExemplars(int x0, int y0) const
  {
    if (o_.regionLabels.empty())
    {
      return nullptr;
    }
    const int x = std::clamp(x0 + P_ / 2, 0, out_.width - 1);
    const int y = std::clamp(y0 + P_ / 2, 0, out_.height - 1);
    const int label = o_.regionLabels[out_.index(x, y)];
    if (label < 0 || static_cast<std::size_t>(label) >= o_.regionExemplars.size() ||
      o_.regionExemplars[static_cast<std::size_t>(label)].empty())
    {
      return nullptr;
    }
    return &o_.regionExemplars[static_cast<std::size_t>(label)];
  }

  // Keeps the candidates whose exemplar may serve the region at the window's centre.
  std::vector<PatchCandidate> allowed(std::vector<PatchCandidate> candidates,
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

  // How many placements already took a source within half a patch of this one.
  int reuses(const PatchCandidate& c) const
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

  // Sources used so far, bucketed by exemplar and half-patch cell, so reuses()
  // looks at neighbours only instead of every earlier placement.
  static std::int64_t sourceKey(int exemplar, long x, long y)
  {
    return (static_cast<std::int64_t>(exemplar) << 42) ^
      (static_cast<std::int64_t>(x + (1L << 20)) << 21) ^ static_cast<std::int64_t>(y + (1L << 20));
  }

  void recordSource(std::size_t placement)
  {
    const Placement& p = result_.placements[placement];
    const double radius = 0.5 * P_;
    sources_[sourceKey(p.exemplar,
               static_cast<long>(std::floor(p.sourceX / radius)),
               static_cast<long>(std::floor(p.sourceY / radius)))]
      .push_back(placement);
  }

  // Returns how many empty cells the placement filled (0 if none could be).
  std::size_t place(const std::vector<PatchCandidate>& candidates, int x0, int y0, bool feature)
  {
    if (candidates.empty())
    {
      return 0;
    }
    std::vector<std::uint8_t> core;
    if (feature)
    {
      // The patch owns the sketched line near its centre (where its own feature
      // was matched) and a small disc around the centre.
      core.assign(static_cast<std::size_t>(P_ * P_), 0);
      for (int j = 0; j < P_; ++j)
      {
        for (int i = 0; i < P_; ++i)
        {
          const double r = std::hypot(i - 0.5 * (P_ - 1), j - 0.5 * (P_ - 1));
          const int x = x0 + i;
          const int y = y0 + j;
          const bool onLine =
            x >= 0 && y >= 0 && x < out_.width && y < out_.height && line_[out_.index(x, y)] != 0;
          if (r <= P_ / 8.0 || (onLine && r <= P_ / 4.0))
          {
            core[static_cast<std::size_t>(j * P_ + i)] = 1;
          }
        }
      }
    }
    // Every candidate's dry-run seam cost, in parallel (one merger workspace per
    // thread); the choice below reads them in candidate order, so it does not
    // depend on the thread count.
    std::vector<Heightfield> patches(candidates.size());
    std::vector<float> offsets(candidates.size(), 0.0f);
    std::vector<MergeResult> dry(candidates.size());
    const long count = static_cast<long>(candidates.size());
#pragma omp parallel for schedule(dynamic)                                                         \
  num_threads(static_cast <int>(std::min <std::size_t>(candidates.size(), mergers_.size())))
    for (long n = 0; n < count; ++n)
    {
      const std::size_t c = static_cast<std::size_t>(n);
      Heightfield patch = extract(candidates[c]);
      if (!feature)
      {
        protectLines(patch, x0, y0);
      }
      offsets[c] = o_.verticalOffset ? fitOffset(patch, x0, y0) : 0.0f;
      for (float& z : patch.z)
      {
        z += offsets[c];
      }
      PatchMerger& merger = mergers_[static_cast<std::size_t>(omp_get_thread_num())];
      dry[c] = merger.seamCost(out_, filled_, patch, x0, y0, feature ? &core : nullptr);
      patches[c] = std::move(patch);
    }
    std::size_t bestIndex = 0;
    double bestSeam = std::numeric_limits<double>::infinity();
    for (std::size_t c = 0; c < candidates.size(); ++c)
    {
      // Anti-repetition: a source already used nearby costs more, so the same
      // exemplar patch is not copied over and over.
      const double seam = (dry[c].overlapCells > 0 ? dry[c].normalisedCost : 0.0) +
        o_.repetitionPenalty * reuses(candidates[c]);
      if (seam < bestSeam)
      {
        bestSeam = seam;
        bestIndex = c;
      }
    }
    const Heightfield& best = patches[bestIndex];
    const float bestOffset = offsets[bestIndex];
    MergeOptions mo;
    mo.mode = o_.merge;
    const MergeResult r = mergers_[0].merge(
      out_, filled_, best, x0, y0, feature ? &core : nullptr, mo, &dry[bestIndex]);
    const int id = static_cast<int>(result_.placements.size());
    const PatchCandidate& chosen = candidates[bestIndex];
    for (int j = 0; j < r.height; ++j)
    {
      for (int i = 0; i < r.width; ++i)
      {
        const std::size_t w = static_cast<std::size_t>(j * r.width + i);
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
    p.seamCost = bestSeam;
    p.offset = bestOffset;
    result_.placements.push_back(p);
    recordSource(result_.placements.size() - 1);
    return r.newCells;
  }

  void placeFeatures()
  {
    const std::vector<FeatureSite> sites = orderedSites();
    for (std::size_t s = 0; s < sites.size(); ++s)
    {
      const FeatureSite& site = sites[s];
      const int x0 = static_cast<int>(std::lround(site.centre.x)) - P_ / 2;
      const int y0 = static_cast<int>(std::lround(site.centre.y)) - P_ / 2;
      const FeatureQuery q = makeFeatureQuery(site, target_.field, noise_, &out_, &filled_, P_);
      const DenseQuery fallback = window(x0, y0);
      place(allowed(
              matcher_.matchFeature(q, &fallback), x0, y0, o_.k * matcher_.pool().exemplars.size()),
        x0,
        y0,
        true);
      report(
        0.1 + 0.3 * static_cast<double>(s + 1) / static_cast<double>(sites.size()), "features");
    }
  }

  void fill()
  {
    const int w = out_.width;
    const int h = out_.height;
    const int step = std::max(1, P_ / 2);
    std::vector<int> xs;
    std::vector<int> ys;
    for (int x = 0; x + P_ < w; x += step)
    {
      xs.push_back(x);
    }
    xs.push_back(std::max(0, w - P_));
    for (int y = 0; y + P_ < h; y += step)
    {
      ys.push_back(y);
    }
    ys.push_back(std::max(0, h - P_));
    xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
    ys.erase(std::unique(ys.begin(), ys.end()), ys.end());
    const std::size_t sites = xs.size() * ys.size();

    // Data term: mean slope of the target in each window, scaled to 0..1.
    std::vector<double> data(sites, 0.0);
    double maxData = 0.0;
    for (std::size_t s = 0; s < sites; ++s)
    {
      const int x0 = xs[s % xs.size()];
      const int y0 = ys[s / xs.size()];
      double g = 0.0;
      for (int j = y0; j < std::min(h - 1, y0 + P_); j += 4)
      {
        for (int i = x0; i < std::min(w - 1, x0 + P_); i += 4)
        {
          if (target_.field.isValid(i, j) && target_.field.isValid(i + 1, j) &&
            target_.field.isValid(i, j + 1))
          {
            g += std::hypot((target_.field.at(i + 1, j) - target_.field.at(i, j)) / out_.cellX,
              (target_.field.at(i, j + 1) - target_.field.at(i, j)) / out_.cellY);
          }
        }
      }
      data[s] = g;
      maxData = std::max(maxData, g);
    }
    for (double& d : data)
    {
      d = maxData > 0 ? d / maxData : 0.0;
    }
    auto stateOf = [&](std::size_t s, double& priority)
    {
      const int x0 = xs[s % xs.size()];
      const int y0 = ys[s / xs.size()];
      std::size_t known = 0;
      std::size_t cells = 0;
      for (int j = y0; j < std::min(h, y0 + P_); ++j)
      {
        for (int i = x0; i < std::min(w, x0 + P_); ++i)
        {
          known += filled_[out_.index(i, j)];
          ++cells;
        }
      }
      const double confidence =
        cells > 0 ? static_cast<double>(known) / static_cast<double>(cells) : 1.0;
      priority = confidence + (o_.fill == FillOrder::BestFirst ? data[s] : 0.0);
      return known < cells; // still has empty cells
    };
    // Max-heap of (priority, -site) with version stamps: only the sites a merge
    // touched are re-scored, nothing is re-sorted.
    using Entry = std::pair<double, long>;
    std::priority_queue<Entry> heap;
    std::vector<int> version(sites, 0);
    std::vector<int> attempts(sites, 0);
    std::vector<std::uint8_t> retired(sites, 0);
    std::size_t open = 0;
    for (std::size_t s = 0; s < sites; ++s)
    {
      double p = 0.0;
      if (stateOf(s, p))
      {
        heap.push({ p, -static_cast<long>(s) * 1024 - 0 });
        ++open;
      }
    }
    const std::size_t initial = std::max<std::size_t>(1, open);
    std::size_t done = 0;
    while (!heap.empty())
    {
      const auto [priority, key] = heap.top();
      heap.pop();
      const std::size_t s = static_cast<std::size_t>((-key) / 1024);
      const int stamp = static_cast<int>((-key) % 1024);
      if (stamp != version[s] % 1024)
      {
        continue; // superseded by a newer score
      }
      double now = 0.0;
      if (retired[s] != 0 || !stateOf(s, now))
      {
        continue;
      }
      const int x0 = xs[s % xs.size()];
      const int y0 = ys[s / xs.size()];
      // A window whose empty cells no candidate can cover (they fall outside
      // every rotated exemplar's valid area) is retired, never retried forever.
      const std::vector<PatchCandidate> candidates =
        allowed(matcher_.matchDense(window(x0, y0), regionExemplars(x0, y0)), x0, y0, o_.fillK);
      if (place(candidates, x0, y0, false) == 0 || ++attempts[s] >= kMaxAttempts)
      {
        retired[s] = 1;
      }
      ++done;
      // Re-score the sites whose windows this patch touched.
      const std::size_t cx = s % xs.size();
      const std::size_t cy = s / xs.size();
      for (std::size_t by = cy > 2 ? cy - 2 : 0; by <= std::min(ys.size() - 1, cy + 2); ++by)
      {
        for (std::size_t bx = cx > 2 ? cx - 2 : 0; bx <= std::min(xs.size() - 1, cx + 2); ++bx)
        {
          const std::size_t t = by * xs.size() + bx;
          double p = 0.0;
          if (retired[t] == 0 && stateOf(t, p))
          {
            ++version[t];
            heap.push({ p, -static_cast<long>(t) * 1024 - (version[t] % 1024) });
          }
        }
      }
      report(0.4 + 0.6 * std::min(1.0, static_cast<double>(done) / static_cast<double>(initial)),
        "fill");
    }
  }

  SynthesisResult finish()
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
    const double sigma = o_.shapeScale < 0.0 ? kShapeFraction * P_ : o_.shapeScale;
    if (sigma > 0.0)
    {
      // Near the sketched lines only (weight falling off over a quarter patch),
      // so the land between them keeps the exemplars' own large-scale relief.
      const Heightfield lowOut = gaussianSmooth(out_, sigma);
      const Heightfield lowTarget = gaussianSmooth(target_.field, sigma);
      const std::vector<float> d = distanceTransform(
        rasteriseChains(target_.graph, out_.width, out_.height), out_.width, out_.height);
      const double reach = 0.25 * P_;
      for (std::size_t c = 0; c < out_.size(); ++c)
      {
        if (out_.isValid(c) && lowTarget.isValid(c))
        {
          const double w =
            target_.graph.chains.empty() ? 1.0 : std::exp(-0.5 * d[c] * d[c] / (reach * reach));
          out_.z[c] += static_cast<float>(w * (lowTarget.z[c] - lowOut.z[c]));
        }
      }
    }
    meetConstraints();
    result_.terrain = std::move(out_);
    return std::move(result_);
  }

  // Height constraints (poly-line Elevation): the terrain is bent so the
  // constrained lines sit exactly at their heights. The correction is harmonic
  // between the lines and fades to zero a patch away (Tasse's final deformation).
  void meetConstraints()
  {
    const int w = out_.width;
    const int h = out_.height;
    std::vector<double> correction(out_.size(), std::numeric_limits<double>::quiet_NaN());
    std::vector<std::uint8_t> onLine(out_.size(), 0);
    bool any = false;
    for (const FeatureChain& c : target_.graph.chains)
    {
      if (c.constraint.size() != c.points.size())
      {
        continue;
      }
      // Heights along the chain: given values, linear in between, none past the ends.
      std::vector<double> z(c.points.size(), std::numeric_limits<double>::quiet_NaN());
      int last = -1;
      for (std::size_t k = 0; k < c.points.size(); ++k)
      {
        if (std::isnan(c.constraint[k]))
        {
          continue;
        }
        z[k] = c.constraint[k];
        if (last >= 0)
        {
          for (std::size_t m = static_cast<std::size_t>(last) + 1; m < k; ++m)
          {
            const double t = static_cast<double>(m - static_cast<std::size_t>(last)) /
              static_cast<double>(k - static_cast<std::size_t>(last));
            z[m] = (1 - t) * c.constraint[static_cast<std::size_t>(last)] + t * c.constraint[k];
          }
        }
        last = static_cast<int>(k);
      }
      for (std::size_t k = 1; k < c.points.size(); ++k)
      {
        if (std::isnan(z[k - 1]) || std::isnan(z[k]))
        {
          continue;
        }
        const Point2& a = c.points[k - 1];
        const Point2& b = c.points[k];
        const int steps =
          std::max(1, static_cast<int>(std::ceil(2.0 * std::hypot(b.x - a.x, b.y - a.y))));
        for (int s = 0; s <= steps; ++s)
        {
          const double t = static_cast<double>(s) / steps;
          const int i = static_cast<int>(std::lround(a.x + t * (b.x - a.x)));
          const int j = static_cast<int>(std::lround(a.y + t * (b.y - a.y)));
          if (i >= 0 && j >= 0 && i < w && j < h && out_.isValid(i, j))
          {
            const std::size_t cell = out_.index(i, j);
            correction[cell] = (1 - t) * z[k - 1] + t * z[k] - out_.z[cell];
            onLine[cell] = 1;
            any = true;
          }
        }
      }
    }
    if (!any)
    {
      return;
    }
    const std::vector<float> d = distanceTransform(onLine, w, h);
    std::vector<std::uint8_t> unknown(out_.size(), 0);
    for (std::size_t c = 0; c < out_.size(); ++c)
    {
      if (onLine[c] == 0)
      {
        if (d[c] < P_ && out_.isValid(c))
        {
          unknown[c] = 1;
          correction[c] = 0.0;
        }
        else
        {
          correction[c] = 0.0; // Dirichlet: no change a patch away
        }
      }
    }
    std::vector<double> zero(out_.size(), 0.0);
    MaskedPoissonSolver solver;
    PoissonOptions po;
    po.tolerance = 1e-6;
    solver.solveLaplacian(
      w, h, out_.cellX, out_.cellY, unknown.data(), zero.data(), correction.data(), po);
    for (std::size_t c = 0; c < out_.size(); ++c)
    {
      if (out_.isValid(c) && std::isfinite(correction[c]))
      {
        out_.z[c] = static_cast<float>(out_.z[c] + correction[c]);
      }
    }
  }

  void report(double fraction, const char* stage) const
  {
    if (o_.progress)
    {
      o_.progress(fraction, stage);
    }
  }

private:
  // Breadth-first: each node, then the path points of its not yet visited chains.
  std::vector<FeatureSite> orderedSites() const
  {
    const std::vector<FeatureSite> all = featureSites(target_.graph, P_, 0.5 * P_);
    std::vector<std::vector<std::size_t>> pathsOfChain(target_.graph.chains.size());
    std::vector<std::size_t> siteOfNode(
      target_.graph.nodes.size(), std::numeric_limits<std::size_t>::max());
    for (std::size_t s = 0; s < all.size(); ++s)
    {
      if (all[s].node >= 0)
      {
        siteOfNode[static_cast<std::size_t>(all[s].node)] = s;
      }
      else if (all[s].chain >= 0)
      {
        pathsOfChain[static_cast<std::size_t>(all[s].chain)].push_back(s);
      }
    }
    std::vector<FeatureSite> ordered;
    std::vector<char> chainDone(target_.graph.chains.size(), 0);
    for (int v : target_.graph.bfsOrder)
    {
      const std::size_t node = static_cast<std::size_t>(v);
      if (siteOfNode[node] != std::numeric_limits<std::size_t>::max())
      {
        ordered.push_back(all[siteOfNode[node]]);
      }
      for (int c : target_.graph.nodes[node].chains)
      {
        if (chainDone[static_cast<std::size_t>(c)] != 0)
        {
          continue;
        }
        chainDone[static_cast<std::size_t>(c)] = 1;
        auto paths = pathsOfChain[static_cast<std::size_t>(c)];
        if (target_.graph.chains[static_cast<std::size_t>(c)].to == v)
        {
          std::reverse(paths.begin(), paths.end()); // walk away from this node
        }
        for (std::size_t s : paths)
        {
          ordered.push_back(all[s]);
        }
      }
    }
    return ordered;
  }

  const SynthesisTarget& target_;
  PatchMatcher& matcher_;
  const SynthesisOptions& o_;
  int P_;
  Heightfield out_;
  std::vector<std::uint8_t> filled_;
  std::vector<std::uint8_t> line_;
  NoiseVariance noise_;
  // One per OpenMP thread.
  std::vector<PatchMerger> mergers_ =
    std::vector<PatchMerger>(static_cast<std::size_t>(std::max(1, omp_get_max_threads())));
  SynthesisResult result_;
  std::unordered_map<std::int64_t, std::vector<std::size_t>> sources_;
};

} // namespace

SynthesisResult synthesize(const SynthesisTarget& target,
  const std::vector<const Heightfield*>& exemplars,
  const std::vector<const FeatureGraph*>& graphs,
  const SynthesisOptions& o)
{
  if (exemplars.empty())
  {
    throw Error("No exemplar: give at least one DEM to copy terrain from.");
  }
  if (target.field.width < o.patchSize || target.field.height < o.patchSize)
  {
    throw Error("The output (" + std::to_string(target.field.width) + " x " +
      std::to_string(target.field.height) + " cells) is smaller than one patch (" +
      std::to_string(o.patchSize) + ").");
  }
  if (!o.regionLabels.empty())
  {
    if (o.regionLabels.size() != target.field.size())
    {
      throw Error("The region labels must cover the output grid (" +
        std::to_string(target.field.width) + " x " + std::to_string(target.field.height) +
        " cells).");
    }
    for (std::size_t r = 0; r < o.regionExemplars.size(); ++r)
    {
      for (int e : o.regionExemplars[r])
      {
        if (e < 0 || static_cast<std::size_t>(e) >= exemplars.size())
        {
          throw Error("Region " + std::to_string(r) + " names exemplar " + std::to_string(e) +
            ", but there are " + std::to_string(exemplars.size()) + " exemplars.");
        }
      }
    }
  }
  auto t0 = Clock::now();
  if (o.progress)
  {
    o.progress(0.0, "setup");
  }
  MatcherOptions mo;
  mo.patchSize = o.patchSize;
  mo.backend = o.backend;
  mo.k = o.k;
  mo.weights.verticalOffset = o.verticalOffset;
  PatchMatcher matcher(exemplars, graphs, mo);
  SynthesisState state(target, matcher, o);
  const double setup = secondsSince(t0);
  state.report(0.1, "setup");
  t0 = Clock::now();
  state.placeFeatures();
  const double features = secondsSince(t0);
  t0 = Clock::now();
  state.fill();
  const double fill = secondsSince(t0);
  SynthesisResult r = state.finish();
  r.timings = { setup, features, fill };
  r.backend = matcher.backendName();
  r.warnings.insert(r.warnings.begin(), matcher.warnings().begin(), matcher.warnings().end());
  r.warnings.insert(r.warnings.begin(), target.warnings.begin(), target.warnings.end());
  return r;
}

} // namespace tsynth
