#include "CrossSections.h"

#include "../Core/Constants.h"
#include "../Core/Error.h"
#include "../Core/Random.h"
#include "Profiles.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tsynth
{
namespace
{

// The section is smoothed at this share of its half width: bumps finer than a
// third of the landform are its texture, not the landform.
constexpr double kLandformSigmaShare = 1.0 / 3.0;
// Each side is the outer half of the section on that side.
constexpr double kSideStartShare = 0.5;
// Half widths (cells) at which the land's relief is measured.
constexpr double kReferenceHalfWidths[] = { 3, 4, 6, 8, 11, 16, 23, 32, 45, 64 };
// The fixed seed of the random cross-sections ("legibil"), one stream per axis.
constexpr std::uint64_t kSectionSeed = 0x6c65676962696cULL;
constexpr std::uint64_t kStreamX = 1;
constexpr std::uint64_t kStreamY = 2;
constexpr std::uint64_t kStreamAngle = 3;
// Draws per wanted section: some land on nodata or reach past the edge.
constexpr int kDrawsPerSection = 4;

// Gaussian smoothing of a short profile (sigma in samples), the kernel
// renormalised where it leaves the section.
std::vector<double> smoothed(const std::vector<double>& z, double sigma)
{
  const int n = static_cast<int>(z.size());
  const int reach = static_cast<int>(std::ceil(3.0 * sigma));
  // The kernel by distance, once: sections are smoothed by the million (the
  // land's relief, the legibility measure), and exp per pair of samples was
  // 6% of a 512 x 512 synthesis.
  std::vector<double> kernel(static_cast<std::size_t>(reach) + 1);
  for (int d = 0; d <= reach; ++d)
  {
    kernel[static_cast<std::size_t>(d)] = std::exp(-0.5 * d * d / (sigma * sigma));
  }
  std::vector<double> out(z.size());
  for (int a = 0; a < n; ++a)
  {
    double sum = 0.0;
    double weight = 0.0;
    for (int b = std::max(0, a - reach); b <= std::min(n - 1, a + reach); ++b)
    {
      const double k = kernel[static_cast<std::size_t>(std::abs(a - b))];
      sum += k * z[static_cast<std::size_t>(b)];
      weight += k;
    }
    out[static_cast<std::size_t>(a)] = sum / weight;
  }
  return out;
}

// The smoothed section and where its sides start (samples from the middle).
struct Landform
{
  std::vector<double> z;
  int half = 0;
  int sideFrom = 0;
  double at(int s) const { return z[static_cast<std::size_t>(s + half)]; }
  // Mean of side -1 (left) or +1 (right).
  double side(int which) const
  {
    double sum = 0.0;
    for (int s = sideFrom; s <= half; ++s)
    {
      sum += at(which * s);
    }
    return sum / (half - sideFrom + 1);
  }
};

Landform landformOf(const std::vector<double>& z)
{
  Landform l;
  l.half = static_cast<int>(z.size() / 2);
  l.z = smoothed(z, kLandformSigmaShare * l.half);
  l.sideFrom = static_cast<int>(std::ceil(kSideStartShare * l.half));
  return l;
}

} // namespace

bool readSection(const Heightfield& hf,
  double x,
  double y,
  double nx,
  double ny,
  int half,
  std::vector<double>& z)
{
  z.resize(static_cast<std::size_t>(2 * half + 1));
  double* const centre = z.data() + half; // centre[s]: sample s, -half..half
  for (int s = -half; s <= half; ++s)
  {
    const float v = sampleBilinear(hf, x + s * nx, y + s * ny);
    if (std::isnan(v))
    {
      return false;
    }
    centre[s] = v;
  }
  return true;
}

double sectionProminence(const std::vector<double>& z, double sign, const SectionReading& r)
{
  const Landform l = landformOf(z);
  const int line = std::min(l.half, static_cast<int>(std::max(r.tolerance, r.lineShare * l.half)));
  double top = -std::numeric_limits<double>::infinity();
  for (int s = -line; s <= line; ++s)
  {
    top = std::max(top, sign * l.at(s));
  }
  return top - std::max(sign * l.side(-1), sign * l.side(1));
}

double sectionRelief(const std::vector<double>& z)
{
  const Landform l = landformOf(z);
  return l.at(0) - 0.5 * (l.side(-1) + l.side(1));
}

double sectionSlope(const std::vector<double>& z)
{
  // The least-squares slope under the smoothing's Gaussian centred on the
  // middle: exact on a plane (the smoothed values beside the middle lose a
  // sample of their kernel at the section's ends, and read 1% flatter).
  const int half = static_cast<int>(z.size() / 2);
  const double sigma = kLandformSigmaShare * half;
  if (!(sigma > 0.0))
  {
    return 0.0;
  }
  const double* const centre = z.data() + half; // centre[s]: sample s, -half..half
  double moment = 0.0;
  double spread = 0.0;
  for (int s = -half; s <= half; ++s)
  {
    const double w = std::exp(-0.5 * s * s / (sigma * sigma));
    moment += w * s * centre[s];
    spread += w * s * s;
  }
  return std::abs(moment / spread);
}

LandRelief::LandRelief(const std::vector<const Heightfield*>& exemplars, int sectionsPerExemplar)
  : halfWidths_(std::begin(kReferenceHalfWidths), std::end(kReferenceHalfWidths))
{
  if (exemplars.empty())
  {
    throw Error("No exemplar to measure the land's relief on.");
  }
  // Each level draws from its own streams: the levels run in parallel and give
  // the same figures on any number of threads.
  const long levels = static_cast<long>(halfWidths_.size());
  relief_.assign(halfWidths_.size(), 0.0);
  steep_.assign(halfWidths_.size(), 0.0);
#pragma omp parallel for schedule(dynamic)
  for (long level = 0; level < levels; ++level)
  {
    measureLevel(exemplars, static_cast<std::size_t>(level), sectionsPerExemplar);
  }
}

LandRelief LandRelief::fromLevels(Levels levels)
{
  if (levels.relief.size() != levels.halfWidths.size() ||
    levels.steep.size() != levels.halfWidths.size())
  {
    throw Error("Internal error: a land relief's levels differ in length.");
  }
  LandRelief r;
  r.halfWidths_ = std::move(levels.halfWidths);
  r.relief_ = std::move(levels.relief);
  r.steep_ = std::move(levels.steep);
  return r;
}

void LandRelief::measureLevel(const std::vector<const Heightfield*>& exemplars,
  std::size_t level,
  int sectionsPerExemplar)
{
  const int half = static_cast<int>(halfWidths_[level]);
  double squares = 0.0;
  std::size_t count = 0;
  std::vector<float> slopes;
  std::vector<double> z;
  for (std::size_t e = 0; e < exemplars.size(); ++e)
  {
    const Heightfield& ex = *exemplars[e];
    const std::uint64_t stream = (level * exemplars.size() + e) << 8;
    int found = 0;
    for (int draw = 0; draw < kDrawsPerSection * sectionsPerExemplar && found < sectionsPerExemplar;
         ++draw)
    {
      const std::uint64_t k = static_cast<std::uint64_t>(draw);
      const double x = seededUniform(kSectionSeed, stream | kStreamX, k) * (ex.width - 1);
      const double y = seededUniform(kSectionSeed, stream | kStreamY, k) * (ex.height - 1);
      const double a = seededUniform(kSectionSeed, stream | kStreamAngle, k) * kTwoPi;
      if (readSection(ex, x, y, std::cos(a), std::sin(a), half, z))
      {
        const double r = sectionRelief(z);
        squares += r * r;
        slopes.push_back(static_cast<float>(sectionSlope(z)));
        ++count;
        ++found;
      }
    }
  }
  relief_[level] = count > 0 ? std::sqrt(squares / static_cast<double>(count)) : 0.0;
  steep_[level] = slopes.empty() ? 0.0 : percentile(slopes, kSteepShare);
}

double LandRelief::at(double h) const
{
  return interpolate(relief_, h);
}

double LandRelief::steepSlope(double h) const
{
  return interpolate(steep_, h);
}

double LandRelief::interpolate(const std::vector<double>& levels, double h) const
{
  if (levels.empty())
  {
    return 0.0;
  }
  if (h <= halfWidths_.front())
  {
    return levels.front();
  }
  for (std::size_t k = 1; k < halfWidths_.size(); ++k)
  {
    if (h <= halfWidths_[k])
    {
      const double t =
        std::log(h / halfWidths_[k - 1]) / std::log(halfWidths_[k] / halfWidths_[k - 1]);
      return (1.0 - t) * levels[k - 1] + t * levels[k];
    }
  }
  return levels.back();
}

} // namespace tsynth
