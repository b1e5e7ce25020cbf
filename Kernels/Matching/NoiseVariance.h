// Multi-resolution noise variance (Tasse's thesis, section 4.3.1): the variance,
// inside a window, of what each level of a Gaussian pyramid adds to the next
// coarser one. Band images and summed-area tables are built once per exemplar,
// so any window's three variances cost a few lookups.
#pragma once

#include "../Core/Heightfield.h"

#include <array>
#include <vector>

namespace tsynth
{

constexpr int kNoiseLevels = 3;

class NoiseVariance
{
public:
  NoiseVariance() = default;
  explicit NoiseVariance(const Heightfield& hf);

  // Variances (m^2) of the band-pass levels (finest first) over the square
  // window of side `size` cells centred at (cx, cy); invalid cells excluded.
  std::array<float, kNoiseLevels> window(double cx, double cy, int size) const;

private:
  struct Table
  {
    int width = 0;
    int height = 0;
    std::vector<double> sum; // (w+1) x (h+1) summed-area tables
    std::vector<double> square;
  };
  std::array<Table, kNoiseLevels> levels_;
  // Valid cells, the same (w+1) x (h+1) table for every level; empty when
  // every cell is valid, and a window's count is then its area (the same
  // whole number the table gives): a 4096 x 4096 target saves 400 MB.
  std::vector<double> count_;
};

} // namespace tsynth
