// Tests of Kernels/Matching/PatchMatcher.cxx: the backends agree, auto picks OpenCL only on an
// accelerator, and the fallbacks to the dense search and to the CPU.
#include "Core/Error.h"
#include "Features/Ppa.h"
#include "Matching/OpenClMatcher.h"
#include "Matching/PatchMatcher.h"
#include "MatchingTestData.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <string>

using namespace tsynth;
using tsynth::test::matching::colorado;
using tsynth::test::matching::crop;

TEST(PatchMatcher, BackendsAgreeAndAutoPicksOpenClOnlyOnAGpu)
{
  const Heightfield ex = crop(colorado(), 60, 60, 400, 400);
  const FeatureExtraction f = extractFeatures(ex, FeatureType::Ridge, {});
  MatcherOptions o;
  o.patchSize = 64;
  o.backend = Backend::Auto;
  // Here OpenCL is PoCL, a CPU device: auto matches on the CPU backend.
  EXPECT_EQ(PatchMatcher({ &ex }, { &f.graph }, o).backend(),
    openClHasAccelerator() ? Backend::OpenCL : Backend::Cpu);
  o.backend = Backend::OpenCL;
  PatchMatcher automatic({ &ex }, { &f.graph }, o);
  EXPECT_EQ(automatic.backend(), Backend::OpenCL);
  o.backend = Backend::Cpu;
  PatchMatcher cpu({ &ex }, { &f.graph }, o);
  EXPECT_EQ(cpu.backend(), Backend::Cpu);
  const NoiseVariance noise(ex);
  const FeatureQuery q = makeFeatureQuery(cpu.pool().sites[3], ex, noise, nullptr, nullptr, 64);
  const auto a = automatic.matchFeature(q);
  const auto b = cpu.matchFeature(q);
  ASSERT_EQ(a.size(), 8u);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t r = 0; r < a.size(); ++r)
  {
    EXPECT_EQ(a[r].poolIndex, b[r].poolIndex);
    EXPECT_NEAR(a[r].cost, b[r].cost, 1e-4 * std::max(1.0f, b[r].cost));
  }
}

TEST(PatchMatcher, MissingFeatureTypeFallsBackToDenseWithAWarning)
{
  const Heightfield ex = crop(colorado(), 60, 60, 300, 300);
  const FeatureExtraction ridges = extractFeatures(ex, FeatureType::Ridge, {});
  MatcherOptions o;
  o.patchSize = 48;
  o.backend = Backend::Cpu;
  PatchMatcher matcher({ &ex }, { &ridges.graph }, o); // ridges only
  FeatureQuery valley;
  valley.type = -1;
  valley.kind = static_cast<int>(NodeKind::End);
  valley.arms = 1;
  DenseQuery window;
  window.heights.assign(48 * 48, 0.0f);
  window.known.assign(48 * 48, 0);
  for (int j = 0; j < 48; ++j)
  {
    for (int i = 0; i < 12; ++i)
    {
      window.heights[static_cast<std::size_t>(j * 48 + i)] = ex.at(100 + i, 120 + j);
      window.known[static_cast<std::size_t>(j * 48 + i)] = 1;
    }
  }
  const auto found = matcher.matchFeature(valley, &window);
  ASSERT_FALSE(found.empty());
  EXPECT_FALSE(found[0].feature);
  EXPECT_NEAR(found[0].centreX, 100 + 23.5, 1e-9); // the window cut from the exemplar
  EXPECT_NEAR(found[0].centreY, 120 + 23.5, 1e-9);
  ASSERT_FALSE(matcher.warnings().empty());
  EXPECT_NE(matcher.warnings().back().find("non-feature"), std::string::npos);
}

TEST(PatchMatcher, NoOpenClPlatformFallsBackToTheCpu)
{
  // A real failure: the ICD loader is pointed at an empty vendor folder.
  setenv("OCL_ICD_VENDORS", "/nonexistent-tsynth-test", 1);
  const Heightfield ex = crop(colorado(), 0, 0, 200, 200);
  const FeatureExtraction f = extractFeatures(ex, FeatureType::Ridge, {});
  MatcherOptions o;
  o.patchSize = 48;
  // Auto has no accelerator to use and takes the CPU, as it would on PoCL.
  EXPECT_FALSE(openClHasAccelerator());
  PatchMatcher matcher({ &ex }, { &f.graph }, o);
  EXPECT_EQ(matcher.backend(), Backend::Cpu);
  // Asked for OpenCL, it says why there is none.
  o.backend = Backend::OpenCL;
  try
  {
    PatchMatcher refused({ &ex }, { &f.graph }, o);
    ADD_FAILURE() << "OpenCL without a platform was accepted";
  }
  catch (const Error& e)
  {
    EXPECT_NE(std::string(e.what()).find("No OpenCL platform"), std::string::npos) << e.what();
  }
}
