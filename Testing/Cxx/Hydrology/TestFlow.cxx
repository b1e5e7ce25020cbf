// Tests of Kernels/Hydrology/Flow.cxx.
// Depression filling, D8 directions and flow accumulation on surfaces with
// known answers and on every real DEM of the project.
#include "Core/Error.h"
#include "Core/HeightfieldIO.h"
#include "Hydrology/Flow.h"
#include "TestData.h"

#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <numeric>
#include <random>

using namespace tsynth;

namespace
{

namespace fs = std::filesystem;

float up(float z, int steps = 1)
{
  for (int s = 0; s < steps; ++s)
  {
    z = std::nextafter(z, std::numeric_limits<float>::infinity());
  }
  return z;
}

Heightfield grid(int w, int h, double cell, const std::function<double(int, int)>& f)
{
  Heightfield hf(w, h);
  hf.cellX = hf.cellY = cell;
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      hf.at(i, j) = static_cast<float>(f(i, j));
    }
  }
  return hf;
}

bool sameBits(const Heightfield& a, const Heightfield& b)
{
  if (a.width != b.width || a.height != b.height || a.valid != b.valid)
  {
    return false;
  }
  for (std::size_t k = 0; k < a.size(); ++k)
  {
    const bool bothNan = std::isnan(a.z[k]) && std::isnan(b.z[k]);
    if (!bothNan && a.z[k] != b.z[k])
    {
      return false;
    }
  }
  return true;
}

// The defining equation of the epsilon fill, checked cell by cell: seeds and
// invalid cells keep their value; every other cell equals max(own height,
// nextafter(lowest filled neighbour)). With strictly increasing steps this has
// one solution, so passing it means the fill is exact, not merely pit-free.
// Returns the number of cells that break it.
std::size_t epsilonFillErrors(const Heightfield& dem,
  const Heightfield& filled,
  const std::vector<std::uint8_t>* sinks = nullptr)
{
  std::size_t errors = 0;
  for (int j = 0; j < dem.height; ++j)
  {
    for (int i = 0; i < dem.width; ++i)
    {
      const std::size_t k = dem.index(i, j);
      if (!isUsableCell(dem, k))
      {
        errors += isUsableCell(filled, k) ? 1 : 0;
        continue;
      }
      if (isSeedCell(dem, sinks, i, j))
      {
        errors += filled.z[k] == dem.z[k] ? 0 : 1;
        continue;
      }
      float lowest = std::numeric_limits<float>::infinity();
      for (int c = 0; c < kD8Directions; ++c)
      {
        lowest = std::min(lowest, filled.at(i + kD8Dx[c], j + kD8Dy[c]));
      }
      errors += filled.z[k] == std::max(dem.z[k], up(lowest)) ? 0 : 1;
    }
  }
  return errors;
}

const Heightfield& colorado()
{
  static const Heightfield hf = readHeightfield(test::bundledData() / "dems" / "colorado.png");
  return hf;
}

// A square basin: a plain at 10-10.3 m around a wall at 20 m enclosing a bowl (2..14 m)
// on rows and columns 5..35, with one gap in the south wall at (20, 4), 15 m,
// and an island cell at 17 m. Filled, the basin spills through the gap.
constexpr int kBasinSize = 41;
constexpr int kBasinLow = 5;
constexpr int kBasinHigh = 35;
constexpr int kGapI = 20;
constexpr int kGapJ = 4;
constexpr float kGapHeight = 15.0f;
constexpr int kIslandI = 28;
constexpr int kIslandJ = 30;
constexpr float kIslandHeight = 17.0f;

Heightfield basin()
{
  return grid(kBasinSize,
    kBasinSize,
    30.0,
    [](int i, int j)
    {
      const bool inside = i >= kBasinLow && i <= kBasinHigh && j >= kBasinLow && j <= kBasinHigh;
      const bool wall = !inside && i >= kBasinLow - 1 && i <= kBasinHigh + 1 &&
        j >= kBasinLow - 1 && j <= kBasinHigh + 1;
      if (i == kGapI && j == kGapJ)
      {
        return static_cast<double>(kGapHeight);
      }
      if (i == kIslandI && j == kIslandJ)
      {
        return static_cast<double>(kIslandHeight);
      }
      if (wall)
      {
        return 20.0;
      }
      if (!inside) // a plain falling 0.1 m per cell towards the border
      {
        return 10.0 + 0.1 * std::min({ i, j, kBasinSize - 1 - i, kBasinSize - 1 - j });
      }
      const double r = std::hypot(i - 20.0, j - 20.0) / 15.0;
      return 2.0 + 6.0 * r * r; // 14 m at the corners: all below the gap
    });
}

} // namespace

