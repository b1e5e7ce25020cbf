// The seams between placed patches as poly-lines, to draw over a terrain: they run along the
// borders between cells that different placements wrote (SynthesisResult::patchId), so a seam
// reads as one continuous line where a mask of seam cells, thresholded, comes out dashed.
#pragma once

#include <vector>

namespace tsynth
{

// A cell corner: corner (i, j) is the lower-left corner of cell (i, j), so in cell units it
// lies at (i - 0.5, j - 0.5) from the centre of cell (0, 0). i runs 0..width, j 0..height.
struct CellCorner
{
  int i = 0;
  int j = 0;
};

using SeamLine = std::vector<CellCorner>;

// Every border between two cells of different non-negative patch ids, joined into poly-lines
// that end where seams meet (three or four patches at a corner) or end; a closed seam starts
// and ends at the same corner. Cells with id -1 (written by no placement) border nothing.
// Deterministic: lines come in the order of their first corner, row by row. Throws
// tsynth::Error when patchId does not hold width x height ids.
std::vector<SeamLine> seamLines(const std::vector<int>& patchId, int width, int height);

} // namespace tsynth
