// Tests of Kernels/Distance/CostScaling.cxx: the minimum-scaling fix and the profiles read from
// rows and drawn images.
#include "Core/Error.h"
#include "Distance/CostScaling.h"
#include "DistanceTestData.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

using namespace tsynth;

namespace
{

using tsynth::test::distance::expectThrowsWith;

std::string writeTemp(const std::string& name, const std::string& text)
{
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

TEST(DistanceSynthesis, MinimumScalingFixInterpolatesFlatParts)
{
  // Falls 5 over 10 cells, flat for 20, falls 5 over 10: both slopes give
  // 15 cost units per 10 cells (c_s = 30) = 1.5; the flat part's bin is tiny.
  const MonotoneProfile p =
    MonotoneProfile::fromPoints({ 0.0, 10.0, 30.0, 40.0 }, { 10.0, 5.0, 5.0, 0.0 });
  const ScalingFunction raw = ScalingFunction::fromProfile(p, 30.0, 1.0, 1e-9, 64, 1.0);
  EXPECT_LT(raw.smallest(), 0.1f);
  const ScalingFunction fixed = ScalingFunction::fromProfile(p, 30.0, 1.0, 0.1, 64, 1.0);
  for (const float v : fixed.table())
  {
    EXPECT_NEAR(v, 1.5f, 1e-4f);
  }
  // w_s = s_m / mu_w: a doubled mean weight halves it.
  const ScalingFunction steep = ScalingFunction::fromProfile(p, 30.0, 2.0, 0.1, 64, 1.0);
  EXPECT_NEAR(steep(7.0f), 0.75f, 1e-4f);
}

TEST(DistanceSynthesis, ProfileCsvRowsAndErrors)
{
  const std::string good = writeTemp("good_profiles.csv",
    "distance,height,profile\n0,10,0\n5,4,0\n10,0,0\n# a second one\n0,1,1\n3,0,1\n");
  const std::vector<MonotoneProfile> profiles = readProfileCsv(good);
  ASSERT_EQ(profiles.size(), 2u);
  EXPECT_DOUBLE_EQ(profiles[0](5.0), 4.0);
  EXPECT_DOUBLE_EQ(profiles[1].length(), 3.0);
  expectThrowsWith(
    [] { readProfileCsv(writeTemp("rising.csv", "0,10\n5,4\n8,6\n10,0\n")); }, "line 3: height 6");
  expectThrowsWith(
    [] { readProfileCsv(writeTemp("backwards.csv", "0,10\n5,4\n5,3\n")); }, "line 3: distance 5");
  expectThrowsWith([] { readProfileCsv(writeTemp("flat.csv", "0,1\n5,1\n")); }, "must fall");
  expectThrowsWith(
    [] { readProfileCsv(writeTemp("gap.csv", "0,1,1\n5,0,1\n")); }, "profile 0 is missing");
}

TEST(DistanceSynthesis, ProfileFromADrawnImage)
{
  // A falling diagonal line drawn in a 20 x 11 image: height 10 - col / 2.
  ColourImage image;
  image.width = 20;
  image.height = 11;
  image.channels = 1;
  image.data.assign(20 * 11, 255);
  for (int col = 0; col < 20; ++col)
  {
    const int height = 10 - col / 2;
    image.data[static_cast<std::size_t>((10 - height) * 20 + col)] = 0;
  }
  const MonotoneProfile p = profileFromImage(image);
  EXPECT_DOUBLE_EQ(p.front(), 10.0);
  EXPECT_DOUBLE_EQ(p.back(), 1.0);
  EXPECT_DOUBLE_EQ(p(4.0), 8.0);
}

TEST(DistanceSynthesis, ProfileFilesAreReadByTheirExtension)
{
  // Rows in a .CSV or .txt in any case; anything else is an image, and a
  // table that is not one is refused by the image reader, not read as rows.
  for (const char* name : { "upper.CSV", "rows.txt" })
  {
    const std::vector<MonotoneProfile> p = readProfiles(writeTemp(name, "0,10\n5,4\n10,0\n"));
    ASSERT_EQ(p.size(), 1u) << name;
    EXPECT_DOUBLE_EQ(p[0](5.0), 4.0) << name;
  }
  EXPECT_THROW(readProfiles(writeTemp("rows.png", "0,10\n5,4\n10,0\n")), Error);
}

} // namespace
