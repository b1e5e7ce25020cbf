// Tests of Kernels/Distance/Profile.cxx: monotone cross-section profiles, their fit and their
// reach.
#include "Core/Error.h"
#include "Distance/Profile.h"
#include "ErrorOf.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

using namespace tsynth;

namespace
{

using tsynth::test::errorOf;

bool contains(const std::string& text, const std::string& part)
{
  return text.find(part) != std::string::npos;
}

} // namespace

TEST(MonotoneProfile, FromPointsNamesTheOffendingPoint)
{
  std::string m = errorOf([] { MonotoneProfile::fromPoints({ 0.0, -5.0, 10.0 }, { 0, 1, 2 }); });
  EXPECT_TRUE(contains(m, "point 2 (-5, 1)")) << m;
  m = errorOf([] { MonotoneProfile::fromPoints({ -1.0, 5.0 }, { 0, 1 }); });
  EXPECT_TRUE(contains(m, "point 1")) << m;
  m = errorOf([] { MonotoneProfile::fromPoints({ 0.0, 10.0, 10.0 }, { 0, 1, 2 }); });
  EXPECT_TRUE(contains(m, "point 3 (10, 2)")) << m;
  EXPECT_TRUE(contains(m, "increase")) << m;
  m = errorOf([] { MonotoneProfile::fromPoints({ 0.0, 10.0, 5.0 }, { 0, 1, 2 }); });
  EXPECT_TRUE(contains(m, "point 3")) << m;
  // Up, level, then down: the fall at point 4 is the offence.
  m = errorOf([] { MonotoneProfile::fromPoints({ 0, 10, 20, 30 }, { 0, 5, 5, 3 }); });
  EXPECT_TRUE(contains(m, "point 4 (30, 3)")) << m;
  EXPECT_TRUE(contains(m, "turns down after going up")) << m;
  m = errorOf([] { MonotoneProfile::fromPoints({ 0, 10, 20 }, { 0, -5, 1 }); });
  EXPECT_TRUE(contains(m, "point 3")) << m;
  EXPECT_TRUE(contains(m, "turns up after going down")) << m;
  m = errorOf([] { MonotoneProfile::fromPoints({ 0, 10 }, { 0, std::nan("") }); });
  EXPECT_TRUE(contains(m, "point 2")) << m;
  EXPECT_FALSE(errorOf([] { MonotoneProfile::fromPoints({ 0, 1 }, { 0 }); }).empty());
  EXPECT_FALSE(errorOf([] { MonotoneProfile::fromPoints({}, {}); }).empty());
  // Level stretches are monotone either way.
  EXPECT_NO_THROW(MonotoneProfile::fromPoints({ 0, 10, 20, 30 }, { 4, 4, 1, 1 }));
  EXPECT_NO_THROW(MonotoneProfile::fromPoints({ 2.5 }, { 7 }));
}

