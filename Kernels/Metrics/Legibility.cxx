#include "Legibility.h"

#include "../Core/Error.h"
#include "../Core/Smoothing.h"
#include "../Features/ChainPath.h"
#include "../Features/CrossSections.h"
#include "../Features/Profiles.h"
#include "../Features/StrokeSpacing.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

namespace tsynth
{
namespace
{

// Samples every cell along the lines and across them.
constexpr double kSampleSpacing = 1.0;
// Random sections read through the terrain's land away from the strokes: as
// many as through one exemplar.
constexpr int kSectionsAround = 1500;
// ... where at least this share of the terrain is that far from every stroke.
constexpr double kLeastLandAway = 0.1;

double median(std::vector<double> v)
{
  if (v.empty())
  {
    return StrokeLegibility::kNaN;
  }
  const std::size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<long>(mid), v.end());
  return v[mid];
}

// The flanks' shading is read from this many cells out from the line (closer,
// the cells are the crest or floor itself, which slopes along the line) ...
constexpr int kFlankNearestCells = 2;
// ... to this share of the half width: the landform's own flank; farther out
// the land turns towards the next line or is the land around.
constexpr double kFlankReachInHalfWidths = 1.0 / 3.0;

struct Sample
{
  double prominence = 0.0;
  double flanks = StrokeLegibility::kNaN; // StrokeLegibility::flankAgreement of this section
  double threshold = 0.0;
  double halfWidth = 0.0;
  double along = 0.0;   // cells along its chain
  bool legible = false; // stands out, in a run the eye can follow (markRuns)
  bool standsOut() const { return prominence > 0.0 && prominence >= threshold; }
};

// A crest (floor) reads as a line only where it stands out along a stretch at
// least this many times its half width long: shorter stretches read as knobs
// (hollows). On a synthesis from Colorado, a short lone ridge no one could
// see on the hillshade stood out at 14 of its 50 samples, scattered: none
// count now; an arc that read along its left part only keeps 87 of its 102
// (of 200), the long stretch there.
constexpr double kRunInHalfWidths = 1.0;
// Gaps in a stretch the eye bridges: up to this share of the half width.
constexpr double kBridgeInHalfWidths = 0.25;

// Marks legible the samples of one chain (in order along it) that stand out
// in runs of at least kRunInHalfWidths half widths, gaps of at most
// kBridgeInHalfWidths half widths bridged.
void markRuns(std::vector<Sample>& chain)
{
  std::size_t k = 0;
  while (k < chain.size())
  {
    if (!chain[k].standsOut())
    {
      ++k;
      continue;
    }
    std::size_t last = k;
    std::size_t next = k + 1;
    for (; next < chain.size(); ++next)
    {
      const Sample& s = chain[next];
      if (s.along - chain[last].along > kBridgeInHalfWidths * s.halfWidth + kSampleSpacing)
      {
        break;
      }
      if (s.standsOut())
      {
        last = next;
      }
    }
    const double run = chain[last].along - chain[k].along + kSampleSpacing;
    const double width = 0.5 * (chain[k].halfWidth + chain[last].halfWidth);
    if (run >= kRunInHalfWidths * width)
    {
      for (std::size_t m = k; m <= last; ++m)
      {
        chain[m].legible = chain[m].standsOut();
      }
    }
    k = last + 1;
  }
}

class SectionReader
{
public:
  SectionReader(const Heightfield& terrain,
    const StrokeSpacing& spacing,
    const LandRelief& land,
    const LandRelief& around,
    const LegibilityOptions& o)
    : terrain_(terrain)
    , land_(land)
    , around_(around)
    , o_(o)
    , spacing_(spacing)
  {
  }

