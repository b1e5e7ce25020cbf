// Tests of Kernels/Synthesis/Regions.cxx.
// A label image chooses the exemplars of each region: resampled nearest onto
// the output, mapped by "L=E1,E2", a label unmapped served by exemplar L, and
// every malformed or impossible map refused in one sentence.
#include "ErrorOf.h"
#include "Synthesis/Regions.h"

#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <vector>

using namespace tsynth;

namespace
{

// A 2 x 2 label image: 0 and 1 on top, 2 and nodata below.
Heightfield quadrants()
{
  Heightfield labels(2, 2);
  labels.z = { 0.0f, 1.0f, 2.0f, std::numeric_limits<float>::quiet_NaN() };
  normaliseMask(labels);
  return labels;
}

} // namespace

TEST(Regions, LabelsAreResampledNearestOntoTheOutput)
{
  SynthesisOptions o;
  assignRegions(o, quadrants(), {}, 4, 4, 3);
  // Each label cell covers 2 x 2 output cells; nodata becomes -1.
  EXPECT_EQ(
    o.regionLabels, std::vector<int>({ 0, 0, 1, 1, 0, 0, 1, 1, 2, 2, -1, -1, 2, 2, -1, -1 }));
}

TEST(Regions, MapsChooseExemplarsAndAnUnmappedLabelTakesItsOwnNumber)
{
  SynthesisOptions o;
  assignRegions(o, quadrants(), { "0=2,1", "2=0" }, 4, 4, 3);
  ASSERT_EQ(o.regionExemplars.size(), 3u);
  EXPECT_EQ(o.regionExemplars[0], std::vector<int>({ 2, 1 }));
  EXPECT_EQ(o.regionExemplars[1], std::vector<int>({ 1 })) << "label 1 is served by exemplar 1";
  EXPECT_EQ(o.regionExemplars[2], std::vector<int>({ 0 }));
}

TEST(Regions, BadMapsAreRefusedInOneSentence)
{
  const Heightfield labels = quadrants();
  auto refusal = [&](const std::vector<std::string>& maps, std::size_t exemplars)
  {
    SynthesisOptions o;
    return test::errorOf([&] { assignRegions(o, labels, maps, 4, 4, exemplars); });
  };
  EXPECT_NE(refusal({ "0:1" }, 3).find("LABEL=E1,E2"), std::string::npos);
  EXPECT_NE(refusal({ "7=1" }, 3).find("present in the region image"), std::string::npos);
  EXPECT_NE(refusal({ "0=1,x" }, 3).find("exemplar numbers run from 0 to 2"), std::string::npos);
  EXPECT_NE(refusal({ "0=3" }, 3).find("exemplar numbers run from 0 to 2"), std::string::npos);
  // Label 2 is in use, unmapped, and there is no exemplar 2.
  EXPECT_NE(refusal({}, 2).find("Region label 2 has no exemplar"), std::string::npos);
  EXPECT_EQ(refusal({ "2=0" }, 2), "");
}
