#include "CostScaling.h"

#include "../Core/Error.h"
#include "../Core/HeightfieldIO.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

namespace tsynth
{
namespace
{

// A pixel darker than this (of 255) belongs to a drawn profile curve.
constexpr double kInkThreshold = 128.0;

// Replaces the bins below `floor` by linear interpolation between the nearest
// bins on either side that are not (one side only: its value; none: floor).
void fixSmallScaling(std::vector<float>& table, float floor)
{
  const std::size_t n = table.size();
  std::vector<std::ptrdiff_t> below(n, -1);
  std::vector<std::ptrdiff_t> above(n, -1);
  std::ptrdiff_t last = -1;
  for (std::size_t i = 0; i < n; ++i)
  {
    below[i] = last;
    if (table[i] >= floor)
    {
      last = static_cast<std::ptrdiff_t>(i);
    }
  }
  last = -1;
  for (std::size_t i = n; i-- > 0;)
  {
    above[i] = last;
    if (table[i] >= floor)
    {
      last = static_cast<std::ptrdiff_t>(i);
    }
  }
  std::vector<float> fixed = table;
  for (std::size_t i = 0; i < n; ++i)
  {
    if (table[i] >= floor)
    {
      continue;
    }
    const std::ptrdiff_t lo = below[i];
    const std::ptrdiff_t hi = above[i];
    if (lo < 0 && hi < 0)
    {
      fixed[i] = floor;
    }
    else if (lo < 0 || hi < 0)
    {
      fixed[i] = table[static_cast<std::size_t>(lo < 0 ? hi : lo)];
    }
    else
    {
      const float f =
        static_cast<float>(static_cast<std::ptrdiff_t>(i) - lo) / static_cast<float>(hi - lo);
      const float a = table[static_cast<std::size_t>(lo)];
      const float b = table[static_cast<std::size_t>(hi)];
      fixed[i] = a + f * (b - a);
    }
  }
  table = std::move(fixed);
}

std::string number(double v)
{
  std::ostringstream s;
  s << v;
  return s.str();
}

std::string rowName(const std::string& source, int line)
{
  return source + " line " + std::to_string(line);
}

} // namespace

ScalingFunction ScalingFunction::fromProfile(const MonotoneProfile& profile,
  double seaCost,
  double meanWeight,
  double minScaling,
  int bins,
  double profileScale)
{
  if (profile.empty() || !(profile.front() > profile.back()))
  {
    throw Error(
      "A cost-scaling profile must fall from its crest (its first height above its last).");
  }
  if (!(seaCost > 0.0) || !(meanWeight > 0.0) || !(profileScale > 0.0) || bins < 2 ||
    !(minScaling >= 0.0))
  {
    throw Error("Cost scaling needs c_s > 0, mu_w > 0, a profile scale > 0, two or more bins and "
                "min t_s >= 0.");
  }
  ScalingFunction f;
  const std::size_t n = static_cast<std::size_t>(bins);
  const double binCost = seaCost / static_cast<double>(bins);
  f.table_.resize(n);
  f.inverseBin_ = static_cast<float>(1.0 / binCost);
  // reach(q): the distance at which the profile has made the share q of its fall,
  // which is where the flipped, scaled profile reaches cost q * c_s.
  double x0 = profile.reach(0.0) * profileScale;
  for (std::size_t b = 0; b < n; ++b)
  {
    const double x1 =
      profile.reach(static_cast<double>(b + 1) / static_cast<double>(bins)) * profileScale;
    const double dx = x1 - x0;
    const double slope = dx > 0.0 ? binCost / dx : 0.0; // cost per lattice step
    f.table_[b] = static_cast<float>(slope / meanWeight);
    x0 = x1;
  }
  // A bin the profile crosses in no distance (float ties) gets its neighbours' value.
  fixSmallScaling(f.table_, static_cast<float>(minScaling));
  return f;
}

float ScalingFunction::smallest() const
{
  return table_.empty() ? 1.0f : *std::min_element(table_.begin(), table_.end());
}

float ScalingFunction::largest() const
{
  return table_.empty() ? 1.0f : *std::max_element(table_.begin(), table_.end());
}

std::vector<MonotoneProfile> profilesFromRows(const std::vector<ProfileRow>& rows,
  const std::string& source)
{
  std::map<int, std::vector<const ProfileRow*>> groups;
  for (const ProfileRow& row : rows)
  {
    if (row.profile < 0)
    {
      throw Error(rowName(source, row.line) + ": profile ids must be 0 or more.");
    }
    if (!std::isfinite(row.distance) || !std::isfinite(row.height))
    {
      throw Error(rowName(source, row.line) + ": distance and height must be finite numbers.");
    }
    groups[row.profile].push_back(&row);
  }
  if (groups.empty())
  {
    throw Error(source + " holds no profile rows.");
  }
  std::vector<MonotoneProfile> profiles;
  for (const auto& [id, group] : groups)
  {
    if (id != static_cast<int>(profiles.size()))
    {
      throw Error(source + ": profile ids must run 0, 1, 2, ... without gaps (profile " +
        std::to_string(profiles.size()) + " is missing).");
    }
    std::vector<double> d;
    std::vector<double> h;
    for (const ProfileRow* row : group)
    {
      if (!d.empty() && !(row->distance > d.back()))
      {
        throw Error(rowName(source, row->line) + ": distance " + number(row->distance) +
          " does not increase along profile " + std::to_string(id) + ".");
      }
      if (!h.empty() && row->height > h.back())
      {
        throw Error(rowName(source, row->line) + ": height " + number(row->height) +
          " rises along profile " + std::to_string(id) +
          "; profiles must fall monotonically away from the crest.");
      }
      d.push_back(row->distance);
      h.push_back(row->height);
    }
    if (d.size() < 2 || !(h.front() > h.back()))
    {
      throw Error(source + ": profile " + std::to_string(id) +
        " needs two or more rows and must fall (its first height above its last).");
    }
    profiles.push_back(MonotoneProfile::fromPoints(d, h));
  }
  return profiles;
}

std::vector<MonotoneProfile> readProfileCsv(const std::string& path)
{
  std::ifstream in(path);
  if (!in)
  {
    throw Error("Cannot open the profile file " + path + ".");
  }
  std::vector<ProfileRow> rows;
  std::string text;
  int line = 0;
  bool firstData = true;
  while (std::getline(in, text))
  {
    ++line;
    std::replace(text.begin(), text.end(), ',', ' ');
    std::replace(text.begin(), text.end(), ';', ' ');
    std::istringstream fields(text);
    std::string first;
    if (!(fields >> first) || first[0] == '#')
    {
      continue;
    }
    fields.clear();
    fields.str(text);
    ProfileRow row;
    row.line = line;
    if (!(fields >> row.distance >> row.height))
    {
      if (firstData)
      {
        firstData = false; // a header
        continue;
      }
      throw Error(rowName(path, line) + ": expected \"distance,height[,profile]\" numbers.");
    }
    firstData = false;
    double id = 0.0;
    if (fields >> id)
    {
      if (id != std::floor(id))
      {
        throw Error(rowName(path, line) + ": the profile id must be a whole number.");
      }
      row.profile = static_cast<int>(id);
    }
    std::string extra;
    fields.clear();
    if (fields >> extra)
    {
      throw Error(rowName(path, line) + ": \"" + extra +
        "\" is one column too many; a row is \"distance,height[,profile]\".");
    }
    rows.push_back(row);
  }
  return profilesFromRows(rows, path);
}

MonotoneProfile profileFromImage(const ColourImage& image)
{
  std::vector<double> distance;
  std::vector<double> height;
  for (int col = 0; col < image.width; ++col)
  {
    double sum = 0.0;
    int count = 0;
    for (int row = 0; row < image.height; ++row)
    {
      const std::uint8_t* p = image.pixel(col, row);
      const double grey = image.channels >= 3 ? (p[0] + p[1] + p[2]) / 3.0 : p[0];
      if (grey < kInkThreshold)
      {
        sum += image.height - 1 - row;
        ++count;
      }
    }
    if (count > 0)
    {
      distance.push_back(col);
      height.push_back(sum / count);
    }
  }
  if (distance.size() < 2)
  {
    throw Error("A profile image needs a dark curve across two or more columns.");
  }
  const std::vector<double> weights(distance.size(), 1.0);
  MonotoneProfile fitted =
    MonotoneProfile::fit(distance, height, weights, Monotonicity::NonIncreasing);
  if (!(fitted.front() > fitted.back()))
  {
    throw Error("The profile image's curve does not fall from left to right.");
  }
  return fitted;
}

std::vector<MonotoneProfile> readProfiles(const std::string& path)
{
  if (hasExtension(path, ".csv") || hasExtension(path, ".txt"))
  {
    return readProfileCsv(path);
  }
  return { profileFromImage(readColourImage(path)) };
}

} // namespace tsynth
