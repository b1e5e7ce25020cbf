// Tests of Kernels/Synthesis/FillOrder.cxx.
// The fill's windows and the order it visits them in (Synthesis/FillOrder),
// on a mask of filled cells that stands in for the output.
#include "Synthesis/FillOrder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

using namespace tsynth;

namespace
{

constexpr int kPatch = 32;

// The output as the fill sees it: which cells are filled. A window's fill
// fills its square; cells marked `never` no patch can cover.
struct Mask
{
  int width;
  int height;
  std::vector<std::uint8_t> filled;
  std::vector<std::uint8_t> never;
  std::vector<std::pair<int, int>> visits;

  Mask(int w, int h)
    : width(w)
    , height(h)
    , filled(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), 0)
    , never(filled.size(), 0)
  {
  }
  std::size_t at(int i, int j) const
  {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(width) +
      static_cast<std::size_t>(i);
  }
  double share(int x0, int y0) const
  {
    std::size_t known = 0;
    std::size_t cells = 0;
    for (int j = y0; j < std::min(height, y0 + kPatch); ++j)
    {
      for (int i = x0; i < std::min(width, x0 + kPatch); ++i)
      {
        known += filled[at(i, j)];
        ++cells;
      }
    }
    return cells > 0 ? static_cast<double>(known) / static_cast<double>(cells) : 1.0;
  }
  std::size_t fill(int x0, int y0)
  {
    visits.emplace_back(x0, y0);
    std::size_t wrote = 0;
    for (int j = y0; j < std::min(height, y0 + kPatch); ++j)
    {
      for (int i = x0; i < std::min(width, x0 + kPatch); ++i)
      {
        if (filled[at(i, j)] == 0 && never[at(i, j)] == 0)
        {
          filled[at(i, j)] = 1;
          ++wrote;
        }
      }
    }
    return wrote;
  }
  FillSteps steps(std::vector<double>* progress = nullptr)
  {
    FillSteps s;
    s.filledShare = [this](int x0, int y0) { return share(x0, y0); };
    s.fillWindow = [this](int x0, int y0) { return fill(x0, y0); };
    if (progress != nullptr)
    {
      s.progress = [progress](double f) { progress->push_back(f); };
    }
    return s;
  }
};

} // namespace

TEST(FillOrder, WindowsAreFlushWithTheEdgesAndOverlapByAQuarterPatch)
{
  for (std::uint64_t seed : { 0u, 1u, 2u })
  {
    const FillGrid g = fillGrid(300, 200, kPatch, kDefaultFillSpacing, seed);
    for (const std::vector<int>* line : { &g.xs, &g.ys })
    {
      const int last = line == &g.xs ? 300 - kPatch : 200 - kPatch;
      ASSERT_GE(line->size(), 2u);
      EXPECT_EQ(line->front(), 0);
      EXPECT_EQ(line->back(), last);
      for (std::size_t k = 1; k < line->size(); ++k)
      {
        const int step = (*line)[k] - (*line)[k - 1];
        EXPECT_GT(step, 0) << k;
        EXPECT_LE(step, kPatch - kMinFillOverlapInPatches * kPatch) << seed << ", " << k;
      }
    }
  }
  // The seed moves the inner windows; the same seed, the same windows.
  EXPECT_EQ(fillGrid(300, 200, kPatch, 0.5, 4).xs, fillGrid(300, 200, kPatch, 0.5, 4).xs);
  EXPECT_NE(fillGrid(300, 200, kPatch, 0.5, 4).xs, fillGrid(300, 200, kPatch, 0.5, 5).xs);
  // Spaced as wide as they may be, no room to move: evenly spaced.
  const std::vector<int> wide = fillGridLine(300, kPatch, kMaxFillSpacing, 4, 0);
  for (std::size_t k = 1; k < wide.size(); ++k)
  {
    EXPECT_NEAR(wide[k] - wide[k - 1], wide[1] - wide[0], 1) << k;
  }
  // A side no longer than a patch: one window.
  EXPECT_EQ(fillGridLine(kPatch, kPatch, 0.5, 0, 0), std::vector<int>{ 0 });
}

TEST(FillOrder, DataTermsAreTheWindowsSlopeScaledToTheSteepest)
{
  Heightfield t(256, 64);
  for (int j = 0; j < t.height; ++j)
  {
    for (int i = 0; i < t.width; ++i)
    {
      t.at(i, j) = i < 128 ? 0.0f : 2.0f * static_cast<float>(i - 128); // flat, then a slope
    }
  }
  const FillGrid g = fillGrid(t.width, t.height, kPatch, 0.5, 0);
  const std::vector<double> data = fillDataTerms(t, g, kPatch);
  ASSERT_EQ(data.size(), g.size());
  EXPECT_DOUBLE_EQ(*std::max_element(data.begin(), data.end()), 1.0);
  for (std::size_t s = 0; s < g.size(); ++s)
  {
    if (g.x0(s) + kPatch <= 128)
    {
      EXPECT_EQ(data[s], 0.0) << s; // wholly on the flat
    }
    if (g.x0(s) >= 128)
    {
      EXPECT_GT(data[s], 0.95) << s; // wholly on the slope
    }
  }
  EXPECT_EQ(fillDataTerms(Heightfield(256, 64), g, kPatch), std::vector<double>(g.size(), 0.0));
}

