// Tests of Kernels/Features/Sketch.cxx: the feature graphs of drawn sketches, stroke maps and
// poly-lines.
#include "Core/Constants.h"
#include "Core/Error.h"
#include "Core/HeightfieldIO.h"
#include "Features/Sketch.h"
#include "TestData.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

using namespace tsynth;

TEST(Sketch, LambdaGivesItsBranchPointAndTheRing)
{
  const ColourImage img =
    readColourImage((test::bundledData() / "sketches" / "lambda_circle_grey.png").string());
  const SketchFeatures s = sketchFeatures(img);
  EXPECT_EQ(s.kind, SketchKind::Grey);
  EXPECT_NEAR(s.strokeWidth, 10.0, 3.0);
  // The lambda: one branch point where the short leg meets the long stroke
  // (pixel column 268, row 257 from the top, read off the image).
  ASSERT_EQ(s.graph.countKind(NodeKind::Branch, FeatureType::Ridge), 1);
  for (const FeatureNode& n : s.graph.nodes)
  {
    if (n.kind == NodeKind::Branch)
    {
      EXPECT_EQ(n.degree, 3);
      EXPECT_NEAR(n.position.x, 268.0, 6.0);
      EXPECT_NEAR(n.position.y, 511.0 - 257.0, 6.0);
    }
  }
  // The ring: one chain about 2 pi 200 pixels long whose two ends nearly touch.
  int rings = 0;
  for (const FeatureChain& c : s.graph.chains)
  {
    if (c.length() > 1000.0)
    {
      ++rings;
      EXPECT_NEAR(c.length(), 2 * kPi * 200.0, 80.0);
      const Point2& a = c.points.front();
      const Point2& b = c.points.back();
      EXPECT_LT(std::hypot(a.x - b.x, a.y - b.y), 12.0);
    }
  }
  EXPECT_EQ(rings, 1);
  // Three lambda ends and the two ends of the opened ring; no valleys.
  EXPECT_EQ(s.graph.countKind(NodeKind::End, FeatureType::Ridge), 5);
  EXPECT_EQ(s.graph.countKind(NodeKind::End, FeatureType::Valley), 0);
  EXPECT_EQ(s.graph.componentCount, 2);
}

TEST(Sketch, StrokeMapsGiveTheExpectedNodes)
{
  const SketchFeatures y = sketchFeatures(
    readColourImage((test::bundledData() / "sketches" / "strokes_y_ridges.png").string()));
  EXPECT_EQ(y.kind, SketchKind::Strokes);
  EXPECT_EQ(y.graph.countKind(NodeKind::Branch, FeatureType::Ridge), 1); // the Y's fork
  EXPECT_EQ(y.graph.countKind(NodeKind::End, FeatureType::Ridge), 3);
  EXPECT_EQ(y.graph.countKind(NodeKind::Branch, FeatureType::Valley), 0); // two separate blue lines
  EXPECT_EQ(y.graph.countKind(NodeKind::End, FeatureType::Valley), 4);
  EXPECT_EQ(y.graph.componentCount, 3);

  const SketchFeatures m = sketchFeatures(
    readColourImage((test::bundledData() / "sketches" / "strokes_valley_meander.png").string()));
  EXPECT_EQ(m.graph.countKind(NodeKind::End, FeatureType::Ridge), 16); // eight straight red strokes
  EXPECT_EQ(m.graph.countKind(NodeKind::Branch, FeatureType::Ridge), 0);
  EXPECT_EQ(m.graph.countKind(NodeKind::End, FeatureType::Valley), 2); // one meandering valley
  EXPECT_EQ(m.graph.countKind(NodeKind::Branch, FeatureType::Valley), 0);
  EXPECT_EQ(m.graph.componentCount, 9);
}

