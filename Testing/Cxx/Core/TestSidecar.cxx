// Tests of Kernels/Core/Sidecar.cxx.
#include "Core/Error.h"
#include "Core/Sidecar.h"
#include "TestData.h"

#include <gtest/gtest.h>

#include <fstream>

namespace
{

std::string writeText(const std::string& name, const std::string& text)
{
  const auto path = (tsynth::test::scratchDir() / name).string();
  std::ofstream(path) << text;
  return path;
}

std::string errorOf(const std::string& path)
{
  try
  {
    tsynth::readSidecar(path);
  }
  catch (const tsynth::Error& e)
  {
    return e.what();
  }
  return "";
}

} // namespace

TEST(Sidecar, ReadsEveryKey)
{
  const auto path = writeText("full.json",
    R"({"z_unit": "ft", "cell_size_m": [30.5, 31], "z_min": -10, "z_max": 250.5, "nodata": 0})");
  const tsynth::Sidecar s = tsynth::readSidecar(path);
  ASSERT_TRUE(s.zUnit && s.cellX && s.cellY && s.zMin && s.zMax && s.nodata);
  EXPECT_EQ(*s.zUnit, tsynth::ZUnit::Feet);
  EXPECT_DOUBLE_EQ(*s.cellX, 30.5);
  EXPECT_DOUBLE_EQ(*s.cellY, 31.0);
  EXPECT_DOUBLE_EQ(*s.zMin, -10.0);
  EXPECT_DOUBLE_EQ(*s.zMax, 250.5);
  EXPECT_DOUBLE_EQ(*s.nodata, 0.0);
}

TEST(Sidecar, SingleCellSizeAppliesToBothAxes)
{
  const tsynth::Sidecar s = tsynth::readSidecar(writeText("one.json", R"({"cell_size_m": 90})"));
  EXPECT_DOUBLE_EQ(*s.cellX, 90.0);
  EXPECT_DOUBLE_EQ(*s.cellY, 90.0);
  EXPECT_FALSE(s.zUnit.has_value());
}

TEST(Sidecar, WriteThenReadIsIdentity)
{
  tsynth::Sidecar s;
  s.zUnit = tsynth::ZUnit::Metres;
  s.cellX = 12.25;
  s.cellY = 13.5;
  s.zMin = 100.125;
  s.zMax = 4000.75;
  const auto path = (tsynth::test::scratchDir() / "written.json").string();
  tsynth::writeSidecar(path, s);
  const tsynth::Sidecar r = tsynth::readSidecar(path);
  EXPECT_EQ(*r.zUnit, tsynth::ZUnit::Metres);
  EXPECT_DOUBLE_EQ(*r.cellX, 12.25);
  EXPECT_DOUBLE_EQ(*r.cellY, 13.5);
  EXPECT_DOUBLE_EQ(*r.zMin, 100.125);
  EXPECT_DOUBLE_EQ(*r.zMax, 4000.75);
  EXPECT_FALSE(r.nodata.has_value());
}

// Found by fuzzing: a sidecar without keys was written as `null`, which the reader refuses.
TEST(Sidecar, EmptySidecarWritesAnObjectItReadsBack)
{
  const auto path = (tsynth::test::scratchDir() / "empty-written.json").string();
  tsynth::writeSidecar(path, tsynth::Sidecar{});
  const tsynth::Sidecar r = tsynth::readSidecar(path);
  EXPECT_FALSE(r.zUnit || r.cellX || r.cellY || r.zMin || r.zMax || r.nodata);
}

TEST(Sidecar, BadInputGetsOneClearSentence)
{
  EXPECT_NE(errorOf(writeText("bad.json", R"({"z_unit": "m", )")).find("is not valid JSON"),
    std::string::npos);
  EXPECT_NE(errorOf(writeText("unit.json", R"({"z_unit": "furlong"})")).find("\"m\" or \"ft\""),
    std::string::npos);
  EXPECT_NE(
    errorOf(writeText("cell.json", R"({"cell_size_m": -3})")).find("positive"), std::string::npos);
  EXPECT_NE(errorOf(writeText("cell3.json", R"({"cell_size_m": [1, 2, 3]})")).find("[x, y]"),
    std::string::npos);
  EXPECT_NE(errorOf(writeText("half.json", R"({"z_min": 3})")).find("together"), std::string::npos);
  EXPECT_NE(errorOf(writeText("order.json", R"({"z_min": 3, "z_max": 2})")).find("greater"),
    std::string::npos);
  EXPECT_NE(errorOf(writeText("array.json", R"([1, 2])")).find("JSON object"), std::string::npos);
  // Found by fuzzing: the JSON parser's number overflow escaped as its own exception type.
  EXPECT_NE(
    errorOf(writeText("overflowing.json", R"({"nodata": 1e999})")).find("too large for a double"),
    std::string::npos);
}

TEST(Sidecar, PathIsBesideTheRaster)
{
  EXPECT_EQ(tsynth::sidecarPathFor("/a/b/alaska.png"), "/a/b/alaska.json");
  EXPECT_EQ(tsynth::sidecarPathFor("dem.tif"), "dem.json");
}

TEST(Sidecar, UnitSpellings)
{
  EXPECT_EQ(tsynth::parseZUnit("Metres"), tsynth::ZUnit::Metres);
  EXPECT_EQ(tsynth::parseZUnit("feet"), tsynth::ZUnit::Feet);
  EXPECT_FALSE(tsynth::parseZUnit("yards").has_value());
}