TEST(FillOrder, ConcentricVisitsTheMostFilledWindowFirstAndFillsEveryCell)
{
  Mask m(200, 160);
  for (int j = 70; j < 90; ++j) // what the feature patches left: a block in the middle
  {
    for (int i = 90; i < 110; ++i)
    {
      m.filled[m.at(i, j)] = 1;
    }
  }
  const FillGrid g = fillGrid(m.width, m.height, kPatch, 0.5, 3);
  FillSteps steps = m.steps();
  // Before each visit, no open window is more filled than the one visited.
  auto fillWindow = steps.fillWindow;
  steps.fillWindow = [&](int x0, int y0)
  {
    const double visited = m.share(x0, y0);
    for (std::size_t s = 0; s < g.size(); ++s)
    {
      const double other = m.share(g.x0(s), g.y0(s));
      EXPECT_TRUE(other >= 1.0 || other <= visited) << s;
    }
    return fillWindow(x0, y0);
  };
  runFill(g, std::vector<double>(g.size(), 0.0), FillOrder::Concentric, 3, steps);
  EXPECT_EQ(std::count(m.filled.begin(), m.filled.end(), 0), 0);
  ASSERT_FALSE(m.visits.empty());
  EXPECT_GT(m.visits.size(), g.size() / 2); // windows overlap: not every one is needed
  EXPECT_LE(m.visits.size(), g.size());
  // The first window visited overlaps the block.
  EXPECT_LT(std::abs(m.visits.front().first + kPatch / 2 - 100), kPatch / 2 + 10);
  EXPECT_LT(std::abs(m.visits.front().second + kPatch / 2 - 80), kPatch / 2 + 10);
}

TEST(FillOrder, BestFirstAddsTheDataTermAndTiesFollowTheSeed)
{
  // Nothing filled, data terms rising eastwards: the east edge goes first.
  Mask m(200, 160);
  const FillGrid g = fillGrid(m.width, m.height, kPatch, 0.5, 0);
  std::vector<double> data(g.size());
  for (std::size_t s = 0; s < g.size(); ++s)
  {
    data[s] = static_cast<double>(g.x0(s)) / (m.width - kPatch);
  }
  runFill(g, data, FillOrder::BestFirst, 0, m.steps());
  EXPECT_EQ(m.visits.front().first, m.width - kPatch);
  // With every priority equal, the seed orders the windows; the same seed,
  // the same order.
  auto order = [&](std::uint64_t seed)
  {
    Mask blank(200, 160);
    runFill(g, std::vector<double>(g.size(), 0.0), FillOrder::BestFirst, seed, blank.steps());
    return blank.visits;
  };
  EXPECT_EQ(order(1), order(1));
  EXPECT_NE(order(1).front(), order(2).front());
}

TEST(FillOrder, AWindowNoPatchCanCoverIsRetiredAndProgressEndsAtOne)
{
  Mask m(160, 160);
  for (int j = 0; j < 10; ++j) // a corner no candidate can cover
  {
    for (int i = 0; i < 10; ++i)
    {
      m.never[m.at(i, j)] = 1;
    }
  }
  const FillGrid g = fillGrid(m.width, m.height, kPatch, 0.5, 0);
  std::vector<double> progress;
  runFill(g, std::vector<double>(g.size(), 0.0), FillOrder::BestFirst, 0, m.steps(&progress));
  // The corner window is tried until it writes nothing, then retired: the
  // fill ends, every other cell filled.
  EXPECT_EQ(std::count(m.filled.begin(), m.filled.end(), 0), 100);
  const auto corner = std::count(m.visits.begin(), m.visits.end(), std::make_pair(0, 0));
  EXPECT_GE(corner, 1);
  EXPECT_LE(corner, kMaxFillAttempts);
  // A window whose patches always write something but never cover the hole
  // is retired after kMaxFillAttempts tries.
  Mask again(160, 160);
  again.never = m.never;
  FillSteps steps = again.steps();
  steps.fillWindow = [&again](int x0, int y0)
  { return std::max<std::size_t>(x0 == 0 && y0 == 0 ? 1 : 0, again.fill(x0, y0)); };
  runFill(g, std::vector<double>(g.size(), 0.0), FillOrder::BestFirst, 0, steps);
  EXPECT_EQ(
    std::count(again.visits.begin(), again.visits.end(), std::make_pair(0, 0)), kMaxFillAttempts);
  ASSERT_EQ(progress.size(), m.visits.size());
  EXPECT_TRUE(std::is_sorted(progress.begin(), progress.end()));
  EXPECT_DOUBLE_EQ(progress.back(), 1.0);
}