TEST(Sketch, ARingStrokeStaysALoop)
{
  ColourImage img;
  img.width = img.height = 200;
  img.channels = 3;
  img.data.assign(200 * 200 * 3, 255);
  for (int r = 0; r < 200; ++r)
  {
    for (int c = 0; c < 200; ++c)
    {
      const double d = std::hypot(c - 100.0, r - 100.0);
      if (d > 56 && d < 64)
      {
        std::uint8_t* p = img.data.data() + (r * 200 + c) * 3;
        p[0] = 230;
        p[1] = 20;
        p[2] = 20;
      }
    }
  }
  const SketchFeatures s = sketchFeatures(img);
  ASSERT_EQ(s.graph.nodes.size(), 1u); // a loop anchored at one path node
  EXPECT_EQ(s.graph.nodes[0].kind, NodeKind::Path);
  ASSERT_EQ(s.graph.chains.size(), 1u);
  EXPECT_EQ(s.graph.chains[0].from, s.graph.chains[0].to);
  EXPECT_NEAR(s.graph.chains[0].length(), 2 * kPi * 60.0, 20.0);
}

TEST(Sketch, BadSketchesAreExplained)
{
  ColourImage small;
  small.width = small.height = 50;
  small.channels = 3;
  small.data.assign(50 * 50 * 3, 255);
  try
  {
    sketchFeatures(small);
    FAIL() << "a 50 x 50 sketch was accepted";
  }
  catch (const Error& e)
  {
    EXPECT_NE(std::string(e.what()).find("smaller than one patch"), std::string::npos);
  }

  ColourImage blank = small;
  blank.width = blank.height = 128;
  blank.data.assign(128 * 128 * 3, 255);
  const SketchFeatures none = sketchFeatures(blank);
  EXPECT_TRUE(none.graph.empty());
  ASSERT_EQ(none.warnings.size(), 1u);

  ColourImage photo = blank;
  for (std::size_t k = 0; k < photo.data.size(); k += 3)
  {
    photo.data[k] = static_cast<std::uint8_t>(k % 251); // a colourful gradient, no strokes
    photo.data[k + 1] = 180;
    photo.data[k + 2] = 60;
  }
  EXPECT_THROW(sketchFeatures(photo), Error);
}

TEST(Sketch, PolylinesBecomeAGraphAsDrawn)
{
  // A Y drawn as three poly-lines sharing the junction (one snapped within tolerance),
  // a closed square loop, and one valley line with height constraints.
  std::vector<Polyline> lines(5);
  lines[0].points = { { 100, 20 }, { 100, 100 } };
  lines[1].points = { { 100.4, 100.3 }, { 50, 180 } };
  lines[2].points = { { 100, 100 }, { 150, 180 } };
  lines[3].points = { { 10, 10 }, { 40, 10 }, { 40, 40 }, { 10, 40 }, { 10, 10 } };
  lines[4].points = { { 200, 20 }, { 210, 100 }, { 220, 190 } };
  lines[4].elevation = { 300.0f, std::nanf(""), 200.0f };
  lines[4].type = FeatureType::Valley;
  const FeatureGraph g = polylineFeatures(lines, 256, 256, 30.0, 30.0, 1.0, 40.0);
  EXPECT_EQ(g.countKind(NodeKind::Branch, FeatureType::Ridge), 1);
  EXPECT_EQ(g.countKind(NodeKind::End, FeatureType::Ridge), 3);
  EXPECT_EQ(g.countKind(NodeKind::Path, FeatureType::Ridge), 1); // the square loop's anchor
  EXPECT_EQ(g.countKind(NodeKind::End, FeatureType::Valley), 2);
  EXPECT_EQ(g.componentCount, 3);
  bool constraintKept = false;
  for (const FeatureChain& c : g.chains)
  {
    if (c.type == FeatureType::Valley)
    {
      ASSERT_EQ(c.constraint.size(), 3u);
      EXPECT_TRUE(std::isnan(c.constraint[1]));
      constraintKept = (c.constraint.front() == 300.0f && c.constraint.back() == 200.0f) ||
        (c.constraint.front() == 200.0f && c.constraint.back() == 300.0f);
    }
  }
  EXPECT_TRUE(constraintKept);
}
