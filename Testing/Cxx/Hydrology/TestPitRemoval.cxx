// Tests of Kernels/Hydrology/PitRemoval.cxx.
// Breaching, the hybrid and removePits: exact answers on hand-made grids, the
// pit-free oracle on every real DEM and on seeded random fields, and the
// contracts (never raised / never lowered, sinks, nodata, limits, errors).
#include "Core/Error.h"
#include "Core/HeightfieldIO.h"
#include "Hydrology/Breach.h"
#include "Hydrology/Flow.h"
#include "Hydrology/PitRemoval.h"
#include "TestData.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <queue>
#include <random>

using namespace tsynth;

namespace
{

namespace fs = std::filesystem;

float down(float z, int steps = 1)
{
  for (int s = 0; s < steps; ++s)
  {
    z = std::nextafter(z, -std::numeric_limits<float>::infinity());
  }
  return z;
}

float up(float z)
{
  return std::nextafter(z, std::numeric_limits<float>::infinity());
}

bool sameBits(const Heightfield& a, const Heightfield& b)
{
  if (a.width != b.width || a.height != b.height || a.valid != b.valid)
  {
    return false;
  }
  for (std::size_t k = 0; k < a.size(); ++k)
  {
    if (!(std::isnan(a.z[k]) && std::isnan(b.z[k])) && a.z[k] != b.z[k])
    {
      return false;
    }
  }
  return true;
}

// Cells higher (sign +1) or lower (-1) than in `before`.
std::size_t countChanged(const Heightfield& before, const Heightfield& after, int sign)
{
  std::size_t n = 0;
  for (std::size_t k = 0; k < before.size(); ++k)
  {
    if (isUsableCell(before, k))
    {
      n += (sign > 0 ? after.z[k] > before.z[k] : after.z[k] < before.z[k]) ? 1 : 0;
    }
  }
  return n;
}

// The digest's sketch of Soille's breaching, written plainly: one
// std::priority_queue of (original height, cell), seeds as isSeedCell, each
// reached cell remembering where it was reached from, and a carve back along
// those links (sinks lowered too) whenever a reached cell is lower.
Heightfield referenceBreach(const Heightfield& dem)
{
  Heightfield t = dem;
  const std::size_t n = dem.size();
  std::vector<std::uint8_t> closed(n, 0);
  std::vector<std::int64_t> from(n, -1);
  using Item = std::pair<float, std::uint32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  for (int j = 0; j < dem.height; ++j)
  {
    for (int i = 0; i < dem.width; ++i)
    {
      if (isSeedCell(dem, nullptr, i, j))
      {
        closed[dem.index(i, j)] = 1;
        open.push({ dem.at(i, j), static_cast<std::uint32_t>(dem.index(i, j)) });
      }
    }
  }
  while (!open.empty())
  {
    const std::uint32_t p = open.top().second;
    open.pop();
    const int pi = static_cast<int>(p % static_cast<std::uint32_t>(dem.width));
    const int pj = static_cast<int>(p / static_cast<std::uint32_t>(dem.width));
    for (int c = 0; c < kD8Directions; ++c)
    {
      const int ni = pi + kD8Dx[c];
      const int nj = pj + kD8Dy[c];
      if (ni < 0 || nj < 0 || ni >= dem.width || nj >= dem.height)
      {
        continue;
      }
      const std::size_t q = dem.index(ni, nj);
      if (closed[q] != 0 || !isUsableCell(dem, q))
      {
        continue;
      }
      closed[q] = 1;
      from[q] = p;
      open.push({ t.z[q], static_cast<std::uint32_t>(q) });
      if (t.z[q] < t.z[p])
      {
        float z = t.z[q];
        for (std::int64_t r = p; r >= 0 && t.z[static_cast<std::size_t>(r)] >= z;
             r = from[static_cast<std::size_t>(r)])
        {
          z = down(z);
          t.z[static_cast<std::size_t>(r)] = z;
        }
      }
    }
  }
  return t;
}

const Heightfield& colorado()
{
  static const Heightfield hf = readHeightfield(test::bundledData() / "dems" / "colorado.png");
  return hf;
}

// A 5 x 3 grid: border cells at 10 m except an outlet on the west edge (0, 1);
// the middle row rises 6, 7 m towards a pit of 3 m at (3, 1). The flood reaches
// the pit from (2, 1) and must carve (2, 1), (1, 1) and, if it is not already
// lower, the outlet.
Heightfield corridor(float outlet)
{
  Heightfield dem(5, 3, 10.0f);
  dem.cellX = dem.cellY = 30.0;
  dem.at(0, 1) = outlet;
  dem.at(1, 1) = 6.0f;
  dem.at(2, 1) = 7.0f;
  dem.at(3, 1) = 3.0f;
  return dem;
}

// White noise 0..100 m, with `holes` of the cells nodata.
Heightfield noise(unsigned seed, int w, int h, double holes)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> height(0.0f, 100.0f);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Heightfield dem(w, h);
  dem.cellX = dem.cellY = 30.0;
  for (float& z : dem.z)
  {
    z = height(rng);
  }
  if (holes > 0.0)
  {
    dem.valid.assign(dem.size(), 1);
    for (std::size_t k = 0; k < dem.size(); ++k)
    {
      if (unit(rng) < holes)
      {
        dem.valid[k] = 0;
        dem.z[k] = std::numeric_limits<float>::quiet_NaN();
      }
    }
  }
  return dem;
}

