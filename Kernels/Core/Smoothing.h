// Gaussian smoothing at large scales in constant time per cell: three box
// filters per axis whose widths give the Gaussian's variance (Wells 1986;
// Kovesi 2010). Invalid cells get no weight and stay invalid; near the edges the
// weights are renormalised, as gaussianSmooth() does.
#pragma once

#include "Heightfield.h"

namespace tsynth
{

// Close to a Gaussian of standard deviation `sigma` cells (exact variance, a
// smooth bell made of three boxes); sigma <= 0 returns the input.
Heightfield smoothLarge(const Heightfield& hf, double sigma);

} // namespace tsynth
