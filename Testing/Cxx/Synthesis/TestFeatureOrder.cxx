// Tests of Kernels/Synthesis/FeatureOrder.cxx.
// The order the feature patches are placed in (Synthesis/FeatureOrder): the
// sites along a Y of ridges, breadth first from its branch node, and thinned
// where they crowd.
#include "Core/Random.h"
#include "Features/Sketch.h"
#include "Synthesis/FeatureOrder.h"
#include "Synthesis/Finishing.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

using namespace tsynth;

namespace
{

constexpr int kSize = 256;
constexpr int kPatch = 32;

// A Y of ridges: a stem from the south and two arms from its top.
SynthesisTarget yTarget()
{
  SynthesisTarget t;
  t.field = Heightfield(kSize, kSize);
  const Point2 fork{ 128, 120 };
  const std::vector<Polyline> lines{ { { { 128, 10 }, fork }, {}, FeatureType::Ridge },
    { { fork, { 40, 240 } }, {}, FeatureType::Ridge },
    { { fork, { 216, 240 } }, {}, FeatureType::Ridge } };
  t.graph = polylineFeatures(lines, kSize, kSize, 1.0, 1.0);
  t.lineHalfSpacing = kSize; // strokes far apart: nothing crowds
  return t;
}

double distance(const Point2& a, const Point2& b)
{
  return std::hypot(a.x - b.x, a.y - b.y);
}

// The smallest distance between two of the sites.
double closestPair(const std::vector<FeatureSite>& sites)
{
  double closest = 1e300;
  for (std::size_t a = 0; a < sites.size(); ++a)
  {
    for (std::size_t b = a + 1; b < sites.size(); ++b)
    {
      closest = std::min(closest, distance(sites[a].centre, sites[b].centre));
    }
  }
  return closest;
}

} // namespace

TEST(FeatureOrder, BreadthFirstFromTheForkEachArmWalkedAwayFromIt)
{
  const SynthesisTarget t = yTarget();
  ASSERT_EQ(t.graph.chains.size(), 3u);
  const std::vector<FeatureSite> sites = featurePlacementOrder(t, kPatch, 7);
  // The fork (the highest-degree node) first, then every arm's path points.
  ASSERT_FALSE(sites.empty());
  EXPECT_EQ(sites.front().node, t.graph.bfsOrder.front());
  EXPECT_NEAR(sites.front().centre.x, 128.0, 1.0);
  EXPECT_NEAR(sites.front().centre.y, 120.0, 1.0);
  // Each chain's path points come together, kSiteSpacingInPatches apart,
  // moving away from the fork.
  for (std::size_t c = 0; c < t.graph.chains.size(); ++c)
  {
    std::vector<Point2> along;
    for (const FeatureSite& s : sites)
    {
      if (s.node < 0 && s.chain == static_cast<int>(c))
      {
        along.push_back(s.centre);
      }
    }
    ASSERT_GE(along.size(), 3u) << c;
    for (std::size_t k = 1; k < along.size(); ++k)
    {
      EXPECT_NEAR(distance(along[k - 1], along[k]), kSiteSpacingInPatches * kPatch, 1.5)
        << c << ", " << k;
      EXPECT_GT(
        distance(along[k], sites.front().centre), distance(along[k - 1], sites.front().centre))
        << c << ", " << k;
    }
  }
  // Every site once: those featureSites makes at that spacing with the
  // seed's phases, none left out or repeated.
  std::vector<double> phases(t.graph.chains.size());
  for (std::size_t c = 0; c < phases.size(); ++c)
  {
    phases[c] = seededUniform(7, kStreamSites, c);
  }
  const std::vector<FeatureSite> all =
    featureSites(t.graph, kPatch, kSiteSpacingInPatches * kPatch, &phases);
  ASSERT_EQ(sites.size(), all.size());
  for (const FeatureSite& s : all)
  {
    EXPECT_EQ(std::count_if(sites.begin(),
                sites.end(),
                [&](const FeatureSite& o) { return distance(o.centre, s.centre) == 0.0; }),
      1);
  }
}

