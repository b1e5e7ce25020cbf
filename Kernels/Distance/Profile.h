// A monotone cross-section profile: height against distance from a feature
// line (or a generator, in distance-based synthesis), piecewise linear between
// its points and constant past the last one. Ridges fall with distance, valleys
// rise; Rusnell's cost-scaling functions need monotone profiles too.
#pragma once

#include <vector>

namespace tsynth
{

enum class Monotonicity
{
  NonIncreasing, // a ridge: height falls away from the line
  NonDecreasing  // a valley: height rises away from the line
};

class MonotoneProfile
{
public:
  MonotoneProfile() = default;

  // From points as given. Throws tsynth::Error naming the first offending point
  // if the distances are negative or not strictly increasing, or the values are
  // not monotone in either direction.
  static MonotoneProfile fromPoints(const std::vector<double>& distances,
    const std::vector<double>& values);

  // Weighted least-squares monotone fit (pool adjacent violators) of noisy
  // samples at increasing distances; samples of zero weight or NaN value are
  // ignored. Throws tsynth::Error if the sizes differ or a distance does not
  // increase.
  static MonotoneProfile fit(const std::vector<double>& distances,
    const std::vector<double>& values,
    const std::vector<double>& weights,
    Monotonicity direction);

  bool empty() const { return distances_.empty(); }
  // Linear between points, the end values outside them.
  double operator()(double distance) const;
  double front() const { return values_.front(); }
  double back() const { return values_.back(); }
  double length() const { return distances_.back(); } // last point's distance
  // The smallest distance at which the profile has made `fraction` (0..1) of
  // its whole change front() -> back(); 0 for a constant profile.
  double reach(double fraction) const;
  // The same shape scaled to change from 0 at the line to 1 at its far end
  // (s(0) = 0, s(length) = 1); a constant profile gives s = 0 everywhere.
  MonotoneProfile normalised() const;

  const std::vector<double>& distances() const { return distances_; }
  const std::vector<double>& values() const { return values_; }

private:
  std::vector<double> distances_;
  std::vector<double> values_;
};

} // namespace tsynth
