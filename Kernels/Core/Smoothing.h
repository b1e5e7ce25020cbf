// Gaussian smoothing at large scales in constant time per cell: three box
// filters per axis whose widths give the Gaussian's variance (Wells 1986;
// Kovesi 2010). Invalid cells get no weight and stay invalid; near the edges the
// weights are renormalised, as gaussianSmooth() does.
#pragma once

#include "Heightfield.h"

#include <array>

namespace tsynth
{

// smoothLarge's box filters per axis.
constexpr int kBoxPasses = 3;

// The odd widths of those boxes whose variances add up to sigma^2, as near as
// odd widths allow (the smallest is 1).
std::array<int, kBoxPasses> boxWidths(double sigma);

// Close to a Gaussian of standard deviation `sigma` cells: a smooth bell made of
// three boxes of odd widths, whose variance is the nearest such widths allow,
// within 1 / (3 sigma) + 1 / (6 sigma^2) of sigma^2 (8.3% low at sigma 4, 2%
// at 16); sigma <= 0 returns the input.
Heightfield smoothLarge(const Heightfield& hf, double sigma);

} // namespace tsynth
