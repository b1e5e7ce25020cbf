// A feature chain as a function of arc length (cells): points and normals
// along it, for measures that walk along sketched lines.
#pragma once

#include "FeatureGraph.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace tsynth
{

// A chain as a function of arc length (cells).
class ChainPath
{
public:
  static constexpr double kDefaultTangentHalfWindow = 3.0;

  explicit ChainPath(const std::vector<Point2>& points)
    : points_(points)
    , arc_(points.size(), 0.0)
  {
    for (std::size_t k = 1; k < points_.size(); ++k)
    {
      arc_[k] =
        arc_[k - 1] + std::hypot(points_[k].x - points_[k - 1].x, points_[k].y - points_[k - 1].y);
    }
  }

  double length() const { return arc_.empty() ? 0.0 : arc_.back(); }

  Point2 at(double s) const
  {
    s = std::clamp(s, 0.0, length());
    const std::size_t k =
      static_cast<std::size_t>(std::upper_bound(arc_.begin(), arc_.end(), s) - arc_.begin());
    if (k == 0 || k >= arc_.size())
    {
      return k == 0 ? points_.front() : points_.back();
    }
    const double span = arc_[k] - arc_[k - 1];
    const double t = span > 0.0 ? (s - arc_[k - 1]) / span : 0.0;
    return { points_[k - 1].x + t * (points_[k].x - points_[k - 1].x),
      points_[k - 1].y + t * (points_[k].y - points_[k - 1].y) };
  }

  // Unit normal (left of the direction of travel), the direction taken over
  // `halfWindow` cells each side (of a hand-drawn or thinned line, not its
  // pixel staircase); false where the line has no direction.
  bool normal(double s, Point2& n, double halfWindow = kDefaultTangentHalfWindow) const
  {
    const Point2 a = at(s - halfWindow);
    const Point2 b = at(s + halfWindow);
    const double len = std::hypot(b.x - a.x, b.y - a.y);
    if (!(len > 0.0))
    {
      return false;
    }
    n = { -(b.y - a.y) / len, (b.x - a.x) / len };
    return true;
  }

private:
  std::vector<Point2> points_;
  std::vector<double> arc_;
};

} // namespace tsynth
