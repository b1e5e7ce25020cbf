// Tests of Kernels/Distance/DistanceSynthesis.cxx.
// Distance-based terrain synthesis (Rusnell 2009) against the thesis's worked
// examples and hand-computed answers: the sea level of Fig 3.6, a cone of a
// linear profile, the blend of eq. 3.7 against its formula, region profiles,
// dendritic ridges, the queues, determinism over seeds and threads, and each
// bad input's message.
#include "Core/Cancellation.h"
#include "Core/Error.h"
#include "Distance/DistanceSynthesis.h"
#include "Distance/Generators.h"
#include "DistanceTestData.h"

#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

using namespace tsynth;

namespace
{

using tsynth::test::distance::cellOf;
using tsynth::test::distance::expectThrowsWith;
using tsynth::test::distance::plainOptions;
using tsynth::test::distance::point;

MonotoneProfile linearProfile(double width)
{
  return MonotoneProfile::fromPoints({ 0.0, width }, { 1.0, 0.0 });
}

// ---------------------------------------------------------------------------
// Worked examples of the thesis

TEST(DistanceSynthesis, SeaLevelOfFigure36)
{
  // s = 1.0 and c_max = 55 give c_s = 55: a generator of cost 10 is 45 high.
  DistanceInputs in;
  in.width = 96;
  in.height = 32;
  in.features = { point(8, 16, 96, 55.0f), point(80, 16, 96, 10.0f) };
  DistanceOptions o = plainOptions();
  o.seaLevelScale = 1.0;
  const DistanceTerrain t = synthesiseByDistance(in, o);
  EXPECT_DOUBLE_EQ(t.seaLevelCost, 55.0);
  EXPECT_DOUBLE_EQ(t.maxGeneratorCost, 55.0);
  EXPECT_NEAR(t.heights.at(80, 16), 45.0f, 1e-5f);
  // The cost-55 generator sits at sea level: nothing above it.
  EXPECT_EQ(t.heights.at(8, 16), 0.0f);
  EXPECT_EQ(t.warnings.size(), 1u); // it is clipped (cost >= c_s)
  // s = 1.2: c_s = 66 and the generator is 56 high (+0.2 in s adds 11 units).
  o.seaLevelScale = 1.2;
  const DistanceTerrain higher = synthesiseByDistance(in, o);
  EXPECT_NEAR(higher.seaLevelCost, 66.0, 1e-9);
  EXPECT_NEAR(higher.heights.at(80, 16), 56.0f, 1e-5f);
  // Without profiles each step costs mu_w: 45 - 1 per axis step.
  EXPECT_NEAR(t.heights.at(70, 16), 35.0f, 1e-4f);
  EXPECT_NEAR(t.heights.at(75, 11), 45.0f - 5.0f * std::sqrt(2.0f), 1e-4f);
}

TEST(DistanceSynthesis, ConeOfALinearProfile)
{
  // A point of cost 10, c_s = 3 * 10 = 30, a linear profile 40 cells wide, r = 0:
  // height 20 at the top, falling 30 / 40 per axis step, footprint radius
  // (c_s - c_g) / c_s * 40 = 26.67 cells in the octile metric.
  const int w = 81;
  DistanceInputs in;
  in.width = w;
  in.height = w;
  in.features = { point(40, 40, w, 10.0f, 0) };
  in.profiles = { linearProfile(40.0) };
  DistanceOptions o = plainOptions();
  o.seaLevelScale = 3.0;
  const DistanceTerrain t = synthesiseByDistance(in, o);
  EXPECT_NEAR(t.heights.at(40, 40), 20.0f, 1e-6f);
  int footprint = 0;
  int expected = 0;
  for (int row = 0; row < w; ++row)
  {
    for (int col = 0; col < w; ++col)
    {
      const double ax = std::abs(col - 40);
      const double ay = std::abs(row - 40);
      const double octile = std::max(ax, ay) + (std::sqrt(2.0) - 1.0) * std::min(ax, ay);
      const double h = 20.0 - 0.75 * octile;
      footprint += t.heights.at(col, row) > 0.0f ? 1 : 0;
      expected += h > 0.0 ? 1 : 0;
      if (h > 1e-3)
      {
        ASSERT_NEAR(t.heights.at(col, row), h, 2e-4) << col << "," << row;
      }
      else if (h < -1e-3)
      {
        ASSERT_EQ(t.heights.at(col, row), 0.0f) << col << "," << row;
      }
    }
  }
  EXPECT_EQ(footprint, expected);
  EXPECT_EQ(t.heights.at(40 + 26, 40) > 0.0f, true); // 26 < 26.67 <= 27
  EXPECT_EQ(t.heights.at(40 + 27, 40), 0.0f);
  EXPECT_EQ(t.featureVisits, static_cast<std::size_t>(footprint)); // bounded: its footprint only
}

TEST(DistanceSynthesis, ProfileScaleStretchesTheFootprint)
{
  const int w = 121;
  DistanceInputs in;
  in.width = w;
  in.height = 9;
  in.features = { point(60, 4, w, 10.0f, 0) };
  in.profiles = { linearProfile(20.0) };
  DistanceOptions o = plainOptions();
  o.seaLevelScale = 2.0; // k = 1/2: radius 10 profile units
  o.profileScale = 3.0;  // 3 cells per unit: 30 cells
  const DistanceTerrain t = synthesiseByDistance(in, o);
  EXPECT_GT(t.heights.at(60 + 29, 4), 0.0f);
  EXPECT_EQ(t.heights.at(60 + 30, 4), 0.0f);
  EXPECT_NEAR(t.heights.at(60 + 15, 4), 5.0f, 1e-4f); // half way down from 10
}

TEST(DistanceSynthesis, ModifiedCostGivesEveryFeatureItsWholeProfile)
{
  // Eq. 3.6: a low feature (cost 20 of c_s 30) is a copy of the high one's
  // shape scaled by k = 1/3 in height and width: 40-cell profile -> radius 13.3.
  const int w = 61;
  DistanceInputs in;
  in.width = w;
  in.height = 5;
  in.features = { point(30, 2, w, 20.0f, 0) };
  in.profiles = { linearProfile(40.0) };
  DistanceOptions o = plainOptions();
  o.seaLevelScale = 1.5;
  const DistanceTerrain t = synthesiseByDistance(in, o);
  EXPECT_NEAR(t.heights.at(30, 2), 10.0f, 1e-5f);
  EXPECT_GT(t.heights.at(30 + 13, 2), 0.0f);
  EXPECT_EQ(t.heights.at(30 + 14, 2), 0.0f);
}

// ---------------------------------------------------------------------------
// Blending (eq. 3.7)

struct TwoFeatures
{
  DistanceTerrain a;
  DistanceTerrain b;
  DistanceInputs both;
};

TwoFeatures twoOverlappingFeatures(DistanceOptions o)
{
  TwoFeatures r;
  r.both.width = 90;
  r.both.height = 50;
  r.both.features = { point(30, 25, 90, 10.0f), point(55, 22, 90, 10.0f) };
  DistanceInputs one = r.both;
  one.features = { r.both.features[0] };
  r.a = synthesiseByDistance(one, o);
  one.features = { r.both.features[1] };
  r.b = synthesiseByDistance(one, o);
  return r;
}

TEST(DistanceSynthesis, BlendFollowsEquation37)
{
  DistanceOptions o;
  o.roughness = 0.5; // random weights: the two fields differ in shape
  o.heightScale = 1.0;
  o.seaLevelScale = 3.0;
  o.approximateFraction = 0.0; // no halting by the other feature: the passes are the lone ones
  for (const double b : { 0.0, 4.0, 60.0 })
  {
    o.blendBias = b;
    const TwoFeatures r = twoOverlappingFeatures(o);
    const DistanceTerrain t = synthesiseByDistance(r.both, o);
    int overlap = 0;
    double worstMaxGap = 0.0;
    for (std::size_t k = 0; k < t.heights.size(); ++k)
    {
      const double ha = r.a.heights.z[k];
      const double hb = r.b.heights.z[k];
      double expected = ha > 0.0 && hb > 0.0
        ? (std::pow(ha, b + 1) + std::pow(hb, b + 1)) / (std::pow(ha, b) + std::pow(hb, b))
        : std::max(ha, hb);
      if (b == 0.0 && ha > 0.0 && hb > 0.0)
      {
        expected = 0.5 * (ha + hb); // the plain mean
      }
      ASSERT_NEAR(t.heights.z[k], expected, 1e-4 * (1.0 + expected)) << "b " << b << " cell " << k;
      if (ha > 0.0 && hb > 0.0)
      {
        ++overlap;
        worstMaxGap = std::max(worstMaxGap, std::max(ha, hb) - t.heights.z[k]);
        EXPECT_EQ(t.contributors[k], 2);
      }
    }
    EXPECT_GT(overlap, 200);
    if (b == 60.0)
    {
      EXPECT_LT(worstMaxGap, 0.3); // tends to the maximum (heights here reach 20)
    }
    if (b == 0.0)
    {
      EXPECT_GT(worstMaxGap, 5.0); // the mean is far from the maximum
    }
  }
}

TEST(DistanceSynthesis, ApproximateHaltingPrunesHiddenFeatures)
{
  // A low feature beside a high one: with p_f it stops where it is below 5%
  // of the approximate height, so it settles fewer cells.
  DistanceInputs in;
  in.width = 80;
  in.height = 40;
  in.features = { point(30, 20, 80, 0.0f), point(40, 20, 80, 18.0f) };
  DistanceOptions o = plainOptions();
  o.seaLevelScale = 1.0 / 0.9; // c_s = 20
  o.approximateFraction = 0.0;
  const DistanceTerrain full = synthesiseByDistance(in, o);
  o.approximateFraction = 0.5;
  const DistanceTerrain pruned = synthesiseByDistance(in, o);
  EXPECT_LT(pruned.featureVisits, full.featureVisits);
}

// ---------------------------------------------------------------------------
// Regions, ridges, generators

DistanceFeature ring(int cx, int cy, double radius, int width, float cost, int profile)
{
  DistanceFeature f;
  GeneratorLine line;
  for (int i = 0; i <= 64; ++i)
  {
    const double a = 2.0 * M_PI * i / 64.0;
    line.points.push_back({ cx + radius * std::cos(a), cy + radius * std::sin(a) });
  }
  line.profile = profile;
  f = generatorsFromLines({ line }, width, width, profile + 1)[0];
  for (GeneratorNode& node : f.nodes)
  {
    node.cost = cost;
  }
  return f;
}

TEST(DistanceSynthesis, RegionProfileOverridesInsideACrater)
{
  const int w = 80;
  DistanceInputs in;
  in.width = w;
  in.height = w;
  in.features = { ring(40, 40, 15.0, w, 5.0f, 0), point(40, 62, w, 5.0f, 0) };
  // Profile 0 a wide linear one, profile 1 a bowl: a steep wall, then a floor.
  in.profiles = { linearProfile(60.0),
    MonotoneProfile::fromPoints({ 0.0, 4.0, 100.0 }, { 1.0, 0.3, 0.0 }) };
  in.regions = enclosedRegions({ in.features[0] }, w, w, 1);
  ASSERT_EQ(in.regions.size(), 1u);
  EXPECT_GT(in.regions[0].cells.size(), 500u); // pi 14^2 = 615
  DistanceOptions o = plainOptions();
  o.seaLevelScale = 4.0;
  const DistanceTerrain t = synthesiseByDistance(in, o);
  DistanceInputs alone = in;
  alone.features.pop_back();
  const DistanceTerrain ringOnly = synthesiseByDistance(alone, o);
  DistanceInputs noRegion = alone;
  noRegion.regions.clear();
  const DistanceTerrain plain = synthesiseByDistance(noRegion, o);
  for (const std::int32_t k : in.regions[0].cells)
  {
    const auto c = static_cast<std::size_t>(k);
    ASSERT_EQ(t.contributors[c], 1);                  // the crater alone blends inside
    ASSERT_EQ(t.heights.z[c], ringOnly.heights.z[c]); // the other feature is excluded
  }
  // The bowl shapes the inside: the linear profile alone would leave the centre
  // at 15 - 15 * (20 / 60) = 10; the bowl's wall drops it below 5.
  EXPECT_NEAR(plain.heights.at(40, 40), 10.0f, 0.35f);
  EXPECT_LT(t.heights.at(40, 40), 5.0f);
  EXPECT_GT(t.heights.at(40, 40), 2.0f);
  // Outside the ring, both features still blend.
  EXPECT_EQ(t.contributors[static_cast<std::size_t>(cellOf(40, 58, w))], 2);
}

TEST(DistanceSynthesis, DendriticRidgesDescendFromPeaks)
{
  const int w = 128;
  DistanceInputs in;
  in.width = w;
  in.height = w;
  in.features = { point(64, 64, w, 5.0f) };
  DistanceOptions o;
  o.heightScale = 1.0;
  o.meanWeight = 1.0;
  o.roughness = 0.75;
  o.seaLevelScale = 10.0; // c_s = 50: the peak reaches about 45 cells
  const DistanceTerrain bare = synthesiseByDistance(in, o);
  o.ridgeCount = 12;
  const DistanceTerrain t = synthesiseByDistance(in, o);
  ASSERT_EQ(t.ridges.size(), 12u);
  EXPECT_GT(t.ridgeNodes, 12u * 5u);
  EXPECT_EQ(t.generators, 1 + t.ridgeNodes);
  const float peak = t.heights.at(64, 64);
  for (const auto& ridge : t.ridges)
  {
    ASSERT_FALSE(ridge.empty());
    for (std::size_t i = 0; i + 1 < ridge.size(); ++i) // start -> towards the peak: rising
    {
      EXPECT_LE(t.heights.z[static_cast<std::size_t>(ridge[i])],
        t.heights.z[static_cast<std::size_t>(ridge[i + 1])]);
    }
    EXPECT_LE(t.heights.z[static_cast<std::size_t>(ridge.back())], peak);
    // The ridge stands above the bare cone: half the cost rise there.
    const auto start = static_cast<std::size_t>(ridge.front());
    EXPECT_NEAR(t.heights.z[start] - 45.0f, 0.5f * (bare.heights.z[start] - 45.0f), 1e-3f);
  }
  // The thesis read literally (f C_a) lifts the ridge above its own peak next to it.
  o.ridgeCost = RidgeCost::ScaledCost;
  const DistanceTerrain literal = synthesiseByDistance(in, o);
  EXPECT_GT(literal.heights.z[static_cast<std::size_t>(literal.ridges[0].back())], peak);
}

// ---------------------------------------------------------------------------
// Determinism

DistanceInputs manyFeatures(int w, int count)
{
  DistanceInputs in;
  in.width = w;
  in.height = w;
  for (int i = 0; i < count; ++i)
  {
    const int col = static_cast<int>((i * 37 + 11) % w);
    const int row = static_cast<int>((i * 61 + 5) % w);
    in.features.push_back(point(col, row, w, NAN, i % 2));
  }
  in.profiles = { linearProfile(40.0),
    MonotoneProfile::fromPoints({ 0.0, 10.0, 40.0 }, { 1.0, 0.8, 0.0 }) };
  return in;
}

TEST(DistanceSynthesis, DeterministicForASeedOnAnyThreadCount)
{
  const DistanceInputs in = manyFeatures(128, 40);
  DistanceOptions o;
  o.ridgeCount = 20;
  o.seed = 3;
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const DistanceTerrain one = synthesiseByDistance(in, o);
  omp_set_num_threads(2);
  const DistanceTerrain two = synthesiseByDistance(in, o);
  const DistanceTerrain again = synthesiseByDistance(in, o);
  omp_set_num_threads(threads);
  EXPECT_EQ(one.heights.z, two.heights.z);
  EXPECT_EQ(two.heights.z, again.heights.z);
  EXPECT_EQ(one.ridges, two.ridges);
  o.seed = 4;
  EXPECT_NE(synthesiseByDistance(in, o).heights.z, one.heights.z);
  // The binary heap settles the same costs.
  o.seed = 3;
  o.queue = DijkstraQueue::BinaryHeap;
  const DistanceTerrain heap = synthesiseByDistance(in, o);
  double worst = 0.0;
  for (std::size_t k = 0; k < heap.heights.size(); ++k)
  {
    worst = std::max(worst, std::fabs(static_cast<double>(heap.heights.z[k] - one.heights.z[k])));
  }
  EXPECT_LT(worst, 1e-3);
}

TEST(DistanceSynthesis, ApproximateOnlyPreview)
{
  const DistanceInputs in = manyFeatures(96, 20);
  DistanceOptions o;
  o.approximateOnly = true;
  const DistanceTerrain t = synthesiseByDistance(in, o);
  EXPECT_EQ(t.heights.z, t.approximate.z);
  EXPECT_EQ(t.featureVisits, 0u);
  o.approximateOnly = false;
  const DistanceTerrain full = synthesiseByDistance(in, o);
  EXPECT_EQ(full.approximate.z, t.approximate.z);
  // The blend never exceeds the maximum of the features (the approximate field
  // is that maximum where the searches agree); it is lower somewhere.
  EXPECT_NE(full.heights.z, t.heights.z);
}

// ---------------------------------------------------------------------------
// Queues: the bucket queue (the default) against the radix heap

// Ten points with fBm costs, a ring and a straight line of equal costs, a
// crater (the ring's inside, its own bowl profile) and 15 dendritic ridges:
// every rule a search's order could touch (generators' ties, regions, paths).
DistanceInputs queueScene()
{
  const int w = 96;
  DistanceInputs in = manyFeatures(w, 10);
  in.features.push_back(ring(48, 48, 14.0, w, 6.0f, 1));
  DistanceFeature line;
  for (int col = 10; col < 40; ++col)
  {
    line.nodes.push_back({ cellOf(col, 80, w), 4.0f, 0 });
  }
  in.features.push_back(line);
  in.profiles.push_back(MonotoneProfile::fromPoints({ 0.0, 4.0, 60.0 }, { 1.0, 0.3, 0.0 }));
  in.regions = enclosedRegions({ in.features[10] }, w, w, 2);
  in.regions.at(0).feature = 10;
  return in;
}

void expectSameTerrain(const DistanceTerrain& a, const DistanceTerrain& b)
{
  EXPECT_EQ(a.heights.z, b.heights.z);
  EXPECT_EQ(a.approximate.z, b.approximate.z);
  EXPECT_EQ(a.contributors, b.contributors);
  EXPECT_EQ(a.ridges, b.ridges);
  EXPECT_EQ(a.featureVisits, b.featureVisits);
}

TEST(DistanceSynthesis, BucketQueueGivesTheRadixHeapsBits)
{
  const DistanceInputs in = queueScene();
  ASSERT_EQ(in.regions.size(), 1u);
  DistanceOptions o;
  o.ridgeCount = 15;
  o.seed = 5;
  EXPECT_EQ(o.queue, DijkstraQueue::Bucket); // the default
  // Random weights; then the thesis's lattice with equal weights, where paths
  // of exactly equal cost meet everywhere and the queue's order picks the
  // predecessor (and so generators, w_s and the ridges' paths).
  for (const bool ties : { false, true })
  {
    SCOPED_TRACE(ties);
    o.roughness = ties ? 0.0 : 0.75;
    o.sqrt2Diagonals = !ties;
    o.queue = DijkstraQueue::Radix;
    const DistanceTerrain radix = synthesiseByDistance(in, o);
    o.queue = DijkstraQueue::Bucket;
    const DistanceTerrain buckets = synthesiseByDistance(in, o);
    EXPECT_EQ(buckets.radixSearches, 0u);
    EXPECT_EQ(buckets.ridges.size(), 15u);
    EXPECT_GT(buckets.featureVisits, 12u * 1000u);
    expectSameTerrain(radix, buckets);
    if (ties)
    {
      // The ties are real: std::priority_queue breaks them otherwise (by cell
      // index), and thousands of heights differ.
      o.queue = DijkstraQueue::BinaryHeap;
      EXPECT_NE(synthesiseByDistance(in, o).heights.z, radix.heights.z);
    }
  }
}

TEST(DistanceSynthesis, BucketQueueLeavesUnevenStepsToTheRadixHeap)
{
  const int w = 64;
  DistanceInputs in;
  in.width = w;
  in.height = w;
  in.features = { point(20, 20, w, 5.0f, 0), point(40, 44, w, 4.0f, 0), point(30, 50, w, 3.0f, 0) };
  // 90% of the fall in the first cell, 10% over the next 29: w_s spans 260x.
  in.profiles = { MonotoneProfile::fromPoints({ 0.0, 1.0, 30.0 }, { 1.0, 0.1, 0.0 }) };
  DistanceOptions o;
  o.seaLevelScale = 3.0; // c_s = 15
  // The greatest step over the least: 2,600 at r = 0.75 mu_w, 63,000 at 0.99
  // (the least weight drawn is 0.0116), both within the 65,536 buckets of the
  // ring; 3.3 million at 0.9999 mu_w: all four searches (the approximate one,
  // three features) fall back.
  for (const auto& [r, fallbacks] :
    { std::pair{ 0.75, 0u }, std::pair{ 0.99, 0u }, std::pair{ 0.9999, 4u } })
  {
    SCOPED_TRACE(r);
    o.roughness = r;
    o.queue = DijkstraQueue::Radix;
    const DistanceTerrain radix = synthesiseByDistance(in, o);
    EXPECT_EQ(radix.radixSearches, 0u); // counts stand-ins for the bucket queue only
    o.queue = DijkstraQueue::Bucket;
    const DistanceTerrain buckets = synthesiseByDistance(in, o);
    EXPECT_EQ(buckets.radixSearches, fallbacks);
    expectSameTerrain(radix, buckets);
    EXPECT_NEAR(buckets.heights.at(40, 44), 55.0f, 0.01f); // (c_s - 4) 5 m at the peak
    EXPECT_GT(buckets.featureVisits, 3u);
  }
}

// ---------------------------------------------------------------------------
// Bad input

TEST(DistanceSynthesis, BadInputMessages)
{
  DistanceInputs in;
  in.width = 32;
  in.height = 32;
  DistanceOptions o;
  expectThrowsWith([&] { synthesiseByDistance(in, o); }, "no generators");
  in.features = { point(5, 5, 32, 10.0f) };
  o.roughness = 1.0;
  expectThrowsWith([&] { synthesiseByDistance(in, o); }, "0 <= r < mu_w");
  o = DistanceOptions{};
  o.blendBias = 65.0;
  expectThrowsWith([&] { synthesiseByDistance(in, o); }, "blending bias b");
  o = DistanceOptions{};
  in.features = { point(5, 5, 32, 1.0e9f) };
  expectThrowsWith([&] { synthesiseByDistance(in, o); }, "swallow the smallest edge step");
  in.features = { point(5, 5, 32, INFINITY) };
  expectThrowsWith([&] { synthesiseByDistance(in, o); }, "infinite generator cost");
  in.features = { point(5, 5, 32, 0.0f) };
  expectThrowsWith([&] { synthesiseByDistance(in, o); }, "c_s = s * c_max is 0");
  in.features = { point(5, 5, 32, 10.0f, 2) };
  in.profiles = { linearProfile(10.0) };
  expectThrowsWith([&] { synthesiseByDistance(in, o); }, "asks for profile 2");
  in.features = { point(5, 5, 32, 10.0f, 0) };
  in.profiles = { MonotoneProfile::fromPoints({ 0.0, 10.0 }, { 0.0, 1.0 }) };
  expectThrowsWith(
    [&] { synthesiseByDistance(in, o); }, "Profile 0: A cost-scaling profile must fall");
  in.profiles.clear();
  in.features = { point(5, 5, 32, 10.0f) };
  in.nodeWeights.assign(31 * 32, 1.0f);
  expectThrowsWith([&] { synthesiseByDistance(in, o); }, "edge-weight image has 992 cells");
  in.nodeWeights.clear();
  // A scope that says stop ends the run at its first report (Core/Progress.h).
  std::vector<std::string> stages;
  o.progress = [&](double, const std::string& stage) { stages.push_back(stage); };
  {
    const CancellationScope stop([] { return true; });
    EXPECT_THROW(synthesiseByDistance(in, o), Cancelled);
  }
  EXPECT_EQ(stages, std::vector<std::string>{ "distance" }) << "stopped at the first report";
}

} // namespace
