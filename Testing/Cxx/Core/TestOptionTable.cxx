// Tests of Kernels/Core/OptionTable.cxx.
// Core/OptionTable: an enumeration's words and an option row's range, as the
// front ends read them.
#include "Core/Error.h"
#include "Core/OptionTable.h"
#include "ErrorOf.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace tsynth
{
namespace
{

using test::errorOf;

const char* const kWeather[] = { "sun", "rain", "snow" };

} // namespace

TEST(OptionTable, ChoicesNumberTheirWordsInOrder)
{
  const Choices weather = choicesOf(kWeather);
  EXPECT_EQ(weather.count, 3u);
  EXPECT_EQ(weather.list(), "sun, rain or snow");
  EXPECT_EQ(weather.valueOf("sun", "--weather"), 0);
  EXPECT_EQ(weather.valueOf("snow", "--weather"), 2);
  EXPECT_STREQ(weather.wordOf(1, "Weather"), "rain");
  EXPECT_EQ(errorOf([&] { weather.valueOf("hail", "--weather"); }),
    "--weather must be sun, rain or snow, not \"hail\".");
  EXPECT_EQ(errorOf([&] { weather.wordOf(3, "Weather"); }),
    "Weather 3 is none of 0 sun, 1 rain or 2 snow.");
  EXPECT_THROW(weather.wordOf(-1, "Weather"), Error);
  EXPECT_THROW(choiceOf<int>(weather, 3, "Weather"), Error);
  EXPECT_EQ(choiceOf<int>(weather, 2, "Weather"), 2);
}

TEST(OptionTable, ChoicesWithValuesStandForThemNotForTheirPositions)
{
  const char* const words[] = { "up", "down" };
  const int values[] = { 1, -1 };
  const Choices slope = choicesOf(words, values);
  EXPECT_EQ(slope.valueAt(0), 1);
  EXPECT_EQ(slope.valueAt(1), -1);
  EXPECT_EQ(slope.valueOf("down", "--slope"), -1);
  EXPECT_STREQ(slope.wordOf(1, "Slope"), "up");
  EXPECT_STREQ(slope.wordOf(-1, "Slope"), "down");
  EXPECT_EQ(errorOf([&] { slope.wordOf(0, "Slope"); }), "Slope 0 is none of 1 up or -1 down.");
  const OptionRow row = choiceRow("Slope", "--slope", 1, slope, { "Up", "Down" });
  EXPECT_EQ(row.min, -1.0) << "the range runs over the values, not the positions";
  EXPECT_EQ(row.max, 1.0);
  const OptionRow weather = choiceRow("Weather", "", 0, choicesOf(kWeather), { "S", "R", "N" });
  EXPECT_EQ(weather.min, 0.0);
  EXPECT_EQ(weather.max, 2.0);
}

TEST(OptionTable, ARowRefusesValuesOutsideItsRangeAndFractionsOfWholeNumbers)
{
  OptionRow count;
  count.property = "Count";
  count.type = OptionType::Integer;
  count.min = 1;
  count.max = 10;
  EXPECT_NO_THROW(count.checkValue(1, "--count"));
  EXPECT_NO_THROW(count.checkValue(10, "--count"));
  EXPECT_EQ(errorOf([&] { count.checkValue(11, "--count"); }),
    "--count expects a whole number from 1 to 10, not 11.");
  EXPECT_EQ(errorOf([&] { count.checkValue(2.5, "--count"); }),
    "--count expects a whole number from 1 to 10, not 2.5.");
  EXPECT_THROW(count.checkValue(0, "--count"), Error);

  OptionRow scale;
  scale.type = OptionType::Real;
  scale.min = 0.0;
  EXPECT_NO_THROW(scale.checkValue(2.5, "--scale"));
  EXPECT_NO_THROW(scale.checkValue(1.0e30, "--scale"));
  EXPECT_EQ(errorOf([&] { scale.checkValue(-0.5, "--scale"); }),
    "--scale expects a number at least 0, not -0.5.");
  EXPECT_THROW(scale.checkValue(std::nan(""), "--scale"), Error);
}

TEST(OptionTable, ARowIsFoundByItsProperty)
{
  std::vector<OptionRow> rows(2);
  rows[0].property = "A";
  rows[1].property = "B";
  EXPECT_EQ(&optionRow(rows, "B"), &rows[1]);
  EXPECT_THROW(optionRow(rows, "C"), Error);
}

} // namespace tsynth
