// Tests of Kernels/Core/Heightfield.cxx.
// Nodata never enters a figure, a window search agrees with looking at every
// window, and the content hash sees every cell, mask bit and cell size.
#include "Core/ContentHash.h"
#include "Core/Heightfield.h"
#include "ErrorOf.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

using namespace tsynth;

namespace
{

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// Every side x side window looked at, one by one.
bool anyValidWindowByLooking(const Heightfield& hf, int side)
{
  for (int y = 0; y + side <= hf.height; ++y)
  {
    for (int x = 0; x + side <= hf.width; ++x)
    {
      bool whole = true;
      for (int j = y; j < y + side && whole; ++j)
      {
        for (int i = x; i < x + side && whole; ++i)
        {
          whole = hf.isValid(i, j);
        }
      }
      if (whole)
      {
        return true;
      }
    }
  }
  return false;
}

std::uint64_t hashOf(const Heightfield& hf)
{
  ContentHasher h;
  hashHeightfield(h, hf);
  return h.digest();
}

} // namespace

TEST(Heightfield, RangeAndMeanLeaveNodataOut)
{
  Heightfield hf(3, 2);
  hf.z = { 10.0f, kNaN, 30.0f, -5.0f, 1.0e30f, 5.0f };
  normaliseMask(hf);
  hf.valid[4] = 0; // a declared nodata value, not NaN
  const HeightRange r = computeHeightRange(hf);
  EXPECT_EQ(r.validCells, 4u);
  EXPECT_EQ(hf.validCount(), 4u);
  EXPECT_EQ(r.min, -5.0f);
  EXPECT_EQ(r.max, 30.0f);
  EXPECT_DOUBLE_EQ(r.mean, 10.0);
}

TEST(Heightfield, NormaliseMaskMarksWhatIsNotFiniteAndDropsAMaskOfAllValid)
{
  Heightfield hf(2, 2);
  hf.z = { 1.0f, std::numeric_limits<float>::infinity(), kNaN, 4.0f };
  normaliseMask(hf);
  ASSERT_TRUE(hf.hasMask());
  EXPECT_EQ(hf.valid, std::vector<std::uint8_t>({ 1, 0, 0, 1 }));
  Heightfield full(2, 2, 3.0f);
  full.valid.assign(4, 1);
  normaliseMask(full);
  EXPECT_FALSE(full.hasMask()) << "a mask of all valid cells is kept";
}

TEST(Heightfield, PercentileIsTheNearestRankBelow)
{
  const std::vector<float> values = { 11, 3, 7, 1, 9, 5, 2, 10, 4, 8, 6 }; // 1..11, shuffled
  EXPECT_EQ(percentile(values, 0.0), 1.0);
  EXPECT_EQ(percentile(values, 0.5), 6.0);
  EXPECT_EQ(percentile(values, 0.95), 10.0); // rank floor(0.95 * 10) = 9
  EXPECT_EQ(percentile(values, 1.0), 11.0);
  EXPECT_EQ(percentile({}, 0.5), 0.0);
}

TEST(Heightfield, AValidWindowIsFoundExactlyWhereOneExists)
{
  std::mt19937 rng(11);
  int found = 0;
  int none = 0;
  for (int trial = 0; trial < 40; ++trial)
  {
    Heightfield hf(23, 17, 1.0f);
    hf.valid.assign(hf.size(), 1);
    std::bernoulli_distribution hole(0.02 + 0.005 * trial);
    for (std::uint8_t& v : hf.valid)
    {
      v = hole(rng) ? 0 : 1;
    }
    for (int side : { 1, 3, 6, 10, 17, 18 })
    {
      SCOPED_TRACE(::testing::Message() << "trial " << trial << ", side " << side);
      const bool expected = anyValidWindowByLooking(hf, side);
      EXPECT_EQ(hasValidWindow(hf, side), expected);
      (expected ? found : none) += 1;
    }
  }
  EXPECT_GT(found, 20) << "too few grids with a window to tell";
  EXPECT_GT(none, 20) << "too few grids without one to tell";
  EXPECT_FALSE(hasValidWindow(Heightfield(5, 5), 6)) << "larger than the grid";
  EXPECT_FALSE(hasValidWindow(Heightfield(5, 5), 0));
}

TEST(Heightfield, ImplausibleHeightsAreRefusedNamingTheInput)
{
  Heightfield hf(4, 1);
  hf.z = { 100.0f, -3.4e38f, 120.0f, 130.0f }; // an undeclared float nodata value
  const std::string message = test::errorOf([&] { checkPlausibleHeights(hf, "dem.tif"); });
  EXPECT_NE(message.find("dem.tif"), std::string::npos) << message;
  hf.valid = { 1, 0, 1, 1 }; // declared: no longer a height
  EXPECT_EQ(test::errorOf([&] { checkPlausibleHeights(hf, "dem.tif"); }), "");
}

TEST(Heightfield, TheContentHashSeesEveryCellMaskBitAndCellSize)
{
  Heightfield hf(8, 6, 100.0f);
  hf.cellX = hf.cellY = 30.0;
  const std::uint64_t base = hashOf(hf);
  EXPECT_EQ(hashOf(hf), base) << "not repeatable";
  Heightfield height = hf;
  height.at(7, 5) = std::nextafter(100.0f, 200.0f);
  Heightfield mask = hf;
  mask.valid.assign(mask.size(), 1);
  Heightfield masked = mask;
  masked.valid[3] = 0;
  Heightfield cell = hf;
  cell.cellY = 30.000001;
  Heightfield shape(6, 8, 100.0f);
  shape.cellX = shape.cellY = 30.0;
  for (const Heightfield* other : { &height, &masked, &cell, &shape })
  {
    EXPECT_NE(hashOf(*other), base);
  }
  EXPECT_NE(hashOf(masked), hashOf(mask));
}
