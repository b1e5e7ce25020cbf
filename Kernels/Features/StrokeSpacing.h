// How far apart a sketch's strokes are, cell by cell: the width a landform
// drawn there can take. Two valleys drawn 50 cells apart are each at most 25
// cells wide, with a divide between them; a lone ridge may be as wide as the
// exemplars' own. The spacing is read off the drawing's medial axis: the cells
// whose nearest stroke points, seen from two neighbouring cells, lie in
// clearly different directions (across from each other, not along one line).
#pragma once

#include <cstdint>
#include <vector>

namespace tsynth
{

struct StrokeSpacing
{
  int width = 0;
  int height = 0;
  // Per cell: metres to the nearest stroke cell.
  std::vector<float> toStroke;
  // Per cell: half the distance between the nearest stroke and the stroke
  // across from it on this side (metres): toStroke plus the distance to the
  // medial axis between them, the path not crossing a stroke. +inf where no
  // stroke faces this one (the open side of a lone line).
  std::vector<float> halfSpacing;
  // 1 on the medial axis between facing strokes.
  std::vector<std::uint8_t> medial;
};

// `strokes`: 1 on stroke cells (every kind of line together: a ridge between
// two valleys faces both). Cells of cellX x cellY metres.
StrokeSpacing strokeSpacing(const std::vector<std::uint8_t>& strokes,
  int width,
  int height,
  double cellX = 1.0,
  double cellY = 1.0);

// The half spacing of each stroke cell, read from the cells beside it: the
// narrower of its two sides, or +inf for a stroke no other faces.
// (For measures that walk along the strokes.)
float strokeHalfSpacing(const StrokeSpacing& s, int i, int j);

} // namespace tsynth