  // The cross-section at p across normal n; false where it cannot be read.
  bool read(const Point2& p, const Point2& n, FeatureType type, Sample& out) const
  {
    const int i = std::clamp(static_cast<int>(std::lround(p.x)), 0, terrain_.width - 1);
    const int j = std::clamp(static_cast<int>(std::lround(p.y)), 0, terrain_.height - 1);
    double h = std::min(o_.loneHalfWidth, static_cast<double>(strokeHalfSpacing(spacing_, i, j)));
    h = std::floor(std::min(h, roomInside(p, n)));
    if (!(h >= o_.minHalfWidth))
    {
      return false;
    }
    std::vector<double> z;
    if (!readSection(terrain_, p.x, p.y, n.x, n.y, static_cast<int>(h), z))
    {
      return false;
    }
    const bool ridge = type == FeatureType::Ridge;
    out.prominence = sectionProminence(z, ridge ? 1.0 : -1.0, o_.reading);
    out.threshold = o_.margin * std::max(land_.at(h), around_.at(h));
    out.halfWidth = h;
    out.flanks = flanks(p, n, h, ridge);
    return true;
  }

private:
  // The mean, over the flank cells either side of p across n, of the cosine
  // between the land's gradient there and the way the landform's flank rises
  // (a floor's: outwards) or falls (a crest's); NaN where none can be read.
  double flanks(const Point2& p, const Point2& n, double h, bool ridge) const
  {
    const int reach =
      std::max(kFlankNearestCells, static_cast<int>(std::floor(kFlankReachInHalfWidths * h)));
    const double cx = terrain_.cellX;
    const double cy = terrain_.cellY;
    double sum = 0.0;
    int count = 0;
    for (const int side : { -1, 1 })
    {
      const double outX = side * n.x * cx; // outwards on this side, metres
      const double outY = side * n.y * cy;
      const double out = std::hypot(outX, outY);
      for (int k = kFlankNearestCells; k <= reach; ++k)
      {
        const double x = p.x + side * k * n.x;
        const double y = p.y + side * k * n.y;
        const double east = sampleBilinear(terrain_, x + 1.0, y);
        const double west = sampleBilinear(terrain_, x - 1.0, y);
        const double north = sampleBilinear(terrain_, x, y + 1.0);
        const double south = sampleBilinear(terrain_, x, y - 1.0);
        const double gx = (east - west) / (2.0 * cx);
        const double gy = (north - south) / (2.0 * cy);
        const double g = std::hypot(gx, gy);
        if (!(g > 0.0) || !(out > 0.0)) // NaN (off the grid, nodata) or flat: no shading
        {
          continue;
        }
        const double rising = (gx * outX + gy * outY) / (g * out);
        sum += ridge ? -rising : rising;
        ++count;
      }
    }
    return count > 0 ? sum / count : StrokeLegibility::kNaN;
  }

  // How far the section can reach both ways from p along n inside the grid.
  double roomInside(const Point2& p, const Point2& n) const
  {
    double room = std::numeric_limits<double>::infinity();
    const double limits[2][3] = { { p.x, terrain_.width - 1 - p.x, n.x },
      { p.y, terrain_.height - 1 - p.y, n.y } };
    for (const auto& l : limits)
    {
      if (std::abs(l[2]) > 1e-12)
      {
        room = std::min(room, std::min(l[0], l[1]) / std::abs(l[2]));
      }
    }
    return room;
  }

