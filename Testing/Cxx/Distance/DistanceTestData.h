// Helpers shared by the distance synthesis tests (tsynth_distance_tests): point generators,
// deterministic options and the check of an error's words.
#pragma once

#include "Core/Error.h"
#include "Distance/DistanceSynthesis.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <functional>
#include <string>

namespace tsynth::test::distance
{

inline std::int32_t cellOf(int col, int row, int width)
{
  return static_cast<std::int32_t>(row * width + col);
}

inline DistanceFeature point(int col, int row, int width, float cost, int profile = kNoProfile)
{
  DistanceFeature f;
  f.nodes.push_back({ cellOf(col, row, width), cost, profile });
  return f;
}

// Deterministic options: no weight noise, heights in cost units.
inline DistanceOptions plainOptions()
{
  DistanceOptions o;
  o.roughness = 0.0;
  o.heightScale = 1.0;
  o.cellSize = 1.0;
  return o;
}

inline void expectThrowsWith(const std::function<void()>& call, const std::string& words)
{
  try
  {
    call();
    FAIL() << "expected an error mentioning \"" << words << "\"";
  }
  catch (const Error& e)
  {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

} // namespace tsynth::test::distance