// Every valid cell lowered by at most `maxDepth` metres.
double deepestCut(const Heightfield& before, const Heightfield& after)
{
  double deepest = 0.0;
  for (std::size_t k = 0; k < before.size(); ++k)
  {
    if (isUsableCell(before, k))
    {
      deepest = std::max(deepest, static_cast<double>(before.z[k]) - after.z[k]);
    }
  }
  return deepest;
}

constexpr double kHuge = 1e30;                                    // limits no channel reaches
constexpr double kTinyDepth = std::numeric_limits<double>::min(); // below any float step

// The three methods with their contracts, on one DEM and sink mask.
void checkAllMethods(const Heightfield& dem, const std::vector<std::uint8_t>* sinks)
{
  const Heightfield filled = fillDepressions(dem, sinks);
  const Heightfield breached = breachDepressions(dem, sinks);
  const PitRemovalOptions defaults;
  const Heightfield hybrid =
    breachOrFillDepressions(dem, defaults.maxBreachDepth, defaults.maxBreachLength, sinks);
  std::size_t bad = 0;
  EXPECT_TRUE(drainsEverywhere(filled, sinks, &bad)) << "fill, cell " << bad;
  EXPECT_TRUE(drainsEverywhere(breached, sinks, &bad)) << "breach, cell " << bad;
  EXPECT_TRUE(drainsEverywhere(hybrid, sinks, &bad)) << "hybrid, cell " << bad;
  EXPECT_EQ(countChanged(dem, filled, -1), 0u) << "fill lowered a cell";
  EXPECT_EQ(countChanged(dem, breached, +1), 0u) << "breach raised a cell";
  EXPECT_LE(deepestCut(dem, hybrid), defaults.maxBreachDepth);
  for (const Heightfield* out : { &filled, &breached, &hybrid })
  {
    EXPECT_EQ(out->valid, dem.valid);
    for (std::size_t k = 0; k < dem.size(); ++k)
    {
      if (!isUsableCell(dem, k))
      {
        ASSERT_TRUE(std::isnan(out->z[k]) || out->z[k] == dem.z[k]) << "invalid cell " << k;
      }
      else if (sinks != nullptr && (*sinks)[k] != 0)
      {
        // Every field here has outlets besides the user's, so user sinks keep their heights.
        ASSERT_EQ(out->z[k], dem.z[k]) << "user sink " << k;
      }
    }
  }
}

} // namespace

TEST(PitRemoval, BreachCarvesTheKnownChannelOfACorridor)
{
  // Outlet at 5 m (above the pit): the outlet is lowered too, one step below (1, 1).
  const Heightfield high = corridor(5.0f);
  const Heightfield a = breachDepressions(high);
  EXPECT_EQ(a.at(3, 1), 3.0f);          // the pit keeps its height
  EXPECT_EQ(a.at(2, 1), down(3.0f, 1)); // each channel cell one float step below the last
  EXPECT_EQ(a.at(1, 1), down(3.0f, 2));
  EXPECT_EQ(a.at(0, 1), down(3.0f, 3)); // the border sink, lowered
  EXPECT_EQ(countChanged(high, a, -1), 3u);
  EXPECT_EQ(countChanged(high, a, +1), 0u);
  EXPECT_TRUE(drainsEverywhere(a, nullptr));
  EXPECT_FALSE(drainsEverywhere(high, nullptr));

  // Outlet at 2 m (below the pit): the carve stops there and the sink is untouched.
  const Heightfield low = corridor(2.0f);
  const Heightfield b = breachDepressions(low);
  EXPECT_EQ(b.at(2, 1), down(3.0f, 1));
  EXPECT_EQ(b.at(1, 1), down(3.0f, 2));
  EXPECT_EQ(b.at(0, 1), 2.0f);
  EXPECT_EQ(countChanged(low, b, -1), 2u);
  EXPECT_TRUE(sameBits(breachDepressions(b), b)); // breaching a pit-free grid changes nothing
}

