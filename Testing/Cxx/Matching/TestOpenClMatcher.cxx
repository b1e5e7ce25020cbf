// Tests of Kernels/Matching/OpenClMatcher.cxx: OpenCL (PoCL here) against the CPU reference, the
// backend names and a kernel build error's report.
#include "Core/Error.h"
#include "Features/Ppa.h"
#include "Matching/CandidatePool.h"
#include "Matching/DenseSearch.h"
#include "Matching/FeatureCost.h"
#include "Matching/LandformTerm.h"
#include "Matching/OpenClMatcher.h"
#include "MatchingTestData.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

using namespace tsynth;
using tsynth::test::matching::colorado;
using tsynth::test::matching::crop;
using tsynth::test::matching::handPoolWithLandform;
using tsynth::test::matching::handQuery;

TEST(OpenCL, FeatureScoresEqualTheCpuReference)
{
  std::shared_ptr<OpenClDevice> device;
  ASSERT_NO_THROW(device = OpenClDevice::create()) << "this machine has PoCL: OpenCL must work";
  const Heightfield ex = crop(colorado(), 40, 40, 500, 500);
  const FeatureExtraction f = extractFeatures(ex, FeatureType::Ridge, {});
  PoolOptions o;
  o.patchSize = 64;
  const CandidatePool pool = buildCandidatePool({ &ex }, { &f.graph }, o);
  ASSERT_GT(pool.size(), 1000u);
  OpenClFeatureScorer scorer(device, pool);
  const NoiseVariance noise(ex);
  std::vector<std::uint8_t> known(ex.size(), 0);
  for (std::size_t k = 0; k < known.size(); k += 3)
  {
    known[k] = 1;
  }
  for (std::size_t s = 0; s < pool.sites.size(); s += pool.sites.size() / 7)
  {
    for (bool offset : { false, true })
    {
      MatchWeights w;
      w.verticalOffset = offset;
      const FeatureQuery q = makeFeatureQuery(pool.sites[s], ex, noise, &ex, &known, 64);
      const auto cpu = scoreFeatureCandidates(pool, q, w);
      const auto gpu = scorer.score(q, w);
      ASSERT_EQ(cpu.size(), gpu.size());
      for (std::size_t c = 0; c < cpu.size(); ++c)
      {
        ASSERT_NEAR(gpu[c], cpu[c], 1e-4 * std::max(1.0f, std::abs(cpu[c]))) << "candidate " << c;
      }
      const auto a = topK(cpu, 8);
      const auto b = topK(gpu, 8);
      for (std::size_t r = 0; r < a.size(); ++r)
      {
        EXPECT_EQ(a[r].index, b[r].index) << "rank " << r;
      }
    }
  }
}

TEST(OpenCL, FeatureScoresWithLandformQueriesEqualTheCpuReference)
{
  std::shared_ptr<OpenClDevice> device;
  ASSERT_NO_THROW(device = OpenClDevice::create()) << "this machine has PoCL: OpenCL must work";
  const Heightfield ex = crop(colorado(), 100, 100, 300, 300);
  const FeatureExtraction f = extractFeatures(ex, FeatureType::Ridge, {});
  PoolOptions o;
  o.patchSize = 48;
  const CandidatePool pool = buildCandidatePool({ &ex }, { &f.graph }, o);
  ASSERT_GT(pool.size(), 500u);
  OpenClFeatureScorer scorer(device, pool);
  // The target: another part of the DEM, low-passed, with a confidence that
  // falls from 1 in the west to 0 in the east, and the north half known.
  const Heightfield target = crop(colorado(), 320, 300, 300, 300);
  const Heightfield lowTarget = landformImage(target, o.patchSize);
  std::vector<float> confidence(target.size());
  std::vector<std::uint8_t> known(target.size());
  for (int j = 0; j < target.height; ++j)
  {
    for (int i = 0; i < target.width; ++i)
    {
      confidence[target.index(i, j)] = 1.0f - static_cast<float>(i) / (target.width - 1);
      known[target.index(i, j)] = j >= target.height / 2 ? 1 : 0;
    }
  }
  const NoiseVariance noise(target);
  int withLandform = 0;
  int queries = 0;
  for (std::size_t s = 0; s < pool.sites.size(); s += pool.sites.size() / 9)
  {
    ++queries;
    const FeatureQuery q = makeFeatureQuery(
      pool.sites[s], target, noise, &target, &known, o.patchSize, &lowTarget, &confidence);
    withLandform += std::any_of(
      q.landformWeight.begin(), q.landformWeight.end(), [](float w) { return w > 0.0f; });
    const auto cpu = scoreFeatureCandidates(pool, q, {});
    const auto gpu = scorer.score(q, {});
    ASSERT_EQ(cpu.size(), gpu.size());
    for (std::size_t c = 0; c < cpu.size(); ++c)
    {
      ASSERT_NEAR(gpu[c], cpu[c], 1e-4 * std::max(1.0f, std::abs(cpu[c]))) << "candidate " << c;
    }
    const auto a = topK(cpu, 8);
    const auto b = topK(gpu, 8);
    for (std::size_t r = 0; r < a.size(); ++r)
    {
      EXPECT_EQ(a[r].index, b[r].index) << "rank " << r;
    }
  }
  EXPECT_GE(2 * withLandform, queries) << "half the queries at least carry landform samples";
  // The hand-made candidate too, both lanes of landform samples.
  const CandidatePool hand = handPoolWithLandform();
  FeatureQuery q = handQuery();
  q.landform[20] = 10.0f;
  q.landformWeight[20] = 1.0f;
  OpenClFeatureScorer handScorer(device, hand);
  EXPECT_NEAR(handScorer.score(q, {})[0], scoreFeatureCandidates(hand, q, {})[0], 1e-5);
}

