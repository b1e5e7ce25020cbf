// The placement of a synthesis (Synthesis/PatchPlacement.h) on the bundled
// Colorado DEM and the Y of ridges at 256 x 256, patch 32: the feature patches
// lay the strokes and leave the land away from them to the fill, the fill
// covers every cell, frozen known cells keep their heights, and the steps in
// turn make the untiled synthesis bit for bit.
#include "Core/Grid.h"
#include "Synthesis/PatchPlacement.h"
#include "Synthesis/Synthesizer.h"
#include "YOverColorado.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

using namespace tsynth;

namespace
{

constexpr int kSize = test::kYSize;
constexpr int kPatch = test::kYPatch;

SynthesisOptions options()
{
  SynthesisOptions o;
  o.patchSize = kPatch;
  o.backend = Backend::Cpu;
  o.pool = test::yOverColoradoSetup().pool;
  o.seed = 5;
  return o;
}

// Cells filled, in share of all.
double filledShare(const TileOutcome& o)
{
  return static_cast<double>(std::count(o.kept.begin(), o.kept.end(), 1)) /
    static_cast<double>(o.kept.size());
}

} // namespace

TEST(PatchPlacement, FeaturesThenFillThenFinishAreTheSynthesis)
{
  const SynthesisSetup& setup = test::yOverColoradoSetup();
  const SynthesisOptions o = options();
  const std::vector<const FeatureGraph*> graphs = setup.graphPointers();
  auto matcher = makeSynthesisMatcher(setup.exemplarPointers(), graphs, o);
  PatchPlacement p(setup.target, matcher.get(), graphs, o);
  p.boundHeights(setup.exemplarPointers());
  p.setTypicalNoise(matcher->dense().typicalNoise());

  p.placeFeatures();
  const TileOutcome features = p.outcome(0, {});
  ASSERT_FALSE(features.placements.empty());
  std::size_t trials = 0;
  for (const Placement& placed : features.placements)
  {
    EXPECT_TRUE(placed.feature);
    // The seam is cut for the best few aligned candidates only
    // (kMostFeatureSeamTrials); all the aligned ones were 14.2 of 16 here.
    EXPECT_GE(placed.seamTrials, 1);
    EXPECT_LE(placed.seamTrials, 4);
    trials += static_cast<std::size_t>(placed.seamTrials);
  }
  std::printf("seam trials per feature placement: %.2f\n",
    static_cast<double>(trials) / static_cast<double>(features.placements.size()));
  // The strokes are laid, the land away from them is left to the fill.
  const double afterFeatures = filledShare(features);
  EXPECT_GT(afterFeatures, 0.2);
  EXPECT_LT(afterFeatures, 0.9);
  std::size_t onLines = 0;
  std::size_t onLinesFilled = 0;
  for (const FeatureChain& chain : setup.target.graph.chains)
  {
    forEachChainCell(chain,
      kSize,
      kSize,
      [&](int i, int j, std::size_t, double)
      {
        ++onLines;
        onLinesFilled += features.kept[rowMajor(i, j, kSize)];
      });
  }
  ASSERT_GT(onLines, 100u);
  EXPECT_EQ(onLinesFilled, onLines) << "a stroke cell no feature patch covered";

  p.fill();
  const TileOutcome filled = p.outcome(0, {});
  EXPECT_EQ(filledShare(filled), 1.0);
  EXPECT_GT(filled.placements.size(), features.placements.size());
  for (std::size_t k = features.placements.size(); k < filled.placements.size(); ++k)
  {
    EXPECT_FALSE(filled.placements[k].feature) << k;
  }

  p.releasePlacement();
  const SynthesisResult steps = p.finish();
  const SynthesisResult whole = synthesize(setup, o);
  EXPECT_EQ(steps.terrain.z, whole.terrain.z);
  EXPECT_EQ(steps.patchId, whole.patchId);
  EXPECT_EQ(steps.placements.size(), whole.placements.size());
}

TEST(PatchPlacement, FrozenKnownCellsKeepTheirHeightsThroughTheFill)
{
  const SynthesisSetup& setup = test::yOverColoradoSetup();
  const SynthesisOptions o = options();
  const std::vector<const FeatureGraph*> graphs = setup.graphPointers();
  auto matcher = makeSynthesisMatcher(setup.exemplarPointers(), graphs, o);
  // A known block in the middle, at 1 km: the neighbours' cells a tile continues.
  constexpr int kLow = 96;
  constexpr int kHigh = 160;
  constexpr float kKnown = 1000.0f;
  Heightfield known(kSize, kSize, std::nanf(""));
  known.valid.assign(known.size(), 0);
  std::vector<std::uint8_t> frozen(known.size(), 0);
  for (int j = kLow; j < kHigh; ++j)
  {
    for (int i = kLow; i < kHigh; ++i)
    {
      known.at(i, j) = kKnown;
      known.valid[known.index(i, j)] = 1;
      frozen[known.index(i, j)] = 1;
    }
  }
  PatchPlacement p(setup.target, matcher.get(), graphs, o, &known);
  p.boundHeights(setup.exemplarPointers());
  p.setTypicalNoise(matcher->dense().typicalNoise());
  p.freeze(frozen);
  p.fill();
  const TileOutcome out = p.outcome(0, {});
  EXPECT_EQ(filledShare(out), 1.0);
  for (int j = kLow; j < kHigh; ++j)
  {
    for (int i = kLow; i < kHigh; ++i)
    {
      ASSERT_EQ(out.heights[known.index(i, j)], kKnown) << i << ", " << j;
      ASSERT_EQ(out.patchId[known.index(i, j)], -1) << i << ", " << j;
    }
  }
  // The land round the block was placed by fill patches.
  EXPECT_GT(out.placements.size(), 10u);
}