TEST(Hydrology, ConeDrainsToTheBorderUnchanged)
{
  const Heightfield cone =
    grid(61, 61, 30.0, [](int i, int j) { return 900.0 - 12.5 * std::hypot(i - 30.0, j - 30.0); });
  const Heightfield filled = fillDepressions(cone);
  EXPECT_TRUE(sameBits(filled, cone));
  EXPECT_TRUE(drainsEverywhere(cone, nullptr));
  EXPECT_EQ(countPits(cone), 0u);
  const auto dir = flowDirections(cone);
  EXPECT_EQ(dir[cone.index(40, 30)], 0); // east of the apex: flows east
  EXPECT_EQ(dir[cone.index(30, 45)], 2); // north: north
  EXPECT_EQ(dir[cone.index(20, 20)], 5); // south-west: south-west
}

TEST(Hydrology, BasinFillsExactlyToItsSpillHeightPlusOneStepPerCell)
{
  const Heightfield dem = basin();
  EXPECT_EQ(countPits(dem), 1u); // the bowl's bottom
  std::size_t bad = 0;
  EXPECT_FALSE(drainsEverywhere(dem, nullptr, &bad));
  EXPECT_EQ(bad, dem.index(20, 20)); // flanks have a lower neighbour; only the bottom has none

  const Heightfield filled = fillDepressions(dem);
  for (int j = 0; j < dem.height; ++j)
  {
    for (int i = 0; i < dem.width; ++i)
    {
      const bool inside = i >= kBasinLow && i <= kBasinHigh && j >= kBasinLow && j <= kBasinHigh;
      if (!inside || (i == kIslandI && j == kIslandJ))
      {
        ASSERT_EQ(filled.at(i, j), dem.at(i, j)) << i << "," << j;
        continue;
      }
      // Water leaves through the gap: the filled level rises one float step
      // per 8-connected step (Chebyshev distance in a square) from the gap.
      const int steps = std::max(std::abs(i - kGapI), std::abs(j - kGapJ));
      ASSERT_EQ(filled.at(i, j), up(kGapHeight, steps)) << i << "," << j;
    }
  }
  EXPECT_TRUE(drainsEverywhere(filled, nullptr));
  EXPECT_EQ(countPits(filled), 0u);
  EXPECT_EQ(epsilonFillErrors(dem, filled), 0u);

  // Below sea level (float steps upwards go towards zero): the same shape.
  Heightfield low = dem;
  for (float& z : low.z)
  {
    z -= 40.0f;
  }
  const Heightfield lowFilled = fillDepressions(low);
  EXPECT_EQ(epsilonFillErrors(low, lowFilled), 0u);
  EXPECT_EQ(lowFilled.at(kGapI, kBasinHigh), up(kGapHeight - 40.0f, kBasinHigh - kGapJ));
}

TEST(Hydrology, FillIsIdempotentAndDeterministic)
{
  for (const Heightfield& dem : { basin(), colorado() })
  {
    const Heightfield once = fillDepressions(dem);
    EXPECT_TRUE(sameBits(fillDepressions(once), once));
    EXPECT_TRUE(sameBits(fillDepressions(dem), once));
  }
}