TEST(PitRemoval, BreachEqualsAPlainPriorityQueueBreachOnEveryRealDem)
{
  const auto dems = test::realDems();
  ASSERT_GE(dems.size(), 3u) << "the bundled DEMs are missing";
  for (const std::string& path : dems)
  {
    SCOPED_TRACE(path);
    const Heightfield dem = readHeightfield(path);
    const Heightfield breached = breachDepressions(dem);
    EXPECT_TRUE(sameBits(breached, referenceBreach(dem)));
    EXPECT_TRUE(sameBits(breachDepressions(breached), breached)); // idempotent
    EXPECT_GT(countChanged(dem, breached, -1), 0u);
  }
}

TEST(PitRemoval, EveryRealDemDrainsAfterEachMethod)
{
  for (const std::string& path : test::realDems())
  {
    SCOPED_TRACE(path);
    const Heightfield dem = readHeightfield(path);
    ASSERT_FALSE(drainsEverywhere(dem, nullptr));
    checkAllMethods(dem, nullptr);
  }
}

TEST(PitRemoval, RandomFieldsDrainWithHolesAndUserSinks)
{
  for (unsigned seed = 1; seed <= 6; ++seed)
  {
    SCOPED_TRACE(seed);
    const Heightfield plain = noise(seed, 61, 47, 0.0);
    const Heightfield holes = noise(seed + 100, 61, 47, 0.08);
    ASSERT_GT(countPits(plain), 100u); // white noise: about one cell in nine is a pit
    checkAllMethods(plain, nullptr);
    checkAllMethods(holes, nullptr);
    EXPECT_TRUE(sameBits(breachDepressions(plain), referenceBreach(plain)));
    EXPECT_TRUE(sameBits(breachDepressions(holes), referenceBreach(holes)));

    // User sinks: 2% of the cells, some of them in the nodata field.
    std::mt19937 rng(seed);
    std::vector<std::uint8_t> sinks(plain.size(), 0);
    for (std::uint8_t& s : sinks)
    {
      s = rng() % 50 == 0 ? 1 : 0;
    }
    checkAllMethods(plain, &sinks);
    checkAllMethods(holes, &sinks);
    // The sinks change the answer (pits drain into them, or are rerouted around them).
    EXPECT_FALSE(sameBits(breachDepressions(plain, &sinks), breachDepressions(plain)));
  }
}

TEST(PitRemoval, BreachReroutesAPitThatWouldLowerAUserSink)
{
  // A bowl (bottom 2 m at (10, 10)) whose only outlet is a gap at 15 m in its
  // south wall; a lake at (10, 13), 3.5 m, on the bowl's flank. The flood from
  // the lake reaches the bottom first, but draining the bottom into the lake
  // would lower the lake: the bottom gets a channel through the gap instead.
  constexpr int kSize = 21;
  Heightfield dem(kSize, kSize);
  dem.cellX = dem.cellY = 30.0;
  for (int j = 0; j < kSize; ++j)
  {
    for (int i = 0; i < kSize; ++i)
    {
      const bool wall = std::max(std::abs(i - 10), std::abs(j - 10)) == 7;
      const double r2 = (i - 10) * (i - 10) + (j - 10) * (j - 10);
      dem.at(i, j) = wall ? 20.0f : static_cast<float>(std::min(2.0 + 0.5 * r2, 19.0));
    }
  }
  dem.at(10, 3) = 15.0f; // the gap
  std::vector<std::uint8_t> sinks(dem.size(), 0);
  sinks[dem.index(10, 13)] = 1;
  ASSERT_EQ(dem.at(10, 13), 6.5f);
  dem.at(10, 13) = 3.5f;

  const Heightfield breached = breachDepressions(dem, &sinks);
  EXPECT_EQ(breached.at(10, 13), 3.5f); // the lake keeps its height
  EXPECT_EQ(breached.at(10, 10), 2.0f); // the bottom is the channel's head
  EXPECT_LT(breached.at(10, 3), 2.0f);  // the gap is carved below the bottom
  EXPECT_TRUE(drainsEverywhere(breached, &sinks));
  EXPECT_EQ(countChanged(dem, breached, +1), 0u);
  // Without the lake's cell as a sink the answer is the plain breach.
  EXPECT_TRUE(sameBits(breachDepressions(dem), referenceBreach(dem)));

  // The hybrid keeps the lake too: with huge limits the bottom is filled (a
  // breach through the lake was refused) or carved through the gap, never lowers the lake.
  const Heightfield hybrid = breachOrFillDepressions(dem, kHuge, 1000000, &sinks);
  EXPECT_EQ(hybrid.at(10, 13), 3.5f);
  EXPECT_TRUE(drainsEverywhere(hybrid, &sinks));

  // Every outlet a user sink (the whole border): no channel can avoid them, so
  // one is lowered as a last resort rather than leaving a pit.
  std::vector<std::uint8_t> all = sinks;
  for (int j = 0; j < kSize; ++j)
  {
    for (int i = 0; i < kSize; ++i)
    {
      if (i == 0 || j == 0 || i == kSize - 1 || j == kSize - 1)
      {
        all[dem.index(i, j)] = 1;
      }
    }
  }
  const Heightfield cornered = breachDepressions(dem, &all);
  EXPECT_TRUE(drainsEverywhere(cornered, &all));
  EXPECT_EQ(countChanged(dem, cornered, +1), 0u);
  std::size_t loweredSinks = 0;
  for (std::size_t k = 0; k < dem.size(); ++k)
  {
    loweredSinks += (all[k] != 0 && cornered.z[k] < dem.z[k]) ? 1 : 0;
  }
  EXPECT_GE(loweredSinks, 1u);
}

