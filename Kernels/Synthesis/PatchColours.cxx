#include "PatchColours.h"

#include "../Core/Error.h"

#include <algorithm>
#include <array>
#include <cstddef>

namespace tsynth
{

namespace
{

using Neighbours = std::vector<std::vector<int>>;

// The patches each patch shares an edge of cells with (sorted, without repeats).
Neighbours touchingPatches(const std::vector<int>& id, std::size_t width, std::size_t height)
{
  const int patches = id.empty() ? 0 : *std::max_element(id.begin(), id.end()) + 1;
  Neighbours touching(static_cast<std::size_t>(std::max(patches, 0)));
  auto link = [&](int a, int b)
  {
    if (a >= 0 && b >= 0 && a != b)
    {
      touching[static_cast<std::size_t>(a)].push_back(b);
      touching[static_cast<std::size_t>(b)].push_back(a);
    }
  };
  for (std::size_t j = 0; j < height; ++j)
  {
    for (std::size_t i = 0; i < width; ++i)
    {
      const std::size_t k = j * width + i;
      if (i + 1 < width)
      {
        link(id[k], id[k + 1]);
      }
      if (j + 1 < height)
      {
        link(id[k], id[k + width]);
      }
    }
  }
  for (auto& list : touching)
  {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  return touching;
}

} // namespace

std::vector<std::int8_t> patchColours(const std::vector<int>& patchId, int width, int height)
{
  const std::size_t w = static_cast<std::size_t>(std::max(width, 0));
  const std::size_t h = static_cast<std::size_t>(std::max(height, 0));
  if (patchId.size() != w * h)
  {
    throw Error("The PatchId map has " + std::to_string(patchId.size()) + " values for a " +
      std::to_string(width) + " x " + std::to_string(height) + " grid.");
  }
  const Neighbours touching = touchingPatches(patchId, w, h);
  std::vector<std::int8_t> colourOf(touching.size(), -1);
  for (std::size_t p = 0; p < touching.size(); ++p)
  {
    std::array<int, kPatchColours> taken{};
    for (int n : touching[p])
    {
      const std::int8_t c = colourOf[static_cast<std::size_t>(n)];
      if (c >= 0)
      {
        ++taken[static_cast<std::size_t>(c)];
      }
    }
    colourOf[p] = static_cast<std::int8_t>(
      std::min_element(taken.begin(), taken.end()) - taken.begin()); // first free, else rarest
  }
  std::vector<std::int8_t> colours(patchId.size(), -1);
  for (std::size_t k = 0; k < patchId.size(); ++k)
  {
    if (patchId[k] >= 0)
    {
      colours[k] = colourOf[static_cast<std::size_t>(patchId[k])];
    }
  }
  return colours;
}

} // namespace tsynth
