#include "Profile.h"

#include "../Core/Error.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

namespace tsynth
{

MonotoneProfile MonotoneProfile::fromPoints(const std::vector<double>& distances,
  const std::vector<double>& values)
{
  if (distances.empty() || distances.size() != values.size())
  {
    throw Error("A profile needs as many heights as distances, and at least one point.");
  }
  int direction = 0; // +1 rising, -1 falling, 0 not yet known
  for (std::size_t k = 0; k < distances.size(); ++k)
  {
    std::ostringstream where;
    where << "point " << k + 1 << " (" << distances[k] << ", " << values[k] << ")";
    if (!std::isfinite(distances[k]) || !std::isfinite(values[k]) || distances[k] < 0.0)
    {
      throw Error("The profile's " + where.str() + " is not a finite, non-negative distance.");
    }
    if (k == 0)
    {
      continue;
    }
    if (!(distances[k] > distances[k - 1]))
    {
      throw Error("The profile's distances must increase, but " + where.str() +
        " does not come after the point before it.");
    }
    const double step = values[k] - values[k - 1];
    const int sign = step > 0.0 ? 1 : (step < 0.0 ? -1 : 0);
    if (sign != 0 && direction != 0 && sign != direction)
    {
      throw Error("The profile must be monotone, but at " + where.str() + " it turns " +
        (sign > 0 ? "up" : "down") + " after going " + (direction > 0 ? "up." : "down."));
    }
    if (sign != 0)
    {
      direction = sign;
    }
  }
  MonotoneProfile p;
  p.distances_ = distances;
  p.values_ = values;
  return p;
}

MonotoneProfile MonotoneProfile::fit(const std::vector<double>& distances,
  const std::vector<double>& values,
  const std::vector<double>& weights,
  Monotonicity direction)
{
  if (values.size() != distances.size() || weights.size() != distances.size())
  {
    throw Error("A profile fit needs one height and one weight per distance.");
  }
  for (std::size_t k = 1; k < distances.size(); ++k)
  {
    if (!(distances[k] > distances[k - 1]))
    {
      throw Error("The distances of a profile fit must increase, but sample " +
        std::to_string(k + 1) + " does not come after the one before it.");
    }
  }
  // Pool adjacent violators on the non-decreasing problem (a falling profile is
  // fitted as the rising profile of -value).
  const double sign = direction == Monotonicity::NonDecreasing ? 1.0 : -1.0;
  struct Block
  {
    double sum = 0.0; // weighted values
    double weight = 0.0;
    std::size_t first = 0, last = 0; // indices into the kept samples
    double mean() const { return sum / weight; }
  };
  std::vector<double> keptDistance;
  std::vector<Block> blocks;
  for (std::size_t k = 0; k < distances.size(); ++k)
  {
    if (!(weights[k] > 0.0) || !std::isfinite(values[k]))
    {
      continue;
    }
    keptDistance.push_back(distances[k]);
    const std::size_t at = keptDistance.size() - 1;
    blocks.push_back({ sign * values[k] * weights[k], weights[k], at, at });
    while (blocks.size() > 1 && blocks[blocks.size() - 2].mean() > blocks.back().mean())
    {
      const Block top = blocks.back();
      blocks.pop_back();
      blocks.back().sum += top.sum;
      blocks.back().weight += top.weight;
      blocks.back().last = top.last;
    }
  }
  MonotoneProfile p;
  p.distances_ = keptDistance;
  p.values_.resize(keptDistance.size());
  for (const Block& b : blocks)
  {
    std::fill(p.values_.begin() + static_cast<long>(b.first),
      p.values_.begin() + static_cast<long>(b.last + 1),
      sign * b.mean());
  }
  return p;
}

double MonotoneProfile::operator()(double distance) const
{
  if (distances_.empty())
  {
    return 0.0;
  }
  if (distance <= distances_.front())
  {
    return values_.front();
  }
  if (distance >= distances_.back())
  {
    return values_.back();
  }
  const auto hi = std::upper_bound(distances_.begin(), distances_.end(), distance);
  const std::size_t k = static_cast<std::size_t>(hi - distances_.begin());
  const double t = (distance - distances_[k - 1]) / (distances_[k] - distances_[k - 1]);
  return values_[k - 1] + t * (values_[k] - values_[k - 1]);
}

double MonotoneProfile::reach(double fraction) const
{
  if (distances_.empty() || values_.back() == values_.front())
  {
    return 0.0;
  }
  const double goal = values_.front() + fraction * (values_.back() - values_.front());
  const bool falling = values_.back() < values_.front();
  for (std::size_t k = 1; k < values_.size(); ++k)
  {
    const bool past = falling ? values_[k] <= goal : values_[k] >= goal;
    if (past)
    {
      const double span = values_[k] - values_[k - 1];
      const double t = span != 0.0 ? (goal - values_[k - 1]) / span : 0.0;
      return distances_[k - 1] + t * (distances_[k] - distances_[k - 1]);
    }
  }
  return distances_.back();
}

MonotoneProfile MonotoneProfile::normalised() const
{
  MonotoneProfile p = *this;
  const double change = empty() ? 0.0 : values_.back() - values_.front();
  for (double& v : p.values_)
  {
    v = change != 0.0 ? (v - values_.front()) / change : 0.0;
  }
  return p;
}

} // namespace tsynth
