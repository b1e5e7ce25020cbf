// Surface drainage on a heightfield: depression filling (Priority-Flood with
// epsilon, Barnes, Lehman & Mulla 2014), D8 flow directions, flow accumulation,
// and the checks that tell whether a terrain drains.
//
// Seeds (outlets): valid cells on the grid border, valid cells with an invalid
// 8-neighbour (nodata acts as an outlet, as water leaves the known terrain
// there), and valid cells marked in an optional `sinks` mask (lakes or
// sinkholes a user keeps). A cell is invalid where the heightfield's mask says
// so or its height is NaN or infinite.
#pragma once

#include "../Core/Heightfield.h"

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace tsynth
{

// D8 codes 0..7, counter-clockwise from east with x east and y north (row 0 is
// the south edge): E, NE, N, NW, W, SW, S, SE. Odd codes are diagonals.
constexpr int kD8Directions = 8;
constexpr std::int8_t kNoFlow = -1; // pit, flat, outlet on the border or invalid cell
constexpr std::array<int, kD8Directions> kD8Dx = { 1, 1, 0, -1, -1, -1, 0, 1 };
constexpr std::array<int, kD8Directions> kD8Dy = { 0, 1, 1, 1, 0, -1, -1, -1 };

constexpr bool isDiagonalD8(int code)
{
  return (code & 1) != 0;
}

// The code pointing back: E <-> W, NE <-> SW, ...
constexpr int oppositeD8(int code)
{
  return (code + kD8Directions / 2) % kD8Directions;
}

// Index offset of the neighbour along `code` in a row-major grid of `width` columns.
constexpr std::ptrdiff_t d8Offset(int code, int width)
{
  return static_cast<std::ptrdiff_t>(kD8Dy[static_cast<std::size_t>(code)]) * width +
    kD8Dx[static_cast<std::size_t>(code)];
}

// Centre-to-centre distance in metres along each code.
std::array<double, kD8Directions> d8Distances(double cellX, double cellY);

// True if the cell is valid (mask) and its height finite.
inline bool isUsableCell(const Heightfield& dem, std::size_t k)
{
  return dem.isValid(k) && std::isfinite(dem.z[k]);
}

// True if the cell is a valid seed: on the border, next to an invalid cell, or
// a sink (`sinks` may be null; otherwise it has one byte per cell).
bool isSeedCell(const Heightfield& dem, const std::vector<std::uint8_t>* sinks, int i, int j);

// Priority-Flood+epsilon: the lowest surface at or above `dem` on which every
// valid non-seed cell is strictly higher than one of its 8 neighbours, so that
// water from every cell reaches a seed. Depressions are raised to their spill
// level, each filled cell one float step (std::nextafter) above the neighbour
// it drains to, so filled flats keep a gradient. Seeds and cells that already
// drain keep their heights; invalid cells stay invalid. Cells raised to the
// spill level go through a FIFO queue instead of the priority queue, and cells
// climbing a slope are settled without it; the result is the same, bit for bit,
// as a plain priority-queue epsilon fill. Deterministic. Throws tsynth::Error if
// `sinks` has the wrong size or the grid has more than 2^32 - 1 cells.
Heightfield fillDepressions(const Heightfield& dem,
  const std::vector<std::uint8_t>* sinks = nullptr);

// D8 steepest descent: for each valid cell the code of the neighbour with the
// largest drop / distance (metres, cellX and cellY aware), ties to the lowest
// code. Flats that drain (equal heights joined to a cell with a lower
// neighbour, or to a seed) are routed across by the shortest way to their exit,
// so water crosses them as drainsEverywhere says it can. kNoFlow on seeds with
// no lower neighbour (outlets), on pits and flats that do not drain, and on
// invalid cells. `sinks` as for fillDepressions (null: border and nodata only).
std::vector<std::int8_t> flowDirections(const Heightfield& dem,
  const std::vector<std::uint8_t>* sinks = nullptr);

// Number of cells whose flow passes through each cell, itself included (a cell
// with nothing upstream has 1). With `valid` (one byte per cell, 0 = invalid;
// null = every cell counts) invalid cells get 0 and count for nothing. O(N), by
// in-degree topological order. Throws tsynth::Error if the sizes disagree, a
// code is out of range, points off the grid or into an invalid cell, or the
// directions form a cycle.
std::vector<std::uint32_t> flowAccumulation(const std::vector<std::int8_t>& directions,
  int width,
  int height,
  const std::vector<std::uint8_t>* valid = nullptr);

// The pit-free oracle: true if every valid non-seed cell has a strictly lower
// valid 8-neighbour, or is joined through 8-connected cells of equal height to
// a cell that has one or to a seed. Otherwise false, and *firstBadCell (when
// given) is the lowest index of a cell that cannot drain.
bool drainsEverywhere(const Heightfield& dem,
  const std::vector<std::uint8_t>* sinks,
  std::size_t* firstBadCell = nullptr);

// Strict local minima: valid cells off the border whose 8 neighbours are all
// valid and strictly higher.
std::size_t countPits(const Heightfield& dem);

} // namespace tsynth
