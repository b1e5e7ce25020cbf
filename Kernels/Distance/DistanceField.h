// Exact Euclidean distances on a grid, in metres, from every cell to the
// nearest of a set of seed cells, with the nearest seed itself (a feature
// transform). The distance-based target field of a sketch and the
// distance-based synthesis (Rusnell 2009) both start from it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace tsynth
{

struct NearestSeeds
{
  int width = 0;
  int height = 0;
  std::vector<float> distance;       // metres; +inf when there is no seed at all
  std::vector<std::int32_t> nearest; // cell index of the nearest seed; -1 without seeds

  bool empty() const { return nearest.empty() || nearest.front() < 0; }
};

// Felzenszwalb and Huttenlocher's two-pass lower envelope of parabolas, with
// cell sizes cellX (columns) and cellY (rows) in metres, so distances are true
// metres on grids whose cells are not square. Ties go to the seed in the lowest
// column, then the lowest row (not the lowest index: the column pass picks the
// row, the row pass the column).
NearestSeeds nearestSeeds(const std::vector<std::uint8_t>& seeds,
  int width,
  int height,
  double cellX = 1.0,
  double cellY = 1.0);

// Distances only, in cells of size 1 (the common case of the target builder).
std::vector<float> distanceTransform(const std::vector<std::uint8_t>& seeds, int width, int height);

} // namespace tsynth