TEST(Hydrology, EveryRealDemDrainsAfterFillAndNotBefore)
{
  const auto dems = test::realDems();
  ASSERT_GE(dems.size(), 12u) << "expected the bundled and shared DEMs";
  for (const std::string& path : dems)
  {
    SCOPED_TRACE(path);
    const Heightfield dem = readHeightfield(path);
    std::size_t bad = 0;
    ASSERT_FALSE(drainsEverywhere(dem, nullptr, &bad)) << "a raw DEM with no depression?";
    // The cell reported has no lower neighbour.
    const int bi = static_cast<int>(bad % static_cast<std::size_t>(dem.width));
    const int bj = static_cast<int>(bad / static_cast<std::size_t>(dem.width));
    for (int c = 0; c < kD8Directions; ++c)
    {
      EXPECT_GE(dem.at(bi + kD8Dx[c], bj + kD8Dy[c]), dem.z[bad]);
    }

    const Heightfield filled = fillDepressions(dem);
    EXPECT_TRUE(drainsEverywhere(filled, nullptr, &bad)) << "cell " << bad;
    EXPECT_EQ(countPits(filled), 0u);
    EXPECT_EQ(epsilonFillErrors(dem, filled), 0u);
    // D8 on the filled DEM: every valid non-seed cell has somewhere to go.
    const auto dir = flowDirections(filled);
    std::size_t stuck = 0;
    for (int j = 1; j + 1 < dem.height; ++j)
    {
      for (int i = 1; i + 1 < dem.width; ++i)
      {
        stuck += (!isSeedCell(dem, nullptr, i, j) && dir[dem.index(i, j)] == kNoFlow) ? 1 : 0;
      }
    }
    EXPECT_EQ(stuck, 0u);
  }
}

TEST(Hydrology, ManyFlatsAndHolesFillExactly)
{
  // Integer heights 0..4: flats and ties everywhere, plus 10% nodata.
  std::mt19937 rng(11);
  Heightfield dem(97, 83);
  dem.valid.assign(dem.size(), 1);
  for (std::size_t k = 0; k < dem.size(); ++k)
  {
    dem.z[k] = static_cast<float>(rng() % 5);
    if (rng() % 10 == 0)
    {
      dem.valid[k] = 0;
      dem.z[k] = std::numeric_limits<float>::quiet_NaN();
    }
  }
  const Heightfield filled = fillDepressions(dem);
  EXPECT_EQ(epsilonFillErrors(dem, filled), 0u);
  EXPECT_TRUE(drainsEverywhere(filled, nullptr));
  EXPECT_EQ(filled.valid, dem.valid);
  for (std::size_t k = 0; k < dem.size(); ++k)
  {
    if (!dem.isValid(k))
    {
      EXPECT_TRUE(std::isnan(filled.z[k]));
    }
  }
}

TEST(Hydrology, NodataCellsAreOutletsAndStayInvalid)
{
  // A bowl whose bottom is nodata: everything drains into the hole, nothing is raised.
  Heightfield bowl = grid(
    31, 31, 30.0, [](int i, int j) { return 100.0 + (i - 15) * (i - 15) + (j - 15) * (j - 15); });
  bowl.valid.assign(bowl.size(), 1);
  bowl.valid[bowl.index(15, 15)] = 0;
  bowl.at(15, 15) = std::numeric_limits<float>::quiet_NaN();
  const Heightfield filled = fillDepressions(bowl);
  EXPECT_TRUE(sameBits(filled, bowl));
  EXPECT_FALSE(filled.isValid(15, 15));
  EXPECT_TRUE(drainsEverywhere(bowl, nullptr));
  EXPECT_EQ(countPits(bowl), 0u);

  const auto dir = flowDirections(bowl);
  EXPECT_EQ(dir[bowl.index(15, 15)], kNoFlow);
  EXPECT_EQ(dir[bowl.index(14, 15)], kNoFlow); // next to the hole: an outlet
  EXPECT_EQ(dir[bowl.index(13, 15)], 0);       // flows east towards the hole
  const auto acc = flowAccumulation(dir, bowl.width, bowl.height, &bowl.valid);
  EXPECT_EQ(acc[bowl.index(15, 15)], 0u);
  std::uint64_t atOutlets = 0;
  for (std::size_t k = 0; k < bowl.size(); ++k)
  {
    atOutlets += (bowl.isValid(k) && dir[k] == kNoFlow) ? acc[k] : 0;
  }
  EXPECT_EQ(atOutlets, bowl.validCount());

  // NaN heights without a mask are holes too.
  Heightfield nanBowl = bowl;
  nanBowl.valid.clear();
  EXPECT_TRUE(sameBits(fillDepressions(nanBowl), nanBowl));

  // A hole on the bowl's side: the bowl fills to the lowest rim of the hole.
  Heightfield side = bowl;
  side.valid[side.index(15, 15)] = 1;
  side.at(15, 15) = 100.0f;
  side.valid[side.index(20, 15)] = 0; // rim neighbours of (20, 15) are seeds
  side.at(20, 15) = std::numeric_limits<float>::quiet_NaN();
  const Heightfield sideFilled = fillDepressions(side);
  EXPECT_EQ(epsilonFillErrors(side, sideFilled), 0u);
  EXPECT_EQ(sideFilled.at(19, 15), 116.0f); // a seed beside the hole keeps its height
  EXPECT_EQ(sideFilled.at(15, 15), up(116.0f, 4));
}

