// Tests of Kernels/Synthesis/PatchColours.cxx.
// The PatchColour map: patches that touch never share a colour, and colours stay few.
#include "Core/Error.h"
#include "Core/Random.h"
#include "Synthesis/PatchColours.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <set>
#include <vector>

namespace
{

// A Voronoi map of `sites` random centres on a w x h grid, with a hole of no patch (-1): the
// shape of a synthesis's PatchId map (irregular cells, each touching about six others).
std::vector<int> voronoiMap(int w, int h, int sites)
{
  std::vector<double> x;
  std::vector<double> y;
  for (int s = 0; s < sites; ++s)
  {
    x.push_back(
      tsynth::seededUniform(7, tsynth::kStreamSites, static_cast<std::uint64_t>(2 * s)) * w);
    y.push_back(
      tsynth::seededUniform(7, tsynth::kStreamSites, static_cast<std::uint64_t>(2 * s + 1)) * h);
  }
  std::vector<int> id(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), -1);
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      if (i < 10 && j < 10)
      {
        continue; // no patch here
      }
      int best = 0;
      for (int s = 1; s < sites; ++s)
      {
        if (std::hypot(i - x[s], j - y[s]) < std::hypot(i - x[best], j - y[best]))
        {
          best = s;
        }
      }
      id[static_cast<std::size_t>(j) * static_cast<std::size_t>(w) + static_cast<std::size_t>(i)] =
        best;
    }
  }
  return id;
}

} // namespace

TEST(PatchColours, TouchingPatchesDifferAndFewColoursAreUsed)
{
  const int w = 200;
  const int h = 150;
  const std::vector<int> id = voronoiMap(w, h, 120);
  const std::vector<std::int8_t> colour = tsynth::patchColours(id, w, h);
  ASSERT_EQ(colour.size(), id.size());
  std::set<int> used;
  int touchingPairs = 0;
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      const std::size_t k = static_cast<std::size_t>(j * w + i);
      if (id[k] < 0)
      {
        EXPECT_EQ(colour[k], -1);
        continue;
      }
      used.insert(colour[k]);
      EXPECT_GE(colour[k], 0);
      EXPECT_LT(colour[k], tsynth::kPatchColours);
      for (std::size_t n : { k + 1, k + static_cast<std::size_t>(w) })
      {
        const bool inside = (n == k + 1) ? i + 1 < w : j + 1 < h;
        if (inside && id[n] >= 0 && id[n] != id[k])
        {
          ++touchingPairs;
          EXPECT_NE(colour[n], colour[k]) << "patches " << id[k] << " and " << id[n];
        }
      }
    }
  }
  EXPECT_GT(touchingPairs, 1000);
  // A planar map coloured greedily: more than 3 colours (it is not bipartite), at most 7.
  EXPECT_GE(used.size(), 3u);
  EXPECT_LE(used.size(), 7u);
  // Deterministic.
  EXPECT_EQ(tsynth::patchColours(id, w, h), colour);
}

TEST(PatchColours, AMapOfTheWrongSizeIsRefused)
{
  EXPECT_THROW(tsynth::patchColours(std::vector<int>(10, 0), 4, 4), tsynth::Error);
}
