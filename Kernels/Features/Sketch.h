// A user's sketch turned into feature graphs: grey sketch maps (through PPA),
// stroke maps (red ridges, blue valleys, thinned to centre lines) and
// poly-lines (used as drawn).
// In ParaView: vtkTerrainSketchFeatures (Terrain Sketch Features), in Filters/.
#pragma once

#include "../Core/Heightfield.h"
#include "../Core/HeightfieldIO.h"
#include "../Core/OptionTable.h"
#include "../Core/PatchSize.h"
#include "FeatureGraph.h"
#include "PpaLimits.h"

#include <string>
#include <vector>

namespace tsynth
{

enum class SketchKind
{
  Grey,   // one channel (or R = G = B): brighter is higher
  Strokes // colour: red ridges, blue valleys
};

// Control points sit half a patch apart along the lines: one per patch placed.
constexpr double kDefaultSketchControlRadius = 0.5 * kDefaultSynthesisPatch; // cells
// Poly-line vertices within a cell of each other join: a user who draws two
// lines to meet lands within a pixel of the point, not on it.
constexpr double kDefaultSnapCells = 1.0;
constexpr double kMaxSnapCells = 1000.0; // beyond, whole sketches collapse to a point

struct SketchOptions
{
  int patchSize = kDefaultSynthesisPatch;             // a sketch smaller than one patch is refused
  double controlRadius = kDefaultSketchControlRadius; // cells
  int smoothingPasses = 2;
  double cellSize = 1.0; // metres per sketch pixel, for the graph's coordinates
};

struct SketchFeatures
{
  FeatureGraph graph;
  SketchKind kind = SketchKind::Grey;
  double strokeWidth = 0.0; // estimated, pixels
  std::vector<std::string> warnings;
};

// Pixel classes of a stroke map (DESIGN.md thresholds).
bool isRidgeColour(const std::uint8_t* rgb);
bool isValleyColour(const std::uint8_t* rgb);

// Grey if every pixel has R, G and B within 8 of each other (or one channel).
SketchKind classifySketch(const ColourImage& image);

// Reads any sketch image: grey maps go through PPA (ridges and valleys), colour
// images through stroke thinning. Throws tsynth::Error for a sketch smaller
// than one patch or a colour image with no ridge or valley strokes.
SketchFeatures sketchFeatures(const ColourImage& image, const SketchOptions& options = {});

// The first channel of an image as heights (row 0 south), cell size 1.
Heightfield greyField(const ColourImage& image);

// The centre lines of the strokes in a binary mask (row-major, width x height,
// row 0 south) as a graph of the given type: the mask's outline smoothed,
// thinned, short spurs and specks removed (as for a stroke map's strokes).
FeatureGraph centreLines(std::vector<std::uint8_t> mask,
  int width,
  int height,
  FeatureType type,
  const SketchOptions& options = {});

// Zhang-Suen thinning of a binary mask (row-major, width x height), in place.
void thinMask(std::vector<std::uint8_t>& mask, int width, int height);

// A poly-line in cell coordinates, with optional per-point height constraints.
struct Polyline
{
  std::vector<Point2> points;
  std::vector<float> elevation; // empty, or one value per point (NaN = none)
  FeatureType type = FeatureType::Ridge;
};

// Drawn poly-lines marked as a sketch (the Terrain Sketch Lines filter sets a
// Polyline's type and elevation as arrays on ParaView's lines): where their
// heights come from.
enum class LineElevation
{
  None = 0,    // the synthesis chooses (elevation NaN)
  FromZ = 1,   // each point's z coordinate; the lines are then laid flat
  Constant = 2 // one height for every point
};
// A constant line height lies between the deepest sea floor (the Challenger
// Deep, about 10,935 m down) and the highest summit (Everest, 8,849 m), rounded
// out: a height past them is a slip of the keyboard.
constexpr double kLowestLineElevation = -11000.0;
constexpr double kHighestLineElevation = 9000.0;

// The Terrain Sketch Lines filter's options as a table: FeatureType (ridge +1,
// valley -1, a Polyline's type), ElevationMode (none, z or constant:
// LineElevation) and Elevation (metres, the constant height).
const std::vector<OptionRow>& sketchLineOptionRows();

// The part [t0, t1] of the segment a + t (b - a), 0 <= t <= 1, that lies on a
// grid of width x height cells (cell coordinates -0.5 to width - 0.5, likewise
// in y), by Liang and Barsky's clipping; t0 > t1 when the segment misses it.
struct SegmentPart
{
  double t0 = 0.0;
  double t1 = 1.0;
  bool missed() const { return t0 > t1; }
};
SegmentPart partOnGrid(const Point2& a, const Point2& b, int width, int height);

// Builds a graph from poly-lines as drawn: end points and shared vertices within
// `snapTolerance` cells are merged; vertices where three or more pieces meet
// become branch nodes; a closed poly-line becomes a loop. Only what lies on the
// grid (cell coordinates -0.5 to width - 0.5, likewise in y) is kept: a line
// is cut where it leaves the grid (height constraints interpolated there).
// Throws tsynth::Error for a point that is not a finite number.
FeatureGraph polylineFeatures(const std::vector<Polyline>& lines,
  int width,
  int height,
  double cellX,
  double cellY,
  double snapTolerance = kDefaultSnapCells,
  double controlRadius = kDefaultSketchControlRadius);

// The Terrain Sketch Features filter's options as a table: PatchSize (--patch,
// the synthesis' range), ControlRadius (0: half the patch), CellSize (--cell;
// 0: the image's spacing, or 1 m for poly-lines), SnapTolerance (cells, for
// poly-lines) and SmoothingPasses (for sketch images).
const std::vector<OptionRow>& sketchOptionRows();

} // namespace tsynth