TEST(OpenCL, DenseCoarseCostsEqualTheCpuReference)
{
  std::shared_ptr<OpenClDevice> device;
  ASSERT_NO_THROW(device = OpenClDevice::create());
  const Heightfield ex = crop(colorado(), 0, 0, 256, 256);
  const Heightfield source = crop(colorado(), 300, 300, 200, 200);
  DenseOptions o;
  o.patchSize = 64;
  const DenseMatcher matcher({ &ex }, o);
  OpenClDenseScorer scorer(device, matcher);
  DenseQuery q;
  q.heights.resize(64 * 64);
  q.known.resize(64 * 64);
  for (int j = 0; j < 64; ++j)
  {
    for (int i = 0; i < 64; ++i)
    {
      q.heights[static_cast<std::size_t>(j * 64 + i)] = source.at(20 + i, 30 + j);
      q.known[static_cast<std::size_t>(j * 64 + i)] = (i < 20 || j < 12) ? 1 : 0;
    }
  }
  const CoarseQuery cq = matcher.coarseQuery(q);
  const auto cpu = matcher.coarseCosts(cq);
  const auto gpu = scorer.coarseCosts(cq);
  ASSERT_EQ(cpu.size(), gpu.size());
  for (std::size_t v = 0; v < cpu.size(); ++v)
  {
    ASSERT_EQ(cpu[v].size(), gpu[v].size());
    for (std::size_t k = 0; k < cpu[v].size(); ++k)
    {
      if (std::isinf(cpu[v][k]))
      {
        ASSERT_TRUE(std::isinf(gpu[v][k]));
        continue;
      }
      ASSERT_NEAR(gpu[v][k], cpu[v][k], 1e-4 * std::max(1.0f, cpu[v][k]));
    }
  }
  const auto a = matcher.refine(q, cpu, 8);
  const auto b = matcher.refine(q, gpu, 8);
  // The pruned pass agrees too, whichever backend sums.
  const auto c = matcher.refine(q,
    matcher.prunedCoarseCosts(cq,
      [&](const CoarseTerms& t, CoarseImage i, const std::vector<std::vector<std::uint8_t>>* r)
      { return scorer.coarseSsd(t, i, r); }),
    8);
  ASSERT_EQ(a.size(), c.size());
  for (std::size_t r = 0; r < a.size(); ++r)
  {
    EXPECT_EQ(a[r].x, c[r].x);
    EXPECT_EQ(a[r].y, c[r].y);
    EXPECT_EQ(a[r].cost, c[r].cost);
  }
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t r = 0; r < a.size(); ++r)
  {
    EXPECT_EQ(a[r].variant, b[r].variant);
    EXPECT_EQ(a[r].x, b[r].x);
    EXPECT_EQ(a[r].y, b[r].y);
    EXPECT_EQ(a[r].cost, b[r].cost);
  }
}

TEST(OpenCL, BackendNames)
{
  EXPECT_EQ(parseBackend("auto"), Backend::Auto);
  EXPECT_EQ(parseBackend("opencl"), Backend::OpenCL);
  EXPECT_EQ(parseBackend("cpu"), Backend::Cpu);
  EXPECT_THROW(parseBackend("cuda"), Error);
}

TEST(OpenCL, ABuildErrorIsReportedWithTheCompilerLog)
{
  try
  {
    OpenClDevice::create("__kernel void broken(__global float* x) { x[0] = undefined_name; }");
    FAIL() << "a broken kernel built";
  }
  catch (const Error& e)
  {
    const std::string message = e.what();
    EXPECT_NE(message.find("did not build"), std::string::npos) << message;
    EXPECT_NE(message.find("undefined_name"), std::string::npos) << message; // the log names it
  }
}
