// Tests of Kernels/Synthesis/SynthesisRequest.cxx.
// Synthesis/SynthesisRequest: the one request both front ends fill, the set-up
// inputs derived from it, and the options table they read.
#include "Core/Error.h"
#include "Core/Memory.h"
#include "Synthesis/ExemplarCache.h"
#include "Synthesis/SynthesisRequest.h"

#include <gtest/gtest.h>

#include <string>

namespace tsynth
{
namespace
{

SetupInputs inputsOf(const SynthesisRequest& r)
{
  return setupInputs(r, {}, {}, ColourImage{}, SetupOptionNames{});
}

std::string defaultWord(const char* property)
{
  const OptionRow& row = synthesisOption(property);
  return row.choices.wordOf(static_cast<int>(row.defaultValue), property);
}

} // namespace

TEST(SynthesisRequest, TheSetUpTakesEachOptionFromTheRequestOnce)
{
  SynthesisRequest r;
  r.options.patchSize = 48;
  r.options.seed = 7;
  r.options.backend = Backend::Cpu;
  r.grid.width = 300;
  r.grid.cellX = 25.0;
  r.landformRelief = 2.0;
  r.memoryBudgetGB = 3.0;
  r.useExemplarCache = false;
  r.cacheDirectory = "/somewhere";
  const SetupInputs in = inputsOf(r);
  EXPECT_EQ(in.patchSize, 48);
  EXPECT_EQ(in.seed, 7u);
  EXPECT_EQ(in.matcherBackend, Backend::Cpu);
  EXPECT_EQ(in.grid.width, 300);
  EXPECT_EQ(in.grid.cellX, 25.0);
  EXPECT_EQ(in.landformRelief, 2.0);
  EXPECT_DOUBLE_EQ(in.memoryBudget, 3.0 * kBytesPerGB);
  EXPECT_EQ(in.cacheDirectory, ""); // the cache is off, wherever it would be

  r.useExemplarCache = true;
  EXPECT_EQ(inputsOf(r).cacheDirectory, "/somewhere");
  r.cacheDirectory.clear();
  EXPECT_EQ(inputsOf(r).cacheDirectory, defaultExemplarCacheDirectory());
}

TEST(SynthesisRequest, TheTableHoldsADefaultRequestsValues)
{
  EXPECT_EQ(synthesisOption("PatchSize").defaultValue, kAutomaticPatch);
  EXPECT_EQ(synthesisOption("PatchSize").min, kAutomaticPatch);
  EXPECT_EQ(synthesisOption("PatchSize").max, kMaxSynthesisPatch);
  EXPECT_EQ(defaultWord("Backend"), "auto");
  EXPECT_EQ(defaultWord("MergeMode"), "new");
  EXPECT_EQ(defaultWord("FillOrder"), "best-first");
  EXPECT_EQ(defaultWord("Drainage"), "off");
  EXPECT_EQ(synthesisOption("VerticalOffset").defaultValue, 1.0);
  EXPECT_EQ(synthesisOption("Repetition").defaultValue, 0.5);
  EXPECT_EQ(synthesisOption("LandformRelief").defaultValue, 1.0);
  EXPECT_EQ(synthesisOption("LandformRelief").min, kMinLandformRelief);
  EXPECT_EQ(synthesisOption("UseExemplarCache").defaultValue, 1.0);
  EXPECT_EQ(synthesisOption("TileSize").defaultValue, 0.0);
  EXPECT_EQ(synthesisOption("MergeMode").flag, "--merge");
  EXPECT_THROW(synthesisOption("Speed"), Error);
}

TEST(SynthesisRequest, EveryChoiceHasALabelPerWordAndItsRangeIsItsWords)
{
  int choices = 0;
  for (const OptionRow& row : synthesisOptionRows())
  {
    SCOPED_TRACE(row.property);
    EXPECT_FALSE(row.flag.empty());
    EXPECT_LE(row.min, row.defaultValue);
    EXPECT_GE(row.max, row.defaultValue);
    if (row.type != OptionType::Choice)
    {
      EXPECT_EQ(row.choices.count, 0u);
      continue;
    }
    ++choices;
    EXPECT_EQ(row.labels.size(), row.choices.count);
    EXPECT_EQ(row.min, 0.0);
    EXPECT_EQ(row.max, static_cast<double>(row.choices.count) - 1.0);
  }
  EXPECT_EQ(choices, 4); // backend, merge, fill order, drainage
}

} // namespace tsynth

namespace tsynth
{

TEST(SynthesisRequest, AnAutomaticPatchIsChosenForTheSketchOnceItIsRead)
{
  Heightfield dem(64, 64, 100.0f);
  const SketchInput demTarget = dem;
  const SketchInput drawing = ColourImage{};
  const SketchInput lines = PolylineSketch{};
  EXPECT_EQ(patchSizeFor(kAutomaticPatch, demTarget), kDefaultDemTargetPatch);
  EXPECT_EQ(patchSizeFor(kAutomaticPatch, drawing), kDefaultSynthesisPatch);
  EXPECT_EQ(patchSizeFor(kAutomaticPatch, lines), kDefaultSynthesisPatch);
  EXPECT_EQ(patchSizeFor(48, demTarget), 48) << "a patch asked for is kept";

  SynthesisRequest r;
  ASSERT_EQ(r.options.patchSize, kAutomaticPatch);
  resolvePatchSize(r, demTarget, SetupOptionNames{});
  EXPECT_EQ(r.options.patchSize, kDefaultDemTargetPatch);
  EXPECT_EQ(inputsOf(r).patchSize, kDefaultDemTargetPatch);
  // The tile size is checked against the patch chosen: two of the DEM's
  // 32-cell patches fit 64 cells, two of 80 would not.
  SynthesisRequest tiled;
  tiled.options.tileSize = 64;
  resolvePatchSize(tiled, demTarget, SetupOptionNames{});
  tiled.options.patchSize = kAutomaticPatch;
  EXPECT_THROW(resolvePatchSize(tiled, drawing, SetupOptionNames{}), Error);
  // A patch the kernels cannot use is refused by the option's name.
  SynthesisRequest odd;
  odd.options.patchSize = 30;
  SetupOptionNames names;
  names.patch = "--patch";
  try
  {
    resolvePatchSize(odd, drawing, names);
    FAIL() << "a patch of 30 was taken";
  }
  catch (const Error& e)
  {
    EXPECT_NE(std::string(e.what()).find("--patch"), std::string::npos) << e.what();
  }
}

} // namespace tsynth
