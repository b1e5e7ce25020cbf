// Tests of Kernels/Distance/DistanceSources.cxx.
// What tsynth distance and the Terrain Distance Synthesis filter read, made
// into the synthesis' inputs: generators from a stroke map or lines, and every
// input that cannot be used refused in one sentence or said in a warning.
#include "Distance/DistanceSources.h"
#include "ErrorOf.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

using namespace tsynth;

namespace
{

// A white RGB image with a red ridge stroke along row `ridgeRow` and, with
// `valleyRow` >= 0, a blue valley stroke along it.
ColourImage strokeMap(int width, int height, int ridgeRow, int valleyRow = -1)
{
  ColourImage image;
  image.width = width;
  image.height = height;
  image.channels = 3;
  image.data.assign(static_cast<std::size_t>(width * height * 3), 255);
  auto paint = [&](int row, std::uint8_t r, std::uint8_t g, std::uint8_t b)
  {
    for (int i = 2; i < width - 2; ++i)
    {
      std::uint8_t* p = image.data.data() + (static_cast<std::size_t>(row) * width + i) * 3;
      p[0] = r;
      p[1] = g;
      p[2] = b;
    }
  };
  paint(ridgeRow, 255, 0, 0);
  if (valleyRow >= 0)
  {
    paint(valleyRow, 0, 0, 255);
  }
  return image;
}

} // namespace

TEST(DistanceSources, AStrokeMapGivesItsGridAndItsRidgesAndSaysValleysAreIgnored)
{
  const ColourImage strokes = strokeMap(40, 30, 10, 20);
  DistanceSources s;
  s.strokes = &strokes;
  std::vector<std::string> warnings;
  const DistanceInputs in = assembleDistanceInputs(s, warnings);
  EXPECT_EQ(in.width, 40);
  EXPECT_EQ(in.height, 30);
  EXPECT_FALSE(in.features.empty());
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("36 blue valley pixels are ignored"), std::string::npos)
    << warnings[0];
}

TEST(DistanceSources, LinesNeedAGridOfTheirOwn)
{
  const std::vector<GeneratorLine> lines = { { { { 2, 2 }, { 20, 12 } }, { 0.0f, 0.0f } } };
  DistanceSources s;
  s.lines = &lines;
  std::vector<std::string> warnings;
  EXPECT_NE(test::errorOf([&] { assembleDistanceInputs(s, warnings); })
              .find("need a grid of two positive numbers of cells"),
    std::string::npos);
  s.width = 32;
  s.height = 16;
  const DistanceInputs in = assembleDistanceInputs(s, warnings);
  EXPECT_EQ(in.width, 32);
  EXPECT_EQ(in.features.size(), 1u);
}

TEST(DistanceSources, WhatCannotBeUsedIsRefusedInOneSentence)
{
  std::vector<std::string> warnings;
  EXPECT_NE(test::errorOf([&] { assembleDistanceInputs(DistanceSources{}, warnings); })
              .find("There are no generators"),
    std::string::npos);
  const ColourImage strokes = strokeMap(40, 30, 10);
  const ColourImage small = strokeMap(20, 30, 10);
  DistanceSources s;
  s.strokes = &strokes;
  s.edgeWeights = &small;
  EXPECT_NE(test::errorOf([&] { assembleDistanceInputs(s, warnings); })
              .find("is 20x30 but the generators' grid is 40x30"),
    std::string::npos);
  s.edgeWeights = nullptr;
  s.regionProfile = 2;
  EXPECT_NE(test::errorOf([&] { assembleDistanceInputs(s, warnings); })
              .find("The region profile 2 does not exist; there are 0 profiles."),
    std::string::npos);
}
