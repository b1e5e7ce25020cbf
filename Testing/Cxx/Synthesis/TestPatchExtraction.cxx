// Tests of Kernels/Synthesis/PatchExtraction.cxx.
// Kernels/Synthesis/PatchExtraction.h: the cut, the shift and the core of a
// patch, as the synthesis and the Terrain Patch Extractor make them.
#include "Features/ChainPointGrid.h"
#include "Features/FeatureGraph.h"
#include "Matching/Orientation.h"
#include "Synthesis/PatchExtraction.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numeric>
#include <vector>

namespace
{

// A 100 x 90 exemplar whose every height names its cell: 1000 x + y.
tsynth::Heightfield namedCells()
{
  tsynth::Heightfield ex(100, 90);
  for (int j = 0; j < ex.height; ++j)
  {
    for (int i = 0; i < ex.width; ++i)
    {
      ex.at(i, j) = static_cast<float>(1000 * i + j);
    }
  }
  return ex;
}

tsynth::PatchCandidate candidateAt(double x, double y, int variant)
{
  tsynth::PatchCandidate c;
  c.centreX = x;
  c.centreY = y;
  c.variant = variant;
  return c;
}

} // namespace

TEST(PatchExtraction, UnrotatedPatchIsTheExemplarWindowAndRotationsTurnIt)
{
  const tsynth::Heightfield ex = namedCells();
  const int P = 20;
  const tsynth::Heightfield straight = tsynth::extractPatch(ex, candidateAt(50, 40, 0), P);
  ASSERT_EQ(straight.width, P);
  EXPECT_FALSE(straight.hasMask());
  for (int j = 0; j < P; ++j)
  {
    for (int i = 0; i < P; ++i)
    {
      ASSERT_EQ(straight.at(i, j), 1000.0f * (40 + i) + (30 + j)) << i << ", " << j;
    }
  }
  // A quarter turn (variant 2) reads the same neighbourhood: every height an
  // exemplar cell's, the centre's near the candidate's centre, and rows of
  // the placed patch running along the exemplar's columns.
  const tsynth::Heightfield turned = tsynth::extractPatch(ex, candidateAt(50, 40, 2), P);
  EXPECT_FALSE(turned.hasMask());
  const float centre = turned.at(P / 2, P / 2);
  EXPECT_NEAR(std::floor(centre / 1000.0f), 50.0, 1.0);
  EXPECT_NEAR(std::fmod(centre, 1000.0f), 40.0, 1.0);
  EXPECT_EQ(std::abs(turned.at(1, 0) - turned.at(0, 0)), 1.0f);
  EXPECT_EQ(std::abs(turned.at(0, 1) - turned.at(0, 0)), 1000.0f);
}

TEST(PatchExtraction, CellsOffTheExemplarAreInvalid)
{
  const tsynth::Heightfield ex = namedCells();
  const tsynth::Heightfield corner = tsynth::extractPatch(ex, candidateAt(2, 2, 0), 20);
  ASSERT_TRUE(corner.hasMask());
  EXPECT_FALSE(corner.isValid(0, 0));                     // cell (-8, -8)
  EXPECT_TRUE(corner.isValid(19, 19));                    // cell (11, 11)
  EXPECT_EQ(corner.validCount(), std::size_t{ 12 * 12 }); // cells 0..11 each way
}

TEST(PatchExtraction, TheShiftFitsTheFilledOverlapElseTheTarget)
{
  const int P = 20;
  tsynth::Heightfield patch(P, P, 4.0f);
  tsynth::Heightfield terrain(60, 60, 10.0f);
  std::vector<std::uint8_t> filled(terrain.size(), 1);
  const tsynth::Heightfield noTarget;
  const std::vector<float> noConfidence;
  EXPECT_FLOAT_EQ(
    tsynth::fitPatchOffset(patch, 5, 5, { terrain, filled, noTarget, noConfidence }), 6.0f);
  // Nothing filled: the target's low-pass decides, weighed by its confidence.
  std::fill(filled.begin(), filled.end(), 0);
  EXPECT_EQ(tsynth::fitPatchOffset(patch, 5, 5, { terrain, filled, noTarget, noConfidence }), 0.0f);
  const tsynth::Heightfield target(60, 60, 7.0f);
  const std::vector<float> confidence(terrain.size(), 0.5f);
  EXPECT_FLOAT_EQ(
    tsynth::fitPatchOffset(patch, 5, 5, { terrain, filled, target, confidence }), 3.0f);
  // Half the window filled (at 10) and half empty (target 7, confidence 0.5):
  // least squares over both, the filled cells weighing twice as much.
  for (int j = 0; j < 60; ++j)
  {
    for (int i = 0; i < 15; ++i)
    {
      filled[terrain.index(i, j)] = 1;
    }
  }
  EXPECT_FLOAT_EQ(tsynth::fitPatchOffset(patch, 5, 5, { terrain, filled, target, confidence }),
    static_cast<float>((200 * 6.0 + 200 * 0.5 * 3.0) / (200 + 200 * 0.5)));
}

