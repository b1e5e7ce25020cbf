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

struct FeatureGraph;

// A landform drawn along a line reads as that line only when it is clearly
// longer than it is wide. Given the exemplars' own width (Colorado's major
// ridges fall over 7.6 km, 84 cells at 90 m), a letter's strokes 130 cells
// long became one broad massif each, whose crest the land's texture hid: the
// T of a "TS" over Colorado read in Tasse's code and not in ours. Held to a
// sixth of their length each side (the landform a third as wide as long),
// the T read; so did lone dashes and chevrons, an H and I drawn as ridges,
// and the bent valley beside the bundled Y, over Colorado and Everest, with
// fewer smooth blobs where broad troughs had been (hillshades side by side,
// Examples/legibility). Strokes joined at their nodes count as one: a valley
// network's short branches keep the room the network's length gives them.
constexpr double kStrokeLengthPerHalfWidth = 6.0;

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

// Per cell: the length (metres) of the connected strokes nearest it, chains
// joined at their nodes (all of a letter's strokes, a whole valley network),
// on the lines' width x height grid of cellX x cellY metres; +inf without
// lines.
std::vector<float> nearestStrokeLength(const FeatureGraph& lines, double cellX, double cellY);

// Holds each cell's halfSpacing to the length of the strokes nearest it over
// kStrokeLengthPerHalfWidth: the room a short stroke's landform may take
// however much room the drawing leaves around it.
void limitByStrokeLength(StrokeSpacing& s, const FeatureGraph& lines, double cellX, double cellY);

// The same with the lengths already read (nearestStrokeLength on s's grid),
// for several spacings of one drawing. Throws tsynth::Error for another grid.
void limitByStrokeLength(StrokeSpacing& s, const std::vector<float>& nearestLength);

} // namespace tsynth