TEST(Hydrology, SinksAreKeptAsLakes)
{
  const Heightfield dem = basin();
  std::vector<std::uint8_t> sinks(dem.size(), 0);
  const std::size_t bottom = dem.index(20, 20);
  sinks[bottom] = 1;
  const Heightfield filled = fillDepressions(dem, &sinks);
  EXPECT_EQ(filled.z[bottom], dem.z[bottom]);
  EXPECT_TRUE(sameBits(filled, dem)); // every bowl cell drains to the lake
  EXPECT_TRUE(drainsEverywhere(dem, &sinks));
  EXPECT_FALSE(drainsEverywhere(dem, nullptr));
  EXPECT_EQ(epsilonFillErrors(dem, filled, &sinks), 0u);

  const std::vector<std::uint8_t> wrong(5, 0);
  EXPECT_THROW(fillDepressions(dem, &wrong), Error);
  EXPECT_THROW(drainsEverywhere(dem, &wrong), Error);
}

TEST(Hydrology, OracleAcceptsFlatsThatReachALowerCell)
{
  // A flat shelf at 50 m draining over its east end; a closed flat is refused.
  Heightfield dem = grid(12, 5, 30.0, [](int, int) { return 80.0; });
  for (int i = 1; i <= 8; ++i)
  {
    dem.at(i, 2) = 50.0f;
  }
  dem.at(9, 2) = 40.0f;
  dem.at(10, 2) = 30.0f;
  dem.at(11, 2) = 20.0f; // the outlet on the east border
  EXPECT_TRUE(drainsEverywhere(dem, nullptr));
  EXPECT_EQ(countPits(dem), 0u);
  dem.at(9, 2) = 60.0f;
  dem.at(10, 2) = 60.0f;
  std::size_t bad = 0;
  EXPECT_FALSE(drainsEverywhere(dem, nullptr, &bad));
  EXPECT_EQ(bad, dem.index(1, 2)); // the border seeds beside it are higher
  const auto dir = flowDirections(dem);
  EXPECT_EQ(dir[dem.index(3, 2)], kNoFlow); // a flat cell
}

TEST(Hydrology, D8OnTiltedPlanesPointsDownhill)
{
  struct Case
  {
    double cellX, cellY, gx, gy; // z = gx * x + gy * y, x and y in metres
    int expected;
  };
  const Case cases[] = {
    { 30, 30, -1.0, 0.0, 0 },  // falls east
    { 30, 30, -1.0, -1.0, 1 }, // north-east: drop 60 m over 42.4 m beats 30 over 30
    { 30, 30, 0.0, 1.0, 6 },   // rises north: flows south
    { 30, 30, 0.3, -1.0, 2 },  // mostly north
    { 30, 30, 1.0, 1.0, 5 },   // south-west
    { 10, 30, -1.0, -1.0, 1 }, // E 1.0, N 1.0, NE 40 / 31.6 = 1.26
    { 10, 30, -1.0, -0.2, 0 }, // E 1.0, NE 16 / 31.6 = 0.51, N 0.2
    { 10, 30, 0.0, -1.0, 2 },  // N 1.0, NE and NW 30 / 31.6 = 0.95
  };
  for (const Case& c : cases)
  {
    Heightfield hf = grid(
      9, 9, 1.0, [&](int i, int j) { return 1000.0 + c.gx * i * c.cellX + c.gy * j * c.cellY; });
    hf.cellX = c.cellX;
    hf.cellY = c.cellY;
    const auto dir = flowDirections(hf);
    for (int j = 1; j < 8; ++j)
    {
      for (int i = 1; i < 8; ++i)
      {
        ASSERT_EQ(dir[hf.index(i, j)], c.expected)
          << c.gx << " " << c.gy << " at " << i << "," << j;
      }
    }
  }
}