TEST(PitRemoval, NodataCellsAreNeverTraversedNorChanged)
{
  // The corridor with its outlet made nodata: (1, 1) is now next to nodata, so
  // it is a sink; the channel ends there and the hole stays a hole.
  Heightfield dem = corridor(5.0f);
  dem.valid.assign(dem.size(), 1);
  dem.valid[dem.index(0, 1)] = 0;
  dem.at(0, 1) = std::numeric_limits<float>::quiet_NaN();
  const Heightfield b = breachDepressions(dem);
  EXPECT_TRUE(std::isnan(b.at(0, 1)));
  EXPECT_FALSE(b.isValid(0, 1));
  // (2, 1) is reached at 7 m from (1, 1), 6 m, not from a 10 m border cell.
  EXPECT_EQ(b.at(2, 1), down(3.0f, 1));
  EXPECT_EQ(b.at(1, 1), down(3.0f, 2));
  EXPECT_TRUE(drainsEverywhere(b, nullptr));
  // NaN without a mask is nodata too.
  Heightfield nanOnly = dem;
  nanOnly.valid.clear();
  const Heightfield c = breachDepressions(nanOnly);
  EXPECT_TRUE(std::isnan(c.at(0, 1)));
  EXPECT_EQ(c.at(1, 1), down(3.0f, 2));
}

TEST(PitRemoval, HybridBreachesWithinTheLimitsAndFillsBeyond)
{
  // The corridor's channel: 3 cells, deepest cut 7 m - down(3 m) at (2, 1).
  const Heightfield dem = corridor(5.0f);
  const double cut = 7.0 - static_cast<double>(down(3.0f));
  const Heightfield breached = breachDepressions(dem);
  EXPECT_TRUE(sameBits(breachOrFillDepressions(dem, cut, 3), breached));
  EXPECT_TRUE(sameBits(breachOrFillDepressions(dem, kHuge, 1000000), breached));
  // One cell too long or a hair too deep: filled, the pit one step above (2, 1).
  Heightfield filled = dem;
  filled.at(3, 1) = up(7.0f);
  EXPECT_TRUE(sameBits(breachOrFillDepressions(dem, cut, 2), filled));
  EXPECT_TRUE(sameBits(breachOrFillDepressions(dem, std::nextafter(cut, 0.0), 3), filled));
  EXPECT_TRUE(sameBits(fillDepressions(dem), filled));
}

