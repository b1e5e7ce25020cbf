// The fill of a synthesis: the grid of windows it fills the output through,
// and the order it visits them in (best first, or concentric), each window
// filled by a step the synthesiser gives. Independent of the placement itself.
#pragma once

#include "../Core/Heightfield.h"
#include "../Core/OptionTable.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <iterator>
#include <vector>

namespace tsynth
{

enum class FillOrder
{
  BestFirst, // priority = confidence + data term, updated locally after each merge
  Concentric // confidence only: layer by layer around what is filled
};

// The fill orders' words, by value (Core/OptionTable.h).
inline constexpr const char* kFillOrderWords[] = { "best-first", "concentric" };
static_assert(std::size(kFillOrderWords) == static_cast<std::size_t>(FillOrder::Concentric) + 1);

// The fill's windows stand this far apart, in patches: half a patch, so that
// each overlaps what is there by at least a quarter patch on every side, and a
// patch's seams have room to hide. The preview spaces them wider (Preview.h).
constexpr double kDefaultFillSpacing = 0.5;
// Consecutive windows overlap by at least this share of a patch, however they
// are spaced and moved by the seed: room for the graph cut to find a seam.
constexpr double kMinFillOverlapInPatches = 0.25;
// So windows may stand at most this far apart.
constexpr double kMaxFillSpacing = 1.0 - kMinFillOverlapInPatches;

// Placements tried at one window before it is retired.
constexpr int kMaxFillAttempts = 4;

// The fill's windows (each a patch square, lower-left corner x0, y0): along
// each axis, windows flush with both edges and evenly spaced at most
// `spacing` patches apart in between, each inner one moved by up to
// kGridJitterInPatches of a patch as the seed draws (consecutive windows
// still overlap by at least kMinFillOverlapInPatches). Window s is column
// s % xs.size() of row s / xs.size().
struct FillGrid
{
  std::vector<int> xs, ys;
  std::size_t size() const { return xs.size() * ys.size(); }
  int x0(std::size_t s) const { return xs[s % xs.size()]; }
  int y0(std::size_t s) const { return ys[s / xs.size()]; }
};

// The window corners along one axis of `length` cells (axis 0: x, 1: y).
std::vector<int> fillGridLine(int length,
  int patchSize,
  double spacing,
  std::uint64_t seed,
  std::uint64_t axis);

FillGrid fillGrid(int width, int height, int patchSize, double spacing, std::uint64_t seed);

// Each window's data term: the mean slope of the target in it, sampled every
// few cells, scaled so that the steepest window has 1 (all 0 on flat land).
std::vector<double> fillDataTerms(const Heightfield& target, const FillGrid& grid, int patchSize);

// What the fill does to the output, given by the synthesiser.
struct FillSteps
{
  // The share (0..1) of window (x0, y0) already filled; 1 for one wholly outside.
  std::function<double(int x0, int y0)> filledShare;
  // Places a patch at window (x0, y0); returns how many cells it wrote (0: no
  // candidate could cover its empty cells).
  std::function<std::size_t(int x0, int y0)> fillWindow;
  // The share of the windows open at the start that have been visited (0..1).
  std::function<void(double fraction)> progress;
};

// The fill: every window with empty cells is visited in order of priority,
// its filled share (plus its data term when best first), ties in the seed's
// order, and re-scored once a patch touched it, until every window is filled
// or retired (no candidate wrote a cell, or kMaxFillAttempts tries). A
// max-heap of priorities with version stamps: only the windows a patch
// touched are re-scored and nothing is re-sorted.
void runFill(const FillGrid& grid,
  const std::vector<double>& dataTerms,
  FillOrder order,
  std::uint64_t seed,
  const FillSteps& steps);

} // namespace tsynth