TEST(PatchExtraction, AFeaturePatchOwnsADiscAndTheLineWithinReach)
{
  const int P = 40;
  const std::vector<std::uint8_t> noLine;
  const std::vector<std::uint8_t> disc = tsynth::featureCore(noLine, 100, 100, 30, 30, P);
  const double discCells = std::accumulate(disc.begin(), disc.end(), 0.0);
  EXPECT_NEAR(discCells, M_PI * 5.0 * 5.0, 0.15 * M_PI * 5.0 * 5.0); // radius P / 8
  // A sketched line along row 50 (the patch's row 20): owned within P / 4 of the centre.
  std::vector<std::uint8_t> line(100 * 100, 0);
  for (int x = 0; x < 100; ++x)
  {
    line[static_cast<std::size_t>(50 * 100 + x)] = 1;
  }
  const std::vector<std::uint8_t> core = tsynth::featureCore(line, 100, 100, 30, 30, P);
  const auto at = [&](int i, int j) { return core[static_cast<std::size_t>(j * P + i)]; };
  EXPECT_EQ(at(20 + 9, 20), 1);  // on the line, 9.5 cells from the centre
  EXPECT_EQ(at(20 + 11, 20), 0); // on the line, past a quarter patch
  EXPECT_EQ(at(20, 20 + 8), 0);  // off the line, past the disc
  EXPECT_EQ(std::accumulate(core.begin(), core.end(), 0.0), discCells + 20 - 10);
}

TEST(PatchExtraction, AFillPatchKeepsOutOfFilledLinesAndFrozenCells)
{
  // An 8 x 8 output with a line along row 3 (filled except at column 4) and a
  // frozen cell at (6, 5); a 4 x 4 patch placed at (3, 2) covers columns 3-6,
  // rows 2-5.
  const int w = 8, h = 8;
  std::vector<std::uint8_t> line(w * h, 0), frozen(w * h, 0), filled(w * h, 1);
  for (int i = 0; i < w; ++i)
  {
    line[3 * w + i] = 1;
  }
  filled[3 * w + 4] = 0;
  frozen[5 * w + 6] = 1;
  tsynth::Heightfield patch(4, 4, 10.0f);
  tsynth::protectKeptCells(patch, 3, 2, { line, frozen, filled, w, h });
  ASSERT_TRUE(patch.hasMask());
  for (int j = 0; j < 4; ++j)
  {
    for (int i = 0; i < 4; ++i)
    {
      const int x = 3 + i, y = 2 + j;
      const bool kept = (y == 3 && x != 4) || (x == 6 && y == 5);
      EXPECT_EQ(patch.isValid(i, j), !kept) << x << ", " << y;
      EXPECT_EQ(std::isnan(patch.at(i, j)), kept) << x << ", " << y;
    }
  }
  // Nothing kept under it: the patch stays without a mask.
  tsynth::Heightfield clear(4, 4, 10.0f);
  tsynth::protectKeptCells(clear, 0, 5, { line, {}, filled, w, h });
  EXPECT_FALSE(clear.hasMask());
  // Past the grid's edge nothing is read.
  tsynth::Heightfield over(4, 4, 10.0f);
  tsynth::protectKeptCells(over, 6, -2, { line, frozen, filled, w, h });
  EXPECT_FALSE(over.hasMask());
}

TEST(PatchExtraction, AFeaturePatchOwnsAStripAlongItsOwnLineTurnedByItsVariant)
{
  // An exemplar ridge along y = 50 from x = 0 to 100 and a valley along x = 10;
  // a candidate centred on the ridge at (50, 50), patch 40 (reach 10 cells).
  tsynth::FeatureGraph g;
  g.width = 100;
  g.height = 100;
  g.nodes.resize(4);
  tsynth::FeatureChain ridge;
  ridge.type = tsynth::FeatureType::Ridge;
  tsynth::FeatureChain valley;
  valley.type = tsynth::FeatureType::Valley;
  for (int x = 0; x <= 100; ++x)
  {
    ridge.points.push_back({ static_cast<double>(x), 50.0 });
    valley.points.push_back({ 10.0, static_cast<double>(x) });
  }
  g.chains = { ridge, valley };
  const tsynth::ChainPointGrid lines(g, 10.0);
  tsynth::PatchCandidate c;
  c.centreX = 50.0;
  c.centreY = 50.0;
  c.variant = 0;
  const std::vector<tsynth::Point2> same =
    tsynth::ownLineOffsets(lines, tsynth::FeatureType::Ridge, c, 40);
  ASSERT_EQ(same.size(), 21u) << "x = 40 to 60: within 10 cells of the centre";
  for (const tsynth::Point2& q : same)
  {
    EXPECT_NEAR(q.y, 0.0, 1e-12);
    EXPECT_LE(std::abs(q.x), 10.0);
  }
  EXPECT_TRUE(tsynth::ownLineOffsets(lines, tsynth::FeatureType::Valley, c, 40).empty())
    << "the valley is 40 cells off";
  // A quarter turn (variant 2) lays the ridge across: offsets along y.
  c.variant = 2;
  for (const tsynth::Point2& q : tsynth::ownLineOffsets(lines, tsynth::FeatureType::Ridge, c, 40))
  {
    EXPECT_NEAR(q.x, 0.0, 1e-9);
  }
  // The strip: 3 cells each side of the offsets, round the patch's centre cell (20, 20).
  std::vector<std::uint8_t> core(40 * 40, 0);
  tsynth::addOwnLineStrip(core, same, 40);
  EXPECT_EQ(core[20 * 40 + 20], 1);
  EXPECT_EQ(core[23 * 40 + 10], 1) << "3 cells above the line";
  EXPECT_EQ(core[24 * 40 + 20], 0) << "4 cells above it";
  EXPECT_EQ(core[20 * 40 + 33], 1) << "3 past the last offset";
  EXPECT_EQ(core[20 * 40 + 34], 0);
}
