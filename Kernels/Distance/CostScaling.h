// Cross-section profiles turned into the cost-scaling functions of distance-
// based synthesis (Rusnell 2009, §3.3.1, eq. 3.5), and the readers of
// profiles: CSV rows of (distance, height[, profile]) and hand-drawn images.
#pragma once

#include "../Core/HeightfieldIO.h"
#include "Profile.h"

#include <cstddef>
#include <string>
#include <vector>

namespace tsynth
{

// w_s(c_m) on [0, c_s], tabulated in equal cost bins and read by linear
// interpolation between bin centres. Built from a profile that falls from its
// crest (distance 0): flipped (cost = inverse height), scaled to [0, c_s], its
// slope s_m per lattice step taken as a function of cost (the mean slope over
// each bin, which averages several slopes at one cost), divided by mu_w; bins
// below minScaling are replaced by linear interpolation between the nearest
// bins on either side that are not (the thesis's minimum-scaling fix). An
// empty function (no profile) is w_s = 1.
class ScalingFunction
{
public:
  ScalingFunction() = default;

  // profileScale: lattice cells per profile distance unit. Throws tsynth::Error
  // unless the profile falls (front() > back()) and seaCost, meanWeight,
  // profileScale > 0 and bins >= 2.
  static ScalingFunction fromProfile(const MonotoneProfile& profile,
    double seaCost,
    double meanWeight,
    double minScaling,
    int bins,
    double profileScale);

  bool empty() const { return table_.empty(); }
  float operator()(float modifiedCost) const
  {
    if (table_.empty())
    {
      return 1.0f;
    }
    const float t = modifiedCost * inverseBin_ - 0.5f;
    if (!(t > 0.0f))
    {
      return table_.front();
    }
    const std::size_t i = static_cast<std::size_t>(t);
    if (i + 1 >= table_.size())
    {
      return table_.back();
    }
    const float f = t - static_cast<float>(i);
    return table_[i] + f * (table_[i + 1] - table_[i]);
  }
  const std::vector<float>& table() const { return table_; }
  float smallest() const; // the least table value (1 when empty)
  float largest() const;  // the greatest table value (1 when empty)

private:
  std::vector<float> table_;
  float inverseBin_ = 0.0f; // bins per cost unit
};

// One row of a profile table; `line` names it in messages (file line or table row).
struct ProfileRow
{
  double distance = 0.0;
  double height = 0.0;
  int profile = 0;
  int line = 0;
};

// Profiles from rows, grouped by id (ids 0..n-1, each with two or more rows, in
// row order). Throws tsynth::Error naming `source` and the offending row when a
// distance does not increase, a height rises, or a profile does not fall at all.
std::vector<MonotoneProfile> profilesFromRows(const std::vector<ProfileRow>& rows,
  const std::string& source);

// Reads "distance,height[,profile]" lines (a first line that is not numbers is
// a header; '#' lines and blank lines are skipped) and passes them to
// profilesFromRows. Throws tsynth::Error naming the file and line.
std::vector<MonotoneProfile> readProfileCsv(const std::string& path);

// A hand-drawn profile: dark pixels (grey < 128) on a light background, one
// curve from the crest at column 0; each column's height is the mean height of
// its dark pixels (in pixels above the bottom row), columns without any are
// skipped, and the result is the least-squares non-increasing fit (PAV), so a
// wobbly stroke still gives a monotone profile. Throws tsynth::Error if fewer
// than two columns are drawn or the curve does not fall.
MonotoneProfile profileFromImage(const ColourImage& image);

// The profiles in a file, for tsynth distance --profile and the Distance
// Synthesis filter's ProfileFileName: a .csv or .txt (any case) of rows
// (readProfileCsv), else an image of one hand-drawn curve (profileFromImage).
std::vector<MonotoneProfile> readProfiles(const std::string& path);

} // namespace tsynth
