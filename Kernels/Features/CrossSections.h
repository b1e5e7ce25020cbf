// Cross-sections of a terrain at a landform's own scale: the heights across a
// line out to a half width h, smoothed at a third of h so that what is left is
// the landform and not the texture on it, and how far its crest (or floor)
// stands out over its two sides. The same reading of random cross-sections of
// an exemplar gives the land's own relief at that scale, which a sketched
// landform must stand out of to be seen (Metrics/Legibility.h), and which the
// target gives its landforms a margin over (Synthesis/Landform.h).
#pragma once

#include "../Core/Heightfield.h"

#include <vector>

namespace tsynth
{

// Heights at x + s n, s = -half .. half cells (bilinear); false where one is
// invalid or outside the grid.
bool readSection(const Heightfield& hf,
  double x,
  double y,
  double nx,
  double ny,
  int half,
  std::vector<double>& z);

struct SectionReading
{
  // The lines wander from the stroke drawn: the crest or floor is looked for
  // within this share of the half width (at least `tolerance` cells).
  double lineShare = 0.2;
  double tolerance = 2.0;
};

// A cross-section z (2 half + 1 heights) once smoothed at a third of its half
// width: the crest (sign +1) or floor (sign -1) near the middle over the higher
// (under the lower) of its two sides, each side the mean of its outer half.
// Positive when both sides are lower (higher), metres.
double sectionProminence(const std::vector<double>& z, double sign, const SectionReading& r = {});

// The same section's slope at its middle, at the smoothing's scale (metres
// per cell, unsigned).
double sectionSlope(const std::vector<double>& z);

// The same section's middle over the mean of both sides (signed, no search for
// the line): the relief a cross-section of land shows at its scale.
double sectionRelief(const std::vector<double>& z);

// The exemplars' own relief per half width: the root mean square sectionRelief
// of random cross-sections through their land (a fixed seed draws them, so it
// is deterministic), at half widths about a factor 1.4 apart, interpolated
// between them in log h.
class LandRelief
{
public:
  LandRelief() = default; // no land: no relief at any half width
  // Throws tsynth::Error without an exemplar.
  explicit LandRelief(const std::vector<const Heightfield*>& exemplars,
    int sectionsPerExemplar = 1500);
  double at(double halfWidth) const; // metres, for a half width in cells
  // The steep end of the land's slopes at that scale: the kSteepShare
  // quantile of the smoothed sections' slope at their middle (metres per
  // cell), the steepest flank a landform of that half width may have and
  // still look like the exemplars' land.
  double steepSlope(double halfWidth) const;
  bool empty() const { return relief_.empty(); }

  // The measured levels, as stored (Synthesis/ExemplarCache.h) and given back.
  struct Levels
  {
    std::vector<double> halfWidths; // cells, increasing
    std::vector<double> relief;     // metres, one per half width
    std::vector<double> steep;      // metres per cell, one per half width
  };
  Levels levels() const { return { halfWidths_, relief_, steep_ }; }
  // Throws tsynth::Error if the three lists differ in length.
  static LandRelief fromLevels(Levels levels);

private:
  double interpolate(const std::vector<double>& levels, double halfWidth) const;
  // One reference half width: its relief_ and steep_ entries.
  void measureLevel(const std::vector<const Heightfield*>& exemplars,
    std::size_t level,
    int sectionsPerExemplar);

  std::vector<double> halfWidths_, relief_, steep_;
};

// The quantile of the land's slopes LandRelief::steepSlope reads: one section
// in thirty is steeper.
constexpr double kSteepShare = 0.99;

} // namespace tsynth