  const Heightfield& terrain_;
  const LandRelief& land_;
  const LandRelief& around_;
  const LegibilityOptions& o_;
  const StrokeSpacing& spacing_;
};

// The samples of each connected stroke, counted as its chains are read.
class StrokeTally
{
public:
  explicit StrokeTally(std::size_t strokes)
    : readings_(strokes)
    , legible_(strokes, 0)
    , low_(strokes, Point2{ kInfinity, kInfinity })
    , high_(strokes, Point2{ -kInfinity, -kInfinity })
  {
  }
  void addLine(std::size_t stroke, const FeatureChain& c)
  {
    StrokeReading& r = readings_[stroke];
    r.type = c.type;
    r.length += c.length();
    for (const Point2& p : c.points)
    {
      low_[stroke] = { std::min(low_[stroke].x, p.x), std::min(low_[stroke].y, p.y) };
      high_[stroke] = { std::max(high_[stroke].x, p.x), std::max(high_[stroke].y, p.y) };
    }
  }
  void addSamples(std::size_t stroke, const std::vector<Sample>& samples)
  {
    readings_[stroke].samples += samples.size();
    for (const Sample& s : samples)
    {
      legible_[stroke] += s.legible ? 1 : 0;
    }
  }
  std::vector<StrokeReading> readings() const
  {
    std::vector<StrokeReading> out = readings_;
    for (std::size_t k = 0; k < out.size(); ++k)
    {
      if (out[k].samples > 0)
      {
        out[k].share = static_cast<double>(legible_[k]) / static_cast<double>(out[k].samples);
      }
      out[k].centre = { 0.5 * (low_[k].x + high_[k].x), 0.5 * (low_[k].y + high_[k].y) };
    }
    return out;
  }

private:
  static constexpr double kInfinity = std::numeric_limits<double>::infinity();
  std::vector<StrokeReading> readings_;
  std::vector<std::size_t> legible_;
  std::vector<Point2> low_;
  std::vector<Point2> high_;
};

// The index of the least legible stroke with enough samples, strokes.size()
// if none has; ties to the first.
std::size_t weakestStroke(const std::vector<StrokeReading>& strokes)
{
  std::size_t weakest = strokes.size();
  for (std::size_t k = 0; k < strokes.size(); ++k)
  {
    if (strokes[k].samples >= kMinWeakestStrokeSamples &&
      (weakest == strokes.size() || strokes[k].share < strokes[weakest].share))
    {
      weakest = k;
    }
  }
  return weakest;
}

StrokeLegibility summarise(const std::vector<Sample>& samples)
{
  StrokeLegibility r;
  r.samples = samples.size();
  if (samples.empty())
  {
    return r;
  }
  std::vector<double> prominence, threshold, width;
  std::size_t legible = 0;
  double flankSum = 0.0;
  for (const Sample& s : samples)
  {
    legible += s.legible ? 1 : 0;
    prominence.push_back(s.prominence);
    threshold.push_back(s.threshold);
    width.push_back(s.halfWidth);
    if (!std::isnan(s.flanks))
    {
      flankSum += s.flanks;
      ++r.flankSamples;
    }
  }
  r.share = static_cast<double>(legible) / static_cast<double>(samples.size());
  if (r.flankSamples > 0)
  {
    r.flankAgreement = flankSum / static_cast<double>(r.flankSamples);
  }
  r.prominence = median(prominence);
  r.threshold = median(threshold);
  r.halfWidth = median(width);
  return r;
}

// The flank agreement of both kinds: the mean over every sample that had
// flank cells to read, of either kind.
double flankAgreementOfBoth(const StrokeLegibility& ridge, const StrokeLegibility& valley)
{
  const std::size_t both = ridge.flankSamples + valley.flankSamples;
  if (both == 0)
  {
    return StrokeLegibility::kNaN;
  }
  auto sum = [](const StrokeLegibility& k)
  { return k.flankSamples > 0 ? k.flankAgreement * static_cast<double>(k.flankSamples) : 0.0; };
  return (sum(ridge) + sum(valley)) / static_cast<double>(both);
}

double pearson(const std::vector<float>& a, const std::vector<float>& b)
{
  double sa = 0.0, sb = 0.0, n = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k)
  {
    if (std::isfinite(a[k]) && std::isfinite(b[k]))
    {
      sa += a[k];
      sb += b[k];
      n += 1.0;
    }
  }
  if (n < 2.0)
  {
    return StrokeLegibility::kNaN;
  }
  const double ma = sa / n;
  const double mb = sb / n;
  double ab = 0.0, aa = 0.0, bb = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k)
  {
    if (std::isfinite(a[k]) && std::isfinite(b[k]))
    {
      ab += (a[k] - ma) * (b[k] - mb);
      aa += (a[k] - ma) * (a[k] - ma);
      bb += (b[k] - mb) * (b[k] - mb);
    }
  }
  return aa > 0.0 && bb > 0.0 ? ab / std::sqrt(aa * bb) : StrokeLegibility::kNaN;
}

