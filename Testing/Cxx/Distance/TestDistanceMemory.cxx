// Tests of Kernels/Distance/DistanceMemory.cxx: the distance synthesis' memory estimate, refused
// before any work with the estimate in the message.
#include "Core/MemoryTestData.h"
#include "Distance/DistanceMemory.h"
#include "Distance/DistanceSynthesis.h"
#include "ErrorOf.h"

#include <gtest/gtest.h>
#include <omp.h>

#include <string>

using namespace tsynth;
using tsynth::test::memory::about;

namespace
{

using tsynth::test::errorOf;

} // namespace

TEST(MemoryBudget, DistanceSynthesisIsRefusedBeforeAnyWork)
{
  const double one = distanceMemoryEstimate(1024, 1024, 1);
  EXPECT_NEAR(one, 128.0e6 + 108.0 * 1024 * 1024, 1.0);
  EXPECT_NEAR(distanceMemoryEstimate(1024, 1024, 4) - one, 3.0 * 8.0 * 1024 * 1024, 1.0);
  DistanceInputs in;
  in.width = 300;
  in.height = 200;
  DistanceFeature f;
  f.nodes.push_back({ 100 * 300 + 150, 1.0f, kNoProfile });
  in.features.push_back(f);
  DistanceOptions o;
  o.memoryBudget = 1.0e5;
  o.memoryOption = "--max-memory";
  o.sizeOption = "--size";
  bool progressed = false;
  o.progress = [&](double, const std::string&) { progressed = true; };
  const std::string m = errorOf([&] { synthesiseByDistance(in, o); });
  EXPECT_NE(m.find("This distance synthesis of 300 x 200 cells " +
              about(distanceMemoryEstimate(300, 200, omp_get_max_threads())) +
              "0.1 MB; give a smaller --size, or raise --max-memory."),
    std::string::npos)
    << m;
  EXPECT_FALSE(progressed);
  o.memoryBudget = 0.0;
  EXPECT_EQ(synthesiseByDistance(in, o).heights.width, 300);
}
