// Tests of Kernels/Synthesis/Synthesiser.cxx: a synthesis stopped after N placements
// (SynthesisOptions::placementLimit).
#include "Core/Error.h"
#include "PlacementTestData.h"
#include "Synthesis/Synthesiser.h"
#include "YOverColorado.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>

using namespace tsynth;
using tsynth::test::placement::kPatch;
using tsynth::test::placement::options;

TEST(PatchPlacement, AStoppedRunIsTheWholeSynthesisFirstPlacementsUnfinished)
{
  // Stepping through the synthesis (SynthesisOptions::placementLimit): stopped
  // after N placements, among the feature patches and in the fill, the run has
  // the whole synthesis' first N placements; its terrain holds heights where
  // they wrote and NaN elsewhere: nothing is finished.
  const SynthesisSetup& setup = test::yOverColoradoSetup();
  SynthesisOptions o = options();
  const SynthesisResult whole = synthesise(setup, o);
  std::size_t features = 0;
  while (features < whole.placements.size() && whole.placements[features].feature)
  {
    ++features;
  }
  ASSERT_GT(features, 2u);
  ASSERT_GT(whole.placements.size(), features + 2);
  for (const std::size_t limit : { std::size_t{ 0 }, features / 2, features + 2 })
  {
    o.placementLimit = limit;
    const SynthesisResult part = synthesise(setup, o);
    ASSERT_EQ(part.placements.size(), limit);
    for (std::size_t k = 0; k < limit; ++k)
    {
      EXPECT_EQ(part.placements[k].x0, whole.placements[k].x0) << k;
      EXPECT_EQ(part.placements[k].y0, whole.placements[k].y0) << k;
      EXPECT_EQ(part.placements[k].sourceX, whole.placements[k].sourceX) << k;
      EXPECT_EQ(part.placements[k].variant, whole.placements[k].variant) << k;
      EXPECT_EQ(part.placements[k].offset, whole.placements[k].offset) << k;
    }
    // The terrain: the patches' own heights where they wrote, NaN elsewhere.
    std::size_t written = 0;
    for (std::size_t c = 0; c < part.terrain.size(); ++c)
    {
      const bool wrote = part.patchId[c] >= 0;
      ASSERT_EQ(std::isnan(part.terrain.z[c]), !wrote) << c;
      written += wrote ? 1 : 0;
    }
    EXPECT_EQ(written > 0, limit > 0);
    EXPECT_EQ(part.terrain.z.size(), part.patches.z.size());
  }
  // Stepping works on one piece.
  o.placementLimit = 3;
  o.tileSize = 2 * kPatch;
  EXPECT_THROW(synthesise(setup, o), Error);
}