TEST(PitRemoval, HybridLimitExtremesOnARealDem)
{
  const Heightfield& dem = colorado();
  const Heightfield breached = breachDepressions(dem);
  EXPECT_TRUE(
    sameBits(breachOrFillDepressions(dem, kHuge, std::numeric_limits<int>::max()), breached));
  const Heightfield tiny = breachOrFillDepressions(dem, kTinyDepth, 1);
  EXPECT_EQ(countChanged(dem, tiny, -1), 0u);
  EXPECT_GT(countChanged(dem, tiny, +1), 0u);
  EXPECT_TRUE(drainsEverywhere(tiny, nullptr));

  // In between: no cut deeper than the limit, and both kinds of change.
  constexpr double kDepth = 5.0;
  constexpr int kLength = 20;
  const Heightfield mixed = breachOrFillDepressions(dem, kDepth, kLength);
  EXPECT_LE(deepestCut(dem, mixed), kDepth);
  EXPECT_GT(deepestCut(dem, breached), kDepth); // so the limit did something
  EXPECT_GT(countChanged(dem, mixed, -1), 0u);
  EXPECT_GT(countChanged(dem, mixed, +1), 0u);
  EXPECT_TRUE(drainsEverywhere(mixed, nullptr));
  // The survey's figures: what it calls within the limits is what the hybrid breaches.
  std::size_t within = 0;
  for (const DepressionChannel& d : surveyDepressions(dem, nullptr))
  {
    EXPECT_GT(d.cells, 0u);
    EXPECT_GE(d.maxLength, 1u);
    within += d.maxCut <= kDepth && d.maxLength <= static_cast<std::size_t>(kLength) ? 1 : 0;
  }
  EXPECT_GT(within, 0u);
}

TEST(PitRemoval, RemovePitsReportsWhatChanged)
{
  for (const PitRemovalMethod method :
    { PitRemovalMethod::Fill, PitRemovalMethod::Breach, PitRemovalMethod::Hybrid })
  {
    SCOPED_TRACE(pitRemovalMethodName(method));
    PitRemovalOptions options;
    options.method = method;
    options.maxBreachDepth = 5.0; // tight enough that the hybrid both breaches and fills here
    options.maxBreachLength = 20;
    const Heightfield& dem = colorado();
    const PitRemovalResult r = removePits(dem, options);
    std::size_t raised = 0;
    std::size_t lowered = 0;
    double maxRaise = 0.0;
    double maxLower = 0.0;
    for (std::size_t k = 0; k < dem.size(); ++k)
    {
      const double d = static_cast<double>(r.dem.z[k]) - dem.z[k];
      const std::uint8_t code = d > 0.0 ? 1 : d < 0.0 ? 2 : 0;
      ASSERT_EQ(r.changed[k], code) << k;
      raised += code == 1 ? 1 : 0;
      lowered += code == 2 ? 1 : 0;
      maxRaise = std::max(maxRaise, d);
      maxLower = std::max(maxLower, -d);
    }
    EXPECT_EQ(r.raisedCells, raised);
    EXPECT_EQ(r.loweredCells, lowered);
    EXPECT_EQ(r.maxRaise, maxRaise);
    EXPECT_EQ(r.maxLower, maxLower);
    EXPECT_EQ(method == PitRemovalMethod::Breach, raised == 0);
    EXPECT_EQ(method == PitRemovalMethod::Fill, lowered == 0);
  }
  // The corridor, exactly.
  PitRemovalOptions breach;
  const Heightfield dem = corridor(5.0f);
  const PitRemovalResult r = removePits(dem, breach);
  EXPECT_EQ(r.loweredCells, 3u);
  EXPECT_EQ(r.raisedCells, 0u);
  EXPECT_EQ(r.maxLower, 7.0 - static_cast<double>(down(3.0f)));
  EXPECT_EQ(r.changed[dem.index(0, 1)], 2);
  EXPECT_EQ(r.changed[dem.index(3, 1)], 0);
  PitRemovalOptions fill;
  fill.method = PitRemovalMethod::Fill;
  const PitRemovalResult f = removePits(dem, fill);
  EXPECT_EQ(f.raisedCells, 1u);
  EXPECT_EQ(f.changed[dem.index(3, 1)], 1);
  EXPECT_EQ(f.maxRaise, static_cast<double>(up(7.0f)) - 3.0);
}