TEST(FeatureOrder, TheSeedShiftsThePathPointsOnlyAndTheSameSeedGivesTheSameOrder)
{
  const SynthesisTarget t = yTarget();
  const std::vector<FeatureSite> a = featurePlacementOrder(t, kPatch, 1);
  const std::vector<FeatureSite> again = featurePlacementOrder(t, kPatch, 1);
  const std::vector<FeatureSite> b = featurePlacementOrder(t, kPatch, 2);
  ASSERT_EQ(a.size(), again.size());
  for (std::size_t s = 0; s < a.size(); ++s)
  {
    EXPECT_EQ(a[s].centre.x, again[s].centre.x);
    EXPECT_EQ(a[s].centre.y, again[s].centre.y);
  }
  // The nodes stay in their order and place; the chains' points move.
  auto nodes = [](const std::vector<FeatureSite>& sites)
  {
    std::vector<std::pair<int, double>> n;
    for (const FeatureSite& s : sites)
    {
      if (s.node >= 0)
      {
        n.emplace_back(s.node, s.centre.x + 1000.0 * s.centre.y);
      }
    }
    return n;
  };
  EXPECT_EQ(nodes(a), nodes(b));
  double shift = 0.0;
  for (const FeatureSite& s : a)
  {
    if (s.node < 0)
    {
      double nearest = 1e300;
      for (const FeatureSite& o : b)
      {
        nearest = std::min(nearest, distance(s.centre, o.centre));
      }
      shift = std::max(shift, nearest);
    }
  }
  EXPECT_GT(shift, 1.0);
}

TEST(FeatureOrder, SitesCrowdOnADemTargetOrOnLinesCloserThanPatchesDraw)
{
  SynthesisTarget t = yTarget();
  EXPECT_FALSE(featureSitesCrowd(t, kPatch));
  const std::vector<FeatureSite> roomy = featurePlacementOrder(t, kPatch, 0);
  EXPECT_LT(closestPair(roomy), kSiteClearanceInPatches * kPatch); // the fork's arms start close

  const double finest = kFinestDrawnSpacingInPatches * kPatch;
  t.lineHalfSpacing = 0.45 * finest; // lines 0.9 of the finest spacing apart
  EXPECT_TRUE(featureSitesCrowd(t, kPatch));
  t.lineHalfSpacing = 0.55 * finest;
  EXPECT_FALSE(featureSitesCrowd(t, kPatch));
  t.detailed = true; // a DEM target
  EXPECT_TRUE(featureSitesCrowd(t, kPatch));

  const std::vector<FeatureSite> thinned = featurePlacementOrder(t, kPatch, 0);
  EXPECT_LT(thinned.size(), roomy.size());
  EXPECT_GE(closestPair(thinned), kSiteClearanceInPatches * kPatch);
  // Each site left out lies within the clearance of one kept before it.
  for (const FeatureSite& s : roomy)
  {
    double nearest = 1e300;
    for (const FeatureSite& k : thinned)
    {
      nearest = std::min(nearest, distance(s.centre, k.centre));
    }
    EXPECT_LT(nearest, kSiteClearanceInPatches * kPatch + 1e-9);
  }
}

TEST(FeatureOrder, SpacedOutKeepsTheFirstOfEachCrowdInOrder)
{
  // Sites every cell along a row, and one in the far corner (the bucket grid's
  // last bucket): every fifth is kept for a clearance of 4.5 cells.
  std::vector<FeatureSite> sites;
  for (int x = 0; x < 40; ++x)
  {
    FeatureSite s;
    s.centre = { static_cast<double>(x), 10.0 };
    s.chain = x;
    sites.push_back(s);
  }
  FeatureSite corner;
  corner.centre = { 99.0, 99.0 };
  corner.chain = 99;
  sites.push_back(corner);
  const std::vector<FeatureSite> kept = spacedOut(sites, 4.5, 100, 100);
  std::vector<int> chains;
  for (const FeatureSite& s : kept)
  {
    chains.push_back(s.chain);
  }
  EXPECT_EQ(chains, (std::vector<int>{ 0, 5, 10, 15, 20, 25, 30, 35, 99 }));
}
