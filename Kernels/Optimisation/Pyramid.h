// Gaussian pyramids for terrain optimisation: each level halves the previous
// one (side n -> ceil(n / 2)) after a 5-tap binomial blur, nodata-aware.
#pragma once

#include "../Core/Heightfield.h"

#include <vector>

namespace tsynth::optim
{

// The next coarser level: cell (i, j) is the binomial (1 4 6 4 1) / 16 average
// of the fine cells around (2i, 2j), weights renormalised over the valid cells
// inside the grid (nodata never enters). A coarse cell is valid if every fine
// cell of its 2 x 2 block is valid; invalid cells hold NaN. Cell size doubles.
Heightfield downsampleHalf(const Heightfield& fine);

// Level 0 is `hf` itself, level k has side ceil(side / 2^k); levels + 1 grids.
std::vector<Heightfield> gaussianPyramid(const Heightfield& hf, int levels);

// Side of level k of a grid of side n (ceil(n / 2^k)).
int levelSide(int n, int k);

} // namespace tsynth::optim