TEST(PitRemoval, AccumulationCountsEveryCellOnceOnABreachedDem)
{
  Heightfield dem = colorado();
  dem.valid.assign(dem.size(), 1);
  for (int j = 200; j < 230; ++j) // a block of nodata inside
  {
    for (int i = 300; i < 340; ++i)
    {
      dem.valid[dem.index(i, j)] = 0;
      dem.at(i, j) = std::numeric_limits<float>::quiet_NaN();
    }
  }
  for (const Heightfield& out : { breachDepressions(dem), breachOrFillDepressions(dem, 5.0, 20) })
  {
    const auto dir = flowDirections(out);
    const auto acc = flowAccumulation(dir, dem.width, dem.height, &out.valid);
    std::uint64_t atOutlets = 0;
    for (std::size_t k = 0; k < dem.size(); ++k)
    {
      if (!dem.isValid(k) || dir[k] != kNoFlow)
      {
        continue;
      }
      atOutlets += acc[k];
      const int i = static_cast<int>(k % static_cast<std::size_t>(dem.width));
      const int j = static_cast<int>(k / static_cast<std::size_t>(dem.width));
      // Flats are routed across to their exits: only seeds end the flow.
      ASSERT_TRUE(isSeedCell(dem, nullptr, i, j)) << "an outlet off the seeds, cell " << k;
    }
    // Breaching keeps the original's flats (colorado's PNG heights have them):
    // cells with a direction but no lower neighbour, which the routing covered.
    std::size_t onFlats = 0;
    for (int j = 1; j + 1 < dem.height; ++j)
    {
      for (int i = 1; i + 1 < dem.width; ++i)
      {
        const std::size_t k = dem.index(i, j);
        bool lower = false;
        for (int c = 0; c < kD8Directions; ++c)
        {
          const std::size_t n = dem.index(i + kD8Dx[c], j + kD8Dy[c]);
          lower = lower || (out.isValid(n) && out.z[n] < out.z[k]);
        }
        onFlats += out.isValid(k) && !lower && dir[k] != kNoFlow ? 1 : 0;
      }
    }
    EXPECT_GT(onFlats, 0u);
    EXPECT_EQ(atOutlets, dem.validCount());
  }
}

TEST(PitRemoval, BadInputsAreRefused)
{
  const Heightfield dem = corridor(5.0f);
  const std::vector<std::uint8_t> wrong(dem.size() + 1, 0);
  EXPECT_THROW(breachDepressions(dem, &wrong), Error);
  EXPECT_THROW(breachOrFillDepressions(dem, 1.0, 10, &wrong), Error);
  PitRemovalOptions options;
  options.sinks = &wrong;
  EXPECT_THROW(removePits(dem, options), Error);
  EXPECT_THROW(breachOrFillDepressions(dem, 0.0, 10), Error);
  EXPECT_THROW(breachOrFillDepressions(dem, 1.0, 0), Error);
  EXPECT_THROW(breachOrFillDepressions(dem, std::nan(""), 10), Error);

  Heightfield empty(4, 4, std::numeric_limits<float>::quiet_NaN());
  for (const PitRemovalMethod method :
    { PitRemovalMethod::Fill, PitRemovalMethod::Breach, PitRemovalMethod::Hybrid })
  {
    PitRemovalOptions o;
    o.method = method;
    EXPECT_THROW(removePits(empty, o), Error);
    empty.valid.assign(empty.size(), 0);
    empty.z.assign(empty.size(), 1.0f);
    EXPECT_THROW(removePits(empty, o), Error); // masked out, finite heights
    empty.valid.clear();
    empty.z.assign(empty.size(), std::numeric_limits<float>::quiet_NaN());
  }
  EXPECT_THROW(parsePitRemovalMethod("carve"), Error);
}

TEST(PitRemoval, BreachAndHybridAreDeterministic)
{
  const Heightfield& dem = colorado();
  EXPECT_TRUE(sameBits(breachDepressions(dem), breachDepressions(dem)));
  EXPECT_TRUE(
    sameBits(breachOrFillDepressions(dem, 5.0, 20), breachOrFillDepressions(dem, 5.0, 20)));
}

TEST(PitRemoval, AnOptionalMethodIsOffThenTheMethods)
{
  EXPECT_EQ(offOrMethodChoices().list(), "off, fill, breach or hybrid");
  const std::vector<std::string> labels{ "Off", "Fill", "Breach", "Hybrid" };
  EXPECT_EQ(offOrMethodLabels(), labels);
  EXPECT_FALSE(offOrMethod(0).has_value());
  EXPECT_EQ(offOrMethod(1), PitRemovalMethod::Fill);
  EXPECT_EQ(offOrMethod(2), PitRemovalMethod::Breach);
  EXPECT_EQ(offOrMethod(3), PitRemovalMethod::Hybrid);
  EXPECT_THROW(offOrMethod(4), Error);
  EXPECT_THROW(offOrMethod(-1), Error);
  for (int value = 0; value <= 3; ++value)
  {
    EXPECT_EQ(offOrMethodValue(offOrMethod(value)), value);
  }
}