TEST(Hydrology, D8TiesGoToTheLowestCodeAndPitsHaveNoFlow)
{
  Heightfield hf = grid(3, 3, 30.0, [](int, int) { return 11.0; });
  hf.at(1, 1) = 10.0f;
  EXPECT_EQ(flowDirections(hf)[hf.index(1, 1)], kNoFlow); // a pit
  hf.at(2, 1) = 9.0f;                                     // east
  hf.at(1, 2) = 9.0f;                                     // north, same drop
  EXPECT_EQ(flowDirections(hf)[hf.index(1, 1)], 0);
  hf.at(2, 1) = 11.0f;
  EXPECT_EQ(flowDirections(hf)[hf.index(1, 1)], 2);
  hf.at(1, 1) = 9.0f;
  EXPECT_EQ(flowDirections(hf)[hf.index(1, 1)], 2); // a flat draining to the border cell (1, 2)
  hf.valid.assign(hf.size(), 1);
  hf.valid[hf.index(1, 1)] = 0;
  EXPECT_EQ(flowDirections(hf)[hf.index(1, 1)], kNoFlow); // invalid
}

TEST(Hydrology, FlatsAreRoutedToTheirExitByTheShortestWayAndClosedFlatsHaveNoFlow)
{
  // A flat terrace at 10 m, columns 1..6 of row 2, whose only exit is the cell
  // (7, 2) at 10 m that flows east to the border at 9 m; the rest is 12 m.
  Heightfield hf = grid(9, 5, 30.0, [](int i, int j) { return j == 2 && i >= 1 ? 10.0 : 12.0; });
  hf.at(8, 2) = 9.0f;
  std::vector<std::int8_t> dir = flowDirections(hf);
  EXPECT_EQ(dir[hf.index(7, 2)], 0); // downhill, east
  for (int i = 1; i <= 6; ++i)
  {
    EXPECT_EQ(dir[hf.index(i, 2)], 0) << i; // across the flat, east
  }
  // Everything but the 18 cells of rows 0 and 4 (no lower neighbour) ends at
  // (8, 2): rows 1 and 3 (18 cells) and (0, 2) fall onto the terrace (6 cells),
  // which crosses to (7, 2) and on to (8, 2) itself: 18 + 1 + 6 + 1 + 1.
  EXPECT_EQ(flowAccumulation(dir, hf.width, hf.height)[hf.index(8, 2)], 27u);
  // Closed: the exit raised above the flat, the terrace is a flat pit.
  hf.at(7, 2) = 12.0f;
  hf.at(8, 2) = 12.0f;
  hf.at(0, 2) = 12.0f;
  dir = flowDirections(hf);
  for (int i = 1; i <= 6; ++i)
  {
    EXPECT_EQ(dir[hf.index(i, 2)], kNoFlow) << i;
  }
  // A user sink on the flat becomes its exit.
  std::vector<std::uint8_t> sinks(hf.size(), 0);
  sinks[hf.index(3, 2)] = 1;
  dir = flowDirections(hf, &sinks);
  EXPECT_EQ(dir[hf.index(3, 2)], kNoFlow);
  EXPECT_EQ(dir[hf.index(1, 2)], 0);
  EXPECT_EQ(dir[hf.index(6, 2)], 4); // west, to the sink
}