// G(sigma) - G(2 sigma) at each sigma, NaN where either is invalid. A
// Gaussian two bands share is computed once.
std::vector<std::vector<float>> bandPasses(const Heightfield& hf, const std::vector<double>& sigmas)
{
  std::map<double, Heightfield> smoothed;
  auto at = [&](double sigma) -> const Heightfield&
  {
    auto found = smoothed.find(sigma);
    if (found == smoothed.end())
    {
      found = smoothed.emplace(sigma, smoothLarge(hf, sigma)).first;
    }
    return found->second;
  };
  std::vector<std::vector<float>> bands;
  for (double sigma : sigmas)
  {
    const Heightfield& fine = at(sigma);
    const Heightfield& coarse = at(2.0 * sigma);
    std::vector<float> band(hf.size(), std::numeric_limits<float>::quiet_NaN());
    for (std::size_t k = 0; k < hf.size(); ++k)
    {
      if (hf.isValid(k) && fine.isValid(k) && coarse.isValid(k))
      {
        band[k] = fine.z[k] - coarse.z[k];
      }
    }
    bands.push_back(std::move(band));
  }
  return bands;
}

// The terrain's own land away from the strokes: every cell nearer a stroke
// than `clearance` cells invalid, so that sections read through it see only
// land the sketch asked nothing of. Empty when less than kLeastLandAway of the
// terrain is that far: too few sections fit in it to say how rough it is.
Heightfield landAwayFromStrokes(const Heightfield& terrain,
  const StrokeSpacing& spacing,
  double clearance)
{
  Heightfield away = terrain;
  away.valid.assign(terrain.size(), 0);
  std::size_t kept = 0;
  for (std::size_t k = 0; k < terrain.size(); ++k)
  {
    if (terrain.isValid(k) && spacing.toStroke[k] >= clearance)
    {
      away.valid[k] = 1;
      ++kept;
    }
  }
  return static_cast<double>(kept) >= kLeastLandAway * static_cast<double>(terrain.size())
    ? away
    : Heightfield();
}

} // namespace

LegibilityMeter::LegibilityMeter(const FeatureGraph& sketch,
  const LandRelief& land,
  const LegibilityOptions& o)
  : sketch_(sketch)
  , land_(land)
  , options_(o)
{
  if (!(o.loneHalfWidth >= o.minHalfWidth && o.minHalfWidth >= 1.0 && o.margin >= 0.0 &&
        o.reading.lineShare >= 0.0 && o.reading.lineShare < 1.0 && o.reading.tolerance >= 0.0))
  {
    throw Error("Legibility options out of range.");
  }
  spacing_ = strokeSpacing(
    rasteriseChains(sketch, sketch.width, sketch.height), sketch.width, sketch.height);
  // Each stroke read at the width the synthesis draws it (Landform.cxx): a
  // short one's is a share of its length.
  limitByStrokeLength(spacing_, sketch, 1.0, 1.0);
}

