// Tests of Kernels/Features/ImpliedLines.cxx: the lines of the other type implied between two
// strokes.
#include "Features/FeatureGraph.h"
#include "Features/ImpliedLines.h"
#include "Features/Sketch.h"
#include "Features/StrokeSpacing.h"

#include <gtest/gtest.h>

#include <array>
#include <limits>
#include <utility>
#include <vector>

using namespace tsynth;

namespace
{

// Straight strokes (x0, y0) -> (x1, y1) of the given types as a graph on w x h.
FeatureGraph drawnLines(int w,
  int h,
  const std::vector<std::array<double, 4>>& ends,
  const std::vector<FeatureType>& types)
{
  std::vector<Polyline> lines;
  for (std::size_t k = 0; k < ends.size(); ++k)
  {
    Polyline p;
    p.points = { { ends[k][0], ends[k][1] }, { ends[k][2], ends[k][3] } };
    p.type = types[k];
    lines.push_back(p);
  }
  return polylineFeatures(lines, w, h, 1.0, 1.0);
}

FeatureGraph implied(const FeatureGraph& drawn, const ImpliedLineOptions& o = {})
{
  const StrokeSpacing s =
    strokeSpacing(rasteriseChains(drawn, drawn.width, drawn.height), drawn.width, drawn.height);
  return impliedLines(drawn, s, o);
}

// Total length (cells) of a graph's chains of one type, and their mean row.
std::pair<double, double> lengthAndMeanRow(const FeatureGraph& g, FeatureType type)
{
  double length = 0.0, rows = 0.0, points = 0.0;
  for (const FeatureChain& c : g.chains)
  {
    if (c.type != type)
    {
      continue;
    }
    length += c.length();
    for (const Point2& p : c.points)
    {
      rows += p.y;
      points += 1.0;
    }
  }
  return { length, points > 0.0 ? rows / points : std::numeric_limits<double>::quiet_NaN() };
}

} // namespace

TEST(ImpliedLines, TwoValleysArePartedByARidgeAndTwoRidgesByAValley)
{
  const int w = 160, h = 100;
  for (FeatureType drawnType : { FeatureType::Valley, FeatureType::Ridge })
  {
    // Two strokes 40 cells apart, 120 long: the line between them runs
    // halfway, at row 50, of the other type, their whole length and a little
    // beyond their ends (where the two ends still face each other: about 18
    // cells at kFacingRatio 1.5), not more.
    const FeatureGraph g =
      drawnLines(w, h, { { 20, 30, 140, 30 }, { 20, 70, 140, 70 } }, { drawnType, drawnType });
    const FeatureGraph i = implied(g);
    const FeatureType other =
      drawnType == FeatureType::Valley ? FeatureType::Ridge : FeatureType::Valley;
    const auto [length, row] = lengthAndMeanRow(i, other);
    EXPECT_GT(length, 120.0);
    EXPECT_LT(length, 160.0);
    EXPECT_NEAR(row, 50.0, 1.5);
    EXPECT_EQ(lengthAndMeanRow(i, drawnType).first, 0.0);
    EXPECT_FALSE(i.bfsOrder.empty());
  }
}

TEST(ImpliedLines, TwoRidgesGetATroughUnlessTurnedOff)
{
  const FeatureGraph g = drawnLines(160,
    100,
    { { 20, 30, 140, 30 }, { 20, 70, 140, 70 } },
    { FeatureType::Ridge, FeatureType::Ridge });
  EXPECT_GT(lengthAndMeanRow(implied(g), FeatureType::Valley).first, 120.0);
  ImpliedLineOptions divides;
  divides.troughs = false;
  EXPECT_TRUE(implied(g, divides).chains.empty());
}

TEST(ImpliedLines, NoneBetweenARidgeAndAValleyFarApartOrAtABend)
{
  const int w = 160, h = 240;
  // A valley facing a ridge: one slope joins them.
  EXPECT_TRUE(implied(drawnLines(w,
                        h,
                        { { 20, 30, 140, 30 }, { 20, 70, 140, 70 } },
                        { FeatureType::Valley, FeatureType::Ridge }))
                .chains.empty());
  // Two valleys 200 cells apart, farther than maxDistance (80) from the line
  // between them: free land.
  EXPECT_TRUE(implied(drawnLines(w,
                        h,
                        { { 20, 20, 140, 20 }, { 20, 220, 140, 220 } },
                        { FeatureType::Valley, FeatureType::Valley }))
                .chains.empty());
  // ... but with room enough they are parted.
  ImpliedLineOptions farther;
  farther.maxDistance = 120.0;
  EXPECT_FALSE(implied(drawnLines(w,
                         h,
                         { { 20, 20, 140, 20 }, { 20, 220, 140, 220 } },
                         { FeatureType::Valley, FeatureType::Valley }),
    farther)
                 .chains.empty());
  // A right-angle bend of one valley (an L) is one stroke, not two facing ones.
  EXPECT_TRUE(implied(drawnLines(w,
                        h,
                        { { 20, 20, 140, 20 }, { 20, 20, 20, 200 } },
                        { FeatureType::Valley, FeatureType::Valley }))
                .chains.empty());
}
