// The chain points of a feature graph, ridges and valleys apart, in square
// buckets: the points near a spot are found without a walk over the whole
// graph (a real DEM's tree holds tens of thousands of them).
#pragma once

#include "FeatureGraph.h"

#include <cmath>
#include <cstddef>
#include <vector>

namespace tsynth
{

class ChainPointGrid
{
public:
  ChainPointGrid() = default;
  // Buckets `side` cells wide over the extent of the graph's chain points.
  ChainPointGrid(const FeatureGraph& graph, double side);

  // Calls visit(point) for every chain point of `type` within `reach` cells of
  // (x, y) on both axes (a square; the caller keeps the disc it wants).
  template<class Visit>
  void forEachNear(FeatureType type, double x, double y, double reach, Visit&& visit) const
  {
    if (columns_ == 0)
    {
      return;
    }
    const std::vector<std::vector<Point2>>& buckets = bucketsOf(type);
    const std::size_t i0 = column(x - reach);
    const std::size_t i1 = column(x + reach);
    const std::size_t j0 = row(y - reach);
    const std::size_t j1 = row(y + reach);
    for (std::size_t j = j0; j <= j1; ++j)
    {
      for (std::size_t i = i0; i <= i1; ++i)
      {
        for (const Point2& q : buckets[j * columns_ + i])
        {
          if (std::abs(q.x - x) <= reach && std::abs(q.y - y) <= reach)
          {
            visit(q);
          }
        }
      }
    }
  }

private:
  const std::vector<std::vector<Point2>>& bucketsOf(FeatureType type) const
  {
    return type == FeatureType::Ridge ? ridges_ : valleys_;
  }
  std::size_t column(double x) const { return clampedBucket(x - x0_, columns_); }
  std::size_t row(double y) const { return clampedBucket(y - y0_, rows_); }
  std::size_t clampedBucket(double offset, std::size_t count) const;

  double side_ = 1.0;
  double x0_ = 0.0;
  double y0_ = 0.0;
  std::size_t columns_ = 0;
  std::size_t rows_ = 0;
  std::vector<std::vector<Point2>> ridges_;
  std::vector<std::vector<Point2>> valleys_;
};

} // namespace tsynth