Legibility LegibilityMeter::measure(const Heightfield& terrain) const
{
  if (sketch_.width != terrain.width || sketch_.height != terrain.height)
  {
    throw Error("The sketch's lines are on a " + std::to_string(sketch_.width) + " x " +
      std::to_string(sketch_.height) + " grid, the terrain is " + std::to_string(terrain.width) +
      " x " + std::to_string(terrain.height) + " cells.");
  }
  // A stroke must stand out of the land around it as this terrain has it, as
  // well as of the exemplars' land: a terrain whose own land is rougher than
  // the exemplars' hides its strokes in it (a ridge arc over Colorado, as
  // prominent as the exemplars' land asks, was lost among knobs as tall).
  const Heightfield away = landAwayFromStrokes(terrain, spacing_, options_.loneHalfWidth);
  const LandRelief around = away.size() > 0 ? LandRelief({ &away }, kSectionsAround) : LandRelief();
  const SectionReader reader(terrain, spacing_, land_, around, options_);
  std::vector<Sample> ridge, valley;
  std::size_t strokeCount = 0;
  const std::vector<std::size_t> strokeOf = connectedChainSets(sketch_, &strokeCount);
  StrokeTally tally(strokeCount);
  for (std::size_t chain = 0; chain < sketch_.chains.size(); ++chain)
  {
    const FeatureChain& c = sketch_.chains[chain];
    tally.addLine(strokeOf[chain], c);
    if (c.points.size() < 2)
    {
      continue;
    }
    const ChainPath path(c.points);
    std::vector<Sample> samples;
    for (double s = 0.0; s <= path.length(); s += kSampleSpacing)
    {
      Point2 n;
      Sample sample;
      if (path.normal(s, n) && reader.read(path.at(s), n, c.type, sample))
      {
        sample.along = s;
        samples.push_back(sample);
      }
    }
    markRuns(samples);
    tally.addSamples(strokeOf[chain], samples);
    std::vector<Sample>& kind = c.type == FeatureType::Ridge ? ridge : valley;
    kind.insert(kind.end(), samples.begin(), samples.end());
  }
  Legibility l;
  l.ridge = summarise(ridge);
  l.valley = summarise(valley);
  const std::size_t all = ridge.size() + valley.size();
  if (all > 0)
  {
    const double r = ridge.empty() ? 0.0 : l.ridge.share * static_cast<double>(ridge.size());
    const double v = valley.empty() ? 0.0 : l.valley.share * static_cast<double>(valley.size());
    l.share = (r + v) / static_cast<double>(all);
  }
  l.flankAgreement = flankAgreementOfBoth(l.ridge, l.valley);
  l.strokes = tally.readings();
  l.weakest = weakestStroke(l.strokes);
  return l;
}

Legibility evaluateLegibility(const Heightfield& terrain,
  const FeatureGraph& sketch,
  const LandRelief& land,
  const LegibilityOptions& options)
{
  return LegibilityMeter(sketch, land, options).measure(terrain);
}

std::vector<double> defaultCorrelationScales()
{
  return { 2.0, 4.0, 8.0, 16.0, 32.0 };
}

std::vector<BandCorrelation> bandPassCorrelation(const Heightfield& terrain,
  const Heightfield& target,
  const std::vector<double>& sigmas)
{
  return BandPassTarget(target, sigmas).correlate(terrain);
}

BandPassTarget::BandPassTarget(const Heightfield& target, std::vector<double> sigmas)
  : width_(target.width)
  , height_(target.height)
  , sigmas_(std::move(sigmas))
  , bands_(bandPasses(target, sigmas_))
{
}

std::vector<BandCorrelation> BandPassTarget::correlate(const Heightfield& terrain) const
{
  if (terrain.width != width_ || terrain.height != height_)
  {
    throw Error("The target (" + std::to_string(width_) + " x " + std::to_string(height_) +
      " cells) is not on the terrain's grid (" + std::to_string(terrain.width) + " x " +
      std::to_string(terrain.height) + ").");
  }
  const std::vector<std::vector<float>> bands = bandPasses(terrain, sigmas_);
  std::vector<BandCorrelation> out;
  for (std::size_t s = 0; s < sigmas_.size(); ++s)
  {
    out.push_back({ sigmas_[s], pearson(bands[s], bands_[s]) });
  }
  return out;
}

} // namespace tsynth
