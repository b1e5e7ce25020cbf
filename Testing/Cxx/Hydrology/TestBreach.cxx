// Tests of Kernels/Hydrology/Breach.cxx: the breaching flood behind pit removal
// (PitRemoval.h) and its survey of depressions, on small grids whose channels
// can be worked out by hand.
#include "Core/Heightfield.h"
#include "Hydrology/Breach.h"
#include "Hydrology/Flow.h"

#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace tsynth
{
namespace
{

// 9 x 5 cells of 1 m, rising 1 m a column to the east from 10 m, with a pit
// of `pitHeight` at (6, 2): the edge drains everything but the pit. Its
// lowest neighbours are column 5's at 15 m, and the lowest edge cell beside
// those is (4, 0) or (4, 4) at 14 m, so the shortest channel out is two cells
// long and cuts 15 m at most.
Heightfield rampWithPit(float pitHeight)
{
  Heightfield dem(9, 5);
  dem.cellX = dem.cellY = 1.0;
  for (int j = 0; j < dem.height; ++j)
  {
    for (int i = 0; i < dem.width; ++i)
    {
      dem.at(i, j) = 10.0f + static_cast<float>(i);
    }
  }
  dem.at(6, 2) = pitHeight;
  return dem;
}

std::size_t cellsChanged(const Heightfield& a, const Heightfield& b)
{
  std::size_t n = 0;
  for (std::size_t k = 0; k < a.size(); ++k)
  {
    n += a.z[k] != b.z[k] ? 1 : 0;
  }
  return n;
}

} // namespace

TEST(Breach, ThePitIsDrainedByAChannelCutToItsLevel)
{
  const Heightfield dem = rampWithPit(0.0f);
  ASSERT_EQ(countPits(dem), 1u);
  const Heightfield out = breachFlood(dem, nullptr);
  EXPECT_EQ(countPits(out), 0u);
  EXPECT_EQ(out.at(6, 2), 0.0f) << "breaching lowers the way out, never raises the pit";
  EXPECT_EQ(cellsChanged(dem, out), 2u) << "a neighbour in column 5 and the edge cell it drains to";
  for (std::size_t k = 0; k < dem.size(); ++k)
  {
    EXPECT_LE(out.z[k], dem.z[k]);
    if (out.z[k] != dem.z[k])
    {
      EXPECT_LT(out.z[k], 0.0f) << "a channel cell goes below the pit";
      EXPECT_GT(out.z[k], -1e-3f) << "by float steps, not metres";
    }
  }
}

TEST(Breach, TheSurveyNamesEachDepressionsLevelSizeAndChannel)
{
  const std::vector<DepressionChannel> one = surveyDepressions(rampWithPit(0.0f), nullptr);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].spill, 15.0f) << "entered from column 5";
  EXPECT_EQ(one[0].cells, 1u);
  EXPECT_NEAR(one[0].maxCut, 15.0, 1e-3) << "column 5's cell cut from 15 m to the pit's 0 m";
  EXPECT_EQ(one[0].maxLength, 2u);
  EXPECT_FALSE(one[0].lowersUserSink);
  // A ramp without the pit has none.
  EXPECT_TRUE(surveyDepressions(rampWithPit(16.0f), nullptr).empty());
}

TEST(Breach, TheHybridBreachesWithinItsLimitsAndFillsBeyondThem)
{
  const Heightfield dem = rampWithPit(0.0f);
  // Within both limits: the same channel as complete breaching.
  EXPECT_EQ(hybridFlood(dem, 20.0, 2, nullptr).z, breachFlood(dem, nullptr).z);
  // Deeper than allowed, or longer: the pit is filled to its spill level instead.
  for (const Heightfield& out :
    { hybridFlood(dem, 10.0, 2, nullptr), hybridFlood(dem, 20.0, 1, nullptr) })
  {
    EXPECT_EQ(cellsChanged(dem, out), 1u);
    EXPECT_GT(out.at(6, 2), 15.0f);
    EXPECT_LT(out.at(6, 2), 15.001f);
    EXPECT_EQ(countPits(out), 0u);
  }
}

TEST(Breach, AUserSinkIsKeptAndNeverCarvedThrough)
{
  const Heightfield dem = rampWithPit(0.0f);
  std::vector<std::uint8_t> sinks(dem.size(), 0);
  sinks[dem.index(6, 2)] = 1;
  EXPECT_EQ(breachFlood(dem, &sinks).z, dem.z) << "the pit drains into itself";
  EXPECT_TRUE(surveyDepressions(dem, &sinks).empty());
}

} // namespace tsynth
