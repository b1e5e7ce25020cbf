#include "ChainPointGrid.h"

#include <algorithm>
#include <limits>

namespace tsynth
{

ChainPointGrid::ChainPointGrid(const FeatureGraph& graph, double side)
  : side_(std::max(side, 1.0))
{
  double x1 = -std::numeric_limits<double>::infinity();
  double y1 = x1;
  x0_ = std::numeric_limits<double>::infinity();
  y0_ = x0_;
  for (const FeatureChain& chain : graph.chains)
  {
    for (const Point2& q : chain.points)
    {
      x0_ = std::min(x0_, q.x);
      y0_ = std::min(y0_, q.y);
      x1 = std::max(x1, q.x);
      y1 = std::max(y1, q.y);
    }
  }
  if (!(x1 >= x0_ && y1 >= y0_))
  {
    x0_ = 0.0;
    y0_ = 0.0;
    return; // no points: columns_ stays 0
  }
  columns_ = static_cast<std::size_t>(std::floor((x1 - x0_) / side_)) + 1;
  rows_ = static_cast<std::size_t>(std::floor((y1 - y0_) / side_)) + 1;
  ridges_.resize(columns_ * rows_);
  valleys_.resize(columns_ * rows_);
  for (const FeatureChain& chain : graph.chains)
  {
    std::vector<std::vector<Point2>>& buckets =
      chain.type == FeatureType::Ridge ? ridges_ : valleys_;
    for (const Point2& q : chain.points)
    {
      buckets[row(q.y) * columns_ + column(q.x)].push_back(q);
    }
  }
}

std::size_t ChainPointGrid::clampedBucket(double offset, std::size_t count) const
{
  const double b = std::floor(offset / side_);
  if (!(b > 0.0))
  {
    return 0; // also NaN
  }
  return std::min(static_cast<std::size_t>(b), count - 1);
}

} // namespace tsynth
