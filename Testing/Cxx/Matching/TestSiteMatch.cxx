// Tests of Kernels/Matching/SiteMatch.cxx: matching at one site of a target, dense or at its
// nearest feature, and the cost map.
#include "Core/Error.h"
#include "Features/FeatureGraph.h"
#include "Features/Ppa.h"
#include "Matching/SiteMatch.h"
#include "MatchingTestData.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

using namespace tsynth;
using tsynth::test::matching::colorado;
using tsynth::test::matching::crop;

TEST(SiteMatch, ADenseSiteFindsItsOwnPlaceAndMapsItsCost)
{
  // The target is a piece of the exemplar: matching its centre finds where it
  // was cut (the unrotated variant), and the cost map is lowest there.
  const Heightfield ex = crop(colorado(), 60, 60, 300, 300);
  const Heightfield target = crop(ex, 100, 120, 96, 96);
  const FeatureExtraction f = extractFeatures(ex, FeatureType::Ridge, {});
  MatcherOptions o;
  o.patchSize = 48;
  o.backend = Backend::Cpu;
  PatchMatcher matcher({ &ex }, { &f.graph }, o);
  const std::vector<std::uint8_t> known(target.size(), 1);
  const SiteMatchResult r = matchAtSite(matcher, target, known, 48.0, 48.0, false, 48);
  ASSERT_FALSE(r.candidates.empty());
  EXPECT_FALSE(r.atFeature);
  EXPECT_NEAR(r.candidates[0].centreX, 100 + 48, 0.5);
  EXPECT_NEAR(r.candidates[0].centreY, 120 + 48, 0.5);
  ASSERT_EQ(r.costMap.size(), ex.size());
  std::size_t lowest = 0;
  for (std::size_t k = 0; k < r.costMap.size(); ++k)
  {
    if (std::isfinite(r.costMap[k]) && !(r.costMap[k] >= r.costMap[lowest]))
    {
      lowest = k;
    }
  }
  // Within one coarse block (4 cells) of where the window was cut.
  EXPECT_LE(std::abs(static_cast<int>(lowest % 300) - 148), 4);
  EXPECT_LE(std::abs(static_cast<int>(lowest / 300) - 168), 4);
}

TEST(SiteMatch, AFeatureSiteSnapsToTheNearestTargetFeatureOrSaysThereIsNone)
{
  const Heightfield ex = crop(colorado(), 60, 60, 300, 300);
  FeatureGraph both = extractFeatures(ex, FeatureType::Ridge, {}).graph;
  appendGraph(both, extractFeatures(ex, FeatureType::Valley, {}).graph);
  MatcherOptions o;
  o.patchSize = 48;
  o.backend = Backend::Cpu;
  PatchMatcher matcher({ &ex }, { &both }, o);
  const std::vector<std::uint8_t> known(ex.size(), 1);
  const SiteMatchResult r = matchAtSite(matcher, ex, known, 150.0, 150.0, true, 48);
  ASSERT_TRUE(r.atFeature);
  EXPECT_LE(std::hypot(r.centreX - 150.0, r.centreY - 150.0), 24.0);
  EXPECT_TRUE(r.candidates.front().feature);
  // A flat target has no feature: a dense match and a warning.
  Heightfield flat(96, 96, 3000.0f);
  flat.cellX = flat.cellY = ex.cellX;
  const SiteMatchResult none =
    matchAtSite(matcher, flat, std::vector<std::uint8_t>(flat.size(), 1), 48.0, 48.0, true, 48);
  EXPECT_FALSE(none.atFeature);
  EXPECT_FALSE(none.candidates.empty());
  ASSERT_FALSE(none.warnings.empty());
  EXPECT_NE(none.warnings.front().find("No target feature"), std::string::npos);
  // Bad input.
  EXPECT_THROW(
    matchAtSite(matcher, flat, std::vector<std::uint8_t>(5, 1), 48, 48, false, 48), Error);
  EXPECT_THROW(
    matchAtSite(
      matcher, crop(ex, 0, 0, 40, 40), std::vector<std::uint8_t>(1600, 1), 20, 20, false, 48),
    Error);
}
