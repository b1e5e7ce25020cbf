// Tests of Kernels/Distance/Generators.cxx: generators from a stroke map and their default costs.
#include "Distance/DistanceSynthesis.h"
#include "Distance/Generators.h"
#include "DistanceTestData.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

using namespace tsynth;

namespace
{

using tsynth::test::distance::cellOf;
using tsynth::test::distance::expectThrowsWith;
using tsynth::test::distance::point;

TEST(DistanceSynthesis, GeneratorsFromAStrokeMap)
{
  ColourImage image;
  image.width = 30;
  image.height = 20;
  image.channels = 3;
  image.data.assign(30 * 20 * 3, 255);
  auto paint = [&](int col, int rowFromTop, std::uint8_t r)
  {
    std::uint8_t* p = image.data.data() + (rowFromTop * 30 + col) * 3;
    p[0] = r;
    p[1] = 0;
    p[2] = 0;
  };
  for (int col = 2; col < 10; ++col)
  {
    paint(col, 15, 255); // a bright red line near the bottom (south)
  }
  for (int col = 20; col < 28; ++col)
  {
    paint(col, col - 18, 210); // a darker red diagonal near the top
  }
  StrokeGenerators g = generatorsFromStrokes(image, 2, ProfileAssignment::ByColour);
  ASSERT_EQ(g.features.size(), 2u);
  EXPECT_EQ(g.colours, 2);
  EXPECT_EQ(g.features[0].nodes.size(), 8u); // scan order from the south
  EXPECT_EQ(g.features[0].nodes[0].cell, cellOf(2, 4, 30));
  EXPECT_EQ(g.features[0].nodes[0].profile, 1); // (255,0,0) sorts after (210,0,0)
  EXPECT_EQ(g.features[1].nodes[0].profile, 0);
  g = generatorsFromStrokes(image, 2, ProfileAssignment::ByFeature);
  EXPECT_EQ(g.features[1].nodes[0].profile, 1);
  ColourImage labels;
  labels.width = 30;
  labels.height = 20;
  labels.channels = 1;
  labels.data.assign(600, 1);
  g = generatorsFromStrokes(image, 2, ProfileAssignment::ByColour, &labels);
  EXPECT_EQ(g.features[0].nodes[0].profile, 1);
  labels.data.assign(600, 2);
  expectThrowsWith([&] { generatorsFromStrokes(image, 2, ProfileAssignment::ByColour, &labels); },
    "names profile 2");
  labels.width = 29;
  expectThrowsWith([&] { generatorsFromStrokes(image, 2, ProfileAssignment::ByColour, &labels); },
    "label image is 29x20");
  image.data.assign(30 * 20 * 3, 255);
  expectThrowsWith(
    [&] { generatorsFromStrokes(image, 2, ProfileAssignment::ByColour); }, "no red ridge strokes");
}

TEST(DistanceSynthesis, DefaultCostsComeFromFbm)
{
  const std::vector<float> c = fbmCosts(64, 64, FbmOptions{}, 7);
  EXPECT_FLOAT_EQ(*std::min_element(c.begin(), c.end()), 0.0f);
  EXPECT_FLOAT_EQ(*std::max_element(c.begin(), c.end()), 30.0f);
  EXPECT_EQ(c, fbmCosts(64, 64, FbmOptions{}, 7));
  EXPECT_NE(c, fbmCosts(64, 64, FbmOptions{}, 8));
  DistanceInputs in;
  in.width = 64;
  in.height = 64;
  in.features = { point(10, 10, 64, NAN), point(50, 40, 64, NAN) };
  DistanceOptions o;
  o.seed = 7;
  const DistanceTerrain t = synthesiseByDistance(in, o);
  EXPECT_FLOAT_EQ(
    static_cast<float>(t.maxGeneratorCost), std::max(c[cellOf(10, 10, 64)], c[cellOf(50, 40, 64)]));
}

} // namespace