TEST(MonotoneProfile, FitIsThePoolAdjacentViolatorsSolution)
{
  std::string m;
  // Rising fit of 5, 1, 2, 0, 6 with weights 1, 2, 1, 1, 1: 5 pools with 1
  // (7/3), then with 2 (9/4), then with 0 (9/5); 6 stays.
  const std::vector<double> d = { 0, 10, 20, 30, 40 };
  const std::vector<double> w = { 1, 2, 1, 1, 1 };
  const MonotoneProfile up =
    MonotoneProfile::fit(d, { 5, 1, 2, 0, 6 }, w, Monotonicity::NonDecreasing);
  const std::vector<double> expected = { 1.8, 1.8, 1.8, 1.8, 6.0 };
  ASSERT_EQ(up.values().size(), expected.size());
  for (std::size_t k = 0; k < expected.size(); ++k)
  {
    EXPECT_NEAR(up.values()[k], expected[k], 1e-12) << k;
  }
  EXPECT_EQ(up.distances(), d);
  // The falling fit of the negated data is the negated solution.
  const MonotoneProfile down =
    MonotoneProfile::fit(d, { -5, -1, -2, 0, -6 }, w, Monotonicity::NonIncreasing);
  for (std::size_t k = 0; k < expected.size(); ++k)
  {
    EXPECT_NEAR(down.values()[k], -expected[k], 1e-12) << k;
  }
  // 1, 3, 2, 4, 3.5, 5 unweighted: two separate pools (2.5 and 3.75).
  const MonotoneProfile two = MonotoneProfile::fit({ 0, 1, 2, 3, 4, 5 },
    { 1, 3, 2, 4, 3.5, 5 },
    { 1, 1, 1, 1, 1, 1 },
    Monotonicity::NonDecreasing);
  const std::vector<double> twoExpected = { 1, 2.5, 2.5, 3.75, 3.75, 5 };
  for (std::size_t k = 0; k < twoExpected.size(); ++k)
  {
    EXPECT_NEAR(two.values()[k], twoExpected[k], 1e-12) << k;
  }
  // Zero weights and NaN values drop out, distances and all.
  const MonotoneProfile dropped = MonotoneProfile::fit({ 0, 1, 2, 3, 4 },
    { 3, 1000, 1, std::nan(""), 2 },
    { 1, 0, 1, 1, 2 },
    Monotonicity::NonDecreasing);
  EXPECT_EQ(dropped.distances(), (std::vector<double>{ 0, 2, 4 }));
  // 3 and 1 pool to 2, then 2 (weight 2) with it: 2 everywhere.
  for (double v : dropped.values())
  {
    EXPECT_NEAR(v, 2.0, 1e-12);
  }
  // Bad input is an error, not a read past the end.
  EXPECT_THROW(
    MonotoneProfile::fit({ 0, 1, 2 }, { 1, 2, 3 }, { 1, 1 }, Monotonicity::NonDecreasing), Error);
  EXPECT_THROW(
    MonotoneProfile::fit({ 0, 1, 2 }, { 1, 2 }, { 1, 1, 1 }, Monotonicity::NonDecreasing), Error);
  m = errorOf(
    [] {
      MonotoneProfile::fit({ 0, 2, 1 }, { 1, 2, 3 }, { 1, 1, 1 }, Monotonicity::NonDecreasing);
    });
  EXPECT_TRUE(contains(m, "sample 3")) << m;
  // Monotone data come back unchanged.
  const MonotoneProfile same =
    MonotoneProfile::fit({ 0, 5, 9 }, { 10, 7, -2 }, { 3, 1, 1 }, Monotonicity::NonIncreasing);
  EXPECT_EQ(same.values(), (std::vector<double>{ 10, 7, -2 }));
}

TEST(MonotoneProfile, EvaluationReachAndNormalised)
{
  // A ridge falling 100 m over 600 m, steepest between 100 and 300 m.
  const MonotoneProfile p =
    MonotoneProfile::fromPoints({ 0, 100, 300, 600 }, { 0, -20, -80, -100 });
  EXPECT_DOUBLE_EQ(p(-50), 0.0);
  EXPECT_DOUBLE_EQ(p(50), -10.0);
  EXPECT_DOUBLE_EQ(p(200), -50.0);
  EXPECT_DOUBLE_EQ(p(450), -90.0);
  EXPECT_DOUBLE_EQ(p(1e6), -100.0);
  EXPECT_DOUBLE_EQ(p.length(), 600.0);
  EXPECT_DOUBLE_EQ(p.reach(0.0), 0.0);
  EXPECT_DOUBLE_EQ(p.reach(0.2), 100.0);
  EXPECT_DOUBLE_EQ(p.reach(0.5), 200.0);
  EXPECT_DOUBLE_EQ(p.reach(0.9), 450.0);
  EXPECT_DOUBLE_EQ(p.reach(1.0), 600.0);
  const MonotoneProfile n = p.normalised();
  EXPECT_EQ(n.distances(), p.distances());
  const std::vector<double> shape = { 0.0, 0.2, 0.8, 1.0 };
  for (std::size_t k = 0; k < shape.size(); ++k)
  {
    EXPECT_NEAR(n.values()[k], shape[k], 1e-15) << k;
  }
  // A valley (rising) with a level start: the reach counts from the start of
  // the change, its smallest distance.
  const MonotoneProfile v = MonotoneProfile::fromPoints({ 0, 50, 150, 250 }, { 5, 5, 35, 45 });
  EXPECT_DOUBLE_EQ(v.reach(0.0), 0.0);
  EXPECT_DOUBLE_EQ(v.reach(0.5), 50.0 + 100.0 * 20.0 / 30.0);
  EXPECT_DOUBLE_EQ(v.reach(0.75), 150.0);
  EXPECT_NEAR(v.normalised()(100.0), 0.375, 1e-15);
  // Constant and empty profiles.
  const MonotoneProfile flat = MonotoneProfile::fromPoints({ 0, 10 }, { 3, 3 });
  EXPECT_DOUBLE_EQ(flat.reach(0.9), 0.0);
  const MonotoneProfile flatShape = flat.normalised();
  for (double x : flatShape.values())
  {
    EXPECT_EQ(x, 0.0);
  }
  const MonotoneProfile none;
  EXPECT_TRUE(none.empty());
  EXPECT_DOUBLE_EQ(none(12.0), 0.0);
  EXPECT_DOUBLE_EQ(none.reach(0.5), 0.0);
}
