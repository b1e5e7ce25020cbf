// Tests of Kernels/Optimisation/PatchMatch.cxx: the orientation maps, the E-step and
// up-sampling on exact matches.
#include "Optimisation/PatchMatch.h"
#include "Optimisation/Pyramid.h"
#include "OptimisationTestData.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

using namespace tsynth;
using tsynth::test::optimisation::crop;
using tsynth::test::optimisation::source;

namespace
{

std::size_t sz(int v)
{
  return static_cast<std::size_t>(v);
}

} // namespace

TEST(Optimisation, OrientedCopiesHoldTheTurnedSourcePatches)
{
  const Heightfield s = crop(source(), 0, 0, 40, 30);
  const optim::SourceLevel level = optim::makeSourceLevel(s, 5, true, true, 0);
  ASSERT_EQ(level.orientations.size(), 8u);
  for (int t : level.orientations)
  {
    const optim::OrientedCopy& c = level.copies[sz(t)];
    EXPECT_EQ(c.width, t % 2 == 0 ? 40 : 30);
    const optim::Orientation& o = c.toSource;
    for (int v = 0; v < c.height; ++v)
    {
      for (int u = 0; u < c.width; ++u)
      {
        const optim::Match m{ u, v, t };
        const std::array<int, 2> at = optim::toSource(level, m);
        ASSERT_EQ(c.z[sz(v) * c.stride + sz(u)], s.at(at[0], at[1]));
        const optim::Match back = optim::fromSource(level, at[0], at[1], t);
        ASSERT_TRUE(back.x == u && back.y == v);
      }
    }
    // The patch read around a copy's centre is the source at c + A u.
    const optim::Match centre{ 10, 12, t };
    const std::array<int, 2> at = optim::toSource(level, centre);
    EXPECT_EQ(c.z[sz(centre.y + 1) * c.stride + sz(centre.x + 2)],
      s.at(at[0] + o.a[0] * 2 + o.a[1] * 1, at[1] + o.a[2] * 2 + o.a[3] * 1));
  }
}

TEST(Optimisation, ExactMatchesReconstructTheSourceAndSurviveUpsampling)
{
  const Heightfield fine = crop(source(), 0, 0, 64, 64);
  const Heightfield coarse = optim::downsampleHalf(fine);
  const optim::SourceLevel sf = optim::makeSourceLevel(fine, 5, false, false, 0);
  const optim::SourceLevel sc = optim::makeSourceLevel(coarse, 5, false, false, 1);
  // Each coarse cell matched to itself (clamped into the valid centres).
  std::vector<optim::Match> map(coarse.size());
  for (int y = 0; y < coarse.height; ++y)
  {
    for (int x = 0; x < coarse.width; ++x)
    {
      map[coarse.index(x, y)] = {
        std::clamp(x, 2, coarse.width - 3), std::clamp(y, 2, coarse.height - 3), 0
      };
    }
  }
  const std::vector<optim::Match> up =
    optim::upsampleMatches(map, coarse.width, sc, sf, fine.width, fine.height, 1, 2);
  std::vector<float> out;
  optim::reconstruct(sf, up, fine.width, fine.height, {}, {}, 0.0, out);
  // Away from the clamped border every patch is the source's own: exact.
  for (int y = 8; y < fine.height - 8; ++y)
  {
    for (int x = 8; x < fine.width - 8; ++x)
    {
      const optim::Match& m = up[fine.index(x, y)];
      ASSERT_TRUE(m.x == x && m.y == y) << x << " " << y;
      ASSERT_EQ(out[fine.index(x, y)], fine.at(x, y));
    }
  }
  // Matching the source against itself finds zero cost almost everywhere.
  optim::TargetGrid g{ fine.width, fine.height, fine.z };
  std::vector<optim::Match> found = optim::randomMatches(sf, fine.width, fine.height, 3, 4);
  std::vector<float> cost;
  optim::PatchMatchSettings settings;
  settings.iterations = 6;
  optim::patchMatch(sf, g, found, cost, settings);
  std::size_t exact = 0;
  for (int y = 2; y < fine.height - 2; ++y)
  {
    for (int x = 2; x < fine.width - 2; ++x)
    {
      exact += cost[fine.index(x, y)] == 0.0f ? 1 : 0;
    }
  }
  EXPECT_GT(double(exact) / (60.0 * 60.0), 0.95);
}