TEST(Hydrology, AccumulationInATiltedVValleyMatchesTheCounts)
{
  // Flanks fall 5 m per cell towards column 10, the axis 1 m per cell south:
  // sideways (5 m / 30 m) beats diagonal ((5 + 1) m / 42.4 m), so every flank
  // cell flows straight to the channel, which flows south to row 0.
  constexpr int kW = 21;
  constexpr int kL = 50;
  constexpr int kAxis = 10;
  const Heightfield v =
    grid(kW, kL, 30.0, [](int i, int j) { return 500.0 + 5.0 * std::abs(i - kAxis) + 1.0 * j; });
  EXPECT_TRUE(sameBits(fillDepressions(v), v));
  const auto dir = flowDirections(v);
  const auto acc = flowAccumulation(dir, kW, kL);
  for (int j = 0; j < kL; ++j)
  {
    for (int i = 0; i < kW; ++i)
    {
      const std::uint32_t expected = i == kAxis ? static_cast<std::uint32_t>((kL - j) * kW)
        : i < kAxis                             ? static_cast<std::uint32_t>(i + 1)
                                                : static_cast<std::uint32_t>(kW - i);
      ASSERT_EQ(acc[v.index(i, j)], expected) << i << "," << j;
    }
  }
  EXPECT_EQ(dir[v.index(kAxis, 0)], kNoFlow); // the outlet
  EXPECT_EQ(acc[v.index(kAxis, 0)], static_cast<std::uint32_t>(kW * kL));
}

TEST(Hydrology, AccumulationConservesCellsOnARealDem)
{
  Heightfield dem = colorado();
  dem.valid.assign(dem.size(), 1);
  for (int j = 200; j < 230; ++j) // a block of nodata inside
  {
    for (int i = 300; i < 340; ++i)
    {
      dem.valid[dem.index(i, j)] = 0;
    }
  }
  const Heightfield filled = fillDepressions(dem);
  const auto dir = flowDirections(filled);
  const auto acc = flowAccumulation(dir, dem.width, dem.height, &filled.valid);
  std::uint64_t atOutlets = 0;
  std::size_t outlets = 0;
  for (std::size_t k = 0; k < dem.size(); ++k)
  {
    if (!dem.isValid(k))
    {
      EXPECT_EQ(acc[k], 0u);
      continue;
    }
    ASSERT_GE(acc[k], 1u);
    if (dir[k] == kNoFlow)
    {
      atOutlets += acc[k];
      ++outlets;
      const int i = static_cast<int>(k % static_cast<std::size_t>(dem.width));
      const int j = static_cast<int>(k / static_cast<std::size_t>(dem.width));
      ASSERT_TRUE(isSeedCell(dem, nullptr, i, j)) << "only seeds may be outlets";
    }
    else
    {
      const std::size_t down =
        static_cast<std::size_t>(static_cast<std::ptrdiff_t>(k) + d8Offset(dir[k], dem.width));
      ASSERT_GT(acc[down], acc[k]);
    }
  }
  EXPECT_EQ(atOutlets, dem.validCount());
  EXPECT_GT(outlets, 0u);
}

TEST(Hydrology, DirectionsAndAccumulationDoNotDependOnThreads)
{
  const Heightfield filled = fillDepressions(colorado());
  const int threads = omp_get_max_threads();
  const auto dir = flowDirections(filled);
  const auto acc = flowAccumulation(dir, filled.width, filled.height);
  omp_set_num_threads(1);
  const auto dir1 = flowDirections(filled);
  omp_set_num_threads(threads);
  EXPECT_EQ(dir, dir1);
  EXPECT_EQ(acc, flowAccumulation(dir1, filled.width, filled.height));
}

TEST(Hydrology, AccumulationRefusesMalformedDirections)
{
  std::vector<std::int8_t> dir(4, kNoFlow);
  EXPECT_THROW(flowAccumulation(dir, 3, 3), Error); // wrong size
  dir.assign(9, kNoFlow);
  dir[4] = 0; // centre -> east
  dir[5] = 4; // east -> centre: a cycle
  EXPECT_THROW(flowAccumulation(dir, 3, 3), Error);
  dir[5] = 0; // east edge -> off the grid
  EXPECT_THROW(flowAccumulation(dir, 3, 3), Error);
  dir[5] = 9;
  EXPECT_THROW(flowAccumulation(dir, 3, 3), Error);
  dir[5] = kNoFlow;
  std::vector<std::uint8_t> valid(9, 1);
  valid[5] = 0;
  EXPECT_THROW(flowAccumulation(dir, 3, 3, &valid), Error); // into an invalid cell
  valid[5] = 1;
  const auto acc = flowAccumulation(dir, 3, 3, &valid);
  EXPECT_EQ(acc[5], 2u);
  EXPECT_EQ(acc[4], 1u);
}
