// Row-major grids. Cell (i, j) of a grid `width` cells wide is element
// j * width + i; the index arithmetic is done in std::size_t once, here, so
// that callers read like the formulas. Any integer types may be passed; each
// is converted to std::size_t before the product, as a cast at the call would.
#pragma once

#include <cstddef>
#include <vector>

namespace tsynth
{

// The element of cell (i, j) in a row-major grid `width` wide.
template<class I, class J, class W>
constexpr std::size_t rowMajor(I i, J j, W width)
{
  return static_cast<std::size_t>(j) * static_cast<std::size_t>(width) +
    static_cast<std::size_t>(i);
}

// The cells of a width x height grid (or any product of two counts).
template<class W, class H>
constexpr std::size_t cellCount(W width, H height)
{
  return static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
}

// A cell's column and row.
struct GridCell
{
  int i;
  int j;
};

// Column and row of element k of a row-major grid `width` wide (rowMajor's inverse).
inline GridCell cellOf(std::size_t k, int width)
{
  const std::size_t w = static_cast<std::size_t>(width); // a grid width is never negative
  return { static_cast<int>(k % w), static_cast<int>(k / w) };
}

// Element k moved by a signed index offset (a neighbour's: negative towards the south and west).
inline std::size_t offsetCell(std::size_t k, std::ptrdiff_t offset)
{
  return static_cast<std::size_t>(static_cast<std::ptrdiff_t>(k) + offset);
}

// A width x height grid of T, row-major: at(i, j) is values[j * width + i].
template<class T>
struct Grid
{
  int width = 0;
  int height = 0;
  std::vector<T> values;

  Grid() = default;
  Grid(int w, int h, const T& fill = T{})
    : width(w)
    , height(h)
    , values(cellCount(w, h), fill)
  {
  }
  std::size_t size() const { return values.size(); }
  std::size_t index(int i, int j) const { return rowMajor(i, j, width); }
  bool contains(int i, int j) const { return i >= 0 && j >= 0 && i < width && j < height; }
  T& at(int i, int j) { return values[index(i, j)]; }
  const T& at(int i, int j) const { return values[index(i, j)]; }
  T& operator[](std::size_t k) { return values[k]; }
  const T& operator[](std::size_t k) const { return values[k]; }
};

} // namespace tsynth
