// Tests of Kernels/Merging/SeamCut.cxx.
// Graph-cut seams: our grid max-flow against Boost's Boykov-Kolmogorov and
// against brute force, plus the constraint and degenerate cases.
#include "Core/HeightfieldIO.h"
#include "Merging/SeamCut.h"
#include "TestData.h"

// Boost.Graph's BK trips GCC's maybe-uninitialized analysis in its own
// iterators; the reference solver is not our code.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/boykov_kolmogorov_max_flow.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

using namespace tsynth;

namespace
{

using Traits = boost::adjacency_list_traits<boost::vecS, boost::vecS, boost::directedS>;
using BoostGraph = boost::adjacency_list<boost::vecS,
  boost::vecS,
  boost::directedS,
  boost::property<boost::vertex_index_t,
    long,
    boost::property<boost::vertex_color_t,
      boost::default_color_type,
      boost::property<boost::vertex_distance_t,
        long,
        boost::property<boost::vertex_predecessor_t, Traits::edge_descriptor>>>>,
  boost::property<boost::edge_capacity_t,
    double,
    boost::property<boost::edge_residual_capacity_t,
      double,
      boost::property<boost::edge_reverse_t, Traits::edge_descriptor>>>>;

// Effective constraints after NaN masking, as SeamCut applies them.
std::vector<SeamConstraint> effective(const std::vector<float>& a,
  const std::vector<float>& b,
  const std::vector<SeamConstraint>& c)
{
  std::vector<SeamConstraint> out(c);
  for (std::size_t k = 0; k < c.size(); ++k)
    if (!std::isfinite(a[k]) || !std::isfinite(b[k]))
      out[k] = SeamConstraint::Outside;
  return out;
}

// Min cut of the original (unreduced) graph: forced pixels tied to their
// terminal with a capacity larger than any cut.
double boostMinCut(int w, int h, const SeamWeights& wt, const std::vector<SeamConstraint>& c)
{
  const int n = w * h;
  BoostGraph g(static_cast<std::size_t>(n + 2));
  const int source = n;
  const int sink = n + 1;
  auto capacity = boost::get(boost::edge_capacity, g);
  auto reverse = boost::get(boost::edge_reverse, g);
  auto addPair = [&](int u, int v, double cap, double rev)
  {
    auto e1 = boost::add_edge(u, v, g).first;
    auto e2 = boost::add_edge(v, u, g).first;
    capacity[e1] = cap;
    capacity[e2] = rev;
    reverse[e1] = e2;
    reverse[e2] = e1;
  };
  double total = 1.0;
  for (int k = 0; k < n; ++k)
  {
    if (!std::isnan(wt.wx[k]))
      total += wt.wx[k];
    if (!std::isnan(wt.wy[k]))
      total += wt.wy[k];
  }
  for (int k = 0; k < n; ++k)
  {
    if (!std::isnan(wt.wx[k]))
      addPair(k, k + 1, wt.wx[k], wt.wx[k]);
    if (!std::isnan(wt.wy[k]))
      addPair(k, k + w, wt.wy[k], wt.wy[k]);
    if (c[k] == SeamConstraint::ForceNew)
      addPair(source, k, 10.0 * total, 0.0);
    if (c[k] == SeamConstraint::ForceOld)
      addPair(k, sink, 10.0 * total, 0.0);
  }
  return boost::boykov_kolmogorov_max_flow(g, source, sink);
}

// Cut cost of a labelling.
double labellingCost(int w, int h, const SeamWeights& wt, const std::vector<std::uint8_t>& label)
{
  double cost = 0.0;
  for (int k = 0; k < w * h; ++k)
  {
    if (!std::isnan(wt.wx[k]) && label[k] != label[k + 1])
      cost += wt.wx[k];
    if (!std::isnan(wt.wy[k]) && label[k] != label[k + w])
      cost += wt.wy[k];
  }
  return cost;
}

struct Problem
{
  int w = 0, h = 0;
  std::vector<float> a, b;
  std::vector<SeamConstraint> c;
};

// Random heights (smooth + noise, some NaN), left column old, right column new,
// a few random forced and outside pixels.
Problem randomProblem(std::mt19937& rng, int w, int h, double noise, double nanFraction)
{
  Problem p;
  p.w = w;
  p.h = h;
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double fa = 0.1 + u(rng), fb = 0.1 + u(rng);
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      float a = static_cast<float>(50.0 * std::sin(fa * i + 0.3 * j) + noise * u(rng));
      float b = static_cast<float>(50.0 * std::cos(fb * j - 0.2 * i) + noise * u(rng));
      if (u(rng) < nanFraction)
        (u(rng) < 0.5 ? a : b) = std::numeric_limits<float>::quiet_NaN();
      p.a.push_back(a);
      p.b.push_back(b);
      SeamConstraint c = SeamConstraint::Free;
      if (i == 0)
        c = SeamConstraint::ForceOld;
      else if (i == w - 1)
        c = SeamConstraint::ForceNew;
      else
      {
        const double r = u(rng);
        c = r < 0.03 ? SeamConstraint::ForceOld
                     : (r < 0.06 ? SeamConstraint::ForceNew
                                 : (r < 0.09 ? SeamConstraint::Outside : SeamConstraint::Free));
      }
      p.c.push_back(c);
    }
  }
  return p;
}

void expectMinCut(SeamCut& cut, const Problem& p, double cellX, double cellY)
{
  const SeamCutResult& r = cut.cut(p.w, p.h, p.a.data(), p.b.data(), p.c.data(), cellX, cellY);
  const std::vector<SeamConstraint> c = effective(p.a, p.b, p.c);
  const double reference = boostMinCut(p.w, p.h, cut.weights(), c);
  const double tol = 1e-9 * std::max(1.0, reference);
  EXPECT_NEAR(r.cost, reference, tol);
  EXPECT_NEAR(r.flow, reference, tol);
  EXPECT_NEAR(labellingCost(p.w, p.h, cut.weights(), r.takeNew), r.cost, tol);
  for (std::size_t k = 0; k < c.size(); ++k)
  {
    if (c[k] == SeamConstraint::ForceNew)
    {
      EXPECT_EQ(r.takeNew[k], 1);
    }
    if (c[k] != SeamConstraint::ForceNew && c[k] != SeamConstraint::Free)
    {
      EXPECT_EQ(r.takeNew[k], 0);
    }
  }
}

} // namespace

TEST(GraphCut, KwatraWeightOnTwoPixels)
{
  // A = (1, 3), B = (0, 0), cell 2 m: mismatch 1 + 3, slopes |1| + |1| + 0 + 0.
  const std::vector<float> a = { 1.0f, 3.0f };
  const std::vector<float> b = { 0.0f, 0.0f };
  const std::vector<SeamConstraint> c = { SeamConstraint::ForceOld, SeamConstraint::ForceNew };
  SeamCut cut;
  const SeamCutResult& r = cut.cut(2, 1, a.data(), b.data(), c.data(), 2.0, 2.0);
  const double eps = 0.01 * 2.0; // 1% of the mean denominator
  EXPECT_DOUBLE_EQ(cut.weights().epsilon, eps);
  EXPECT_DOUBLE_EQ(r.cost, 4.0 / (2.0 + eps));
  EXPECT_EQ(r.cutEdges, 1);
  EXPECT_EQ(r.takeNew[0], 0);
  EXPECT_EQ(r.takeNew[1], 1);
  EXPECT_EQ(r.seam[0], 1);
  EXPECT_EQ(r.seam[1], 1);
  // Without the gradient term: Zhou's plain mismatch.
  SeamCutOptions plain;
  plain.gradientTerm = false;
  EXPECT_DOUBLE_EQ(cut.cut(2, 1, a.data(), b.data(), c.data(), 2.0, 2.0, plain).cost, 4.0);
}

TEST(GraphCut, SeamFollowsTheCheapestColumn)
{
  // A and B agree exactly on column 5 only: the cut must pass there (cost 0)
  // and every pixel left of it stays old.
  const int w = 10, h = 6;
  std::vector<float> a(w * h), b(w * h);
  std::vector<SeamConstraint> c(w * h, SeamConstraint::Free);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
    {
      a[j * w + i] = static_cast<float>(i * 10 + j);
      b[j * w + i] = static_cast<float>(i * 10 + j + (i == 5 ? 0 : 7));
      c[j * w + i] = i == 0 ? SeamConstraint::ForceOld
                            : (i == w - 1 ? SeamConstraint::ForceNew : SeamConstraint::Free);
    }
  SeamCut cut;
  const SeamCutResult& r = cut.cut(w, h, a.data(), b.data(), c.data(), 1.0, 1.0);
  EXPECT_EQ(r.cutEdges, h);
  // Edges (4,5) and (5,6) both carry a mismatch of 7, but B's slope is larger
  // around (5,6) (10 + 13.5 against 6.5 + 10), so (5,6) is cheaper: column 5
  // stays old and the cost is h * 7 / (10 + 10 + 10 + 13.5 + eps).
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      EXPECT_EQ(r.takeNew[j * w + i], i > 5 ? 1 : 0) << i << "," << j;
    }
  }
  EXPECT_NEAR(r.cost, h * 7.0 / (43.5 + cut.weights().epsilon), 1e-12);
}

TEST(GraphCut, MatchesBoostOnRandomGrids)
{
  std::mt19937 rng(12345);
  SeamCut cut; // one workspace for every problem: storage reuse is exercised
  const int sizes[][2] = { { 5, 4 }, { 17, 9 }, { 40, 30 }, { 80, 27 }, { 12, 50 }, { 96, 32 } };
  for (int trial = 0; trial < 36; ++trial)
  {
    const auto& s = sizes[trial % 6];
    const double noise = trial % 3 == 0 ? 0.0 : (trial % 3 == 1 ? 5.0 : 100.0);
    const Problem p = randomProblem(rng, s[0], s[1], noise, trial % 4 == 0 ? 0.05 : 0.0);
    SCOPED_TRACE(trial);
    expectMinCut(cut, p, trial % 2 ? 30.0 : 1.0, trial % 2 ? 20.0 : 1.0);
  }
}

TEST(GraphCut, MatchesBoostOnDemOverlaps)
{
  const Heightfield alps = readHeightfield(test::bundledData() / "dems" / "alps-montblanc.png");
  const Heightfield colorado = readHeightfield(test::bundledData() / "dems" / "colorado.png");
  SeamCut cut;
  const int sizes[][2] = { { 80, 27 }, { 96, 32 }, { 27, 80 } };
  int count = 0;
  for (const Heightfield* dem : { &alps, &colorado })
  {
    for (int trial = 0; trial < 6; ++trial)
    {
      const auto& s = sizes[trial % 3];
      Problem p;
      p.w = s[0];
      p.h = s[1];
      const int ax = 10 + 37 * trial, ay = 20 + 23 * trial;
      const int bx = 150 + 11 * trial, by = 90 + 29 * trial;
      for (int j = 0; j < p.h; ++j)
        for (int i = 0; i < p.w; ++i)
        {
          p.a.push_back(dem->at(ax + i, ay + j));
          // The second exemplar supplies the new patch half the time.
          const Heightfield& other = trial % 2 ? colorado : *dem;
          p.b.push_back(other.at(bx + i, by + j));
          const bool horizontal = p.w > p.h;
          const int along = horizontal ? i : j;
          const int length = horizontal ? p.w : p.h;
          p.c.push_back(along == 0
              ? SeamConstraint::ForceOld
              : (along == length - 1 ? SeamConstraint::ForceNew : SeamConstraint::Free));
        }
      SCOPED_TRACE(trial);
      expectMinCut(cut, p, dem->cellX, dem->cellY);
      ++count;
    }
  }
  EXPECT_EQ(count, 12);
}

TEST(GraphCut, MatchesBruteForceOnTinyOverlaps)
{
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  SeamCut cut;
  int checked = 0;
  for (int trial = 0; trial < 150; ++trial)
  {
    const int w = 2 + trial % 4;
    const int h = 2 + (trial / 4) % 3;
    Problem p = randomProblem(rng, w, h, trial % 2 ? 30.0 : 0.5, trial % 5 == 0 ? 0.1 : 0.0);
    // Random constraints everywhere, at most 12 free pixels.
    for (auto& c : p.c)
    {
      const double r = u(rng);
      c = r < 0.15 ? SeamConstraint::ForceOld
                   : (r < 0.3 ? SeamConstraint::ForceNew
                              : (r < 0.37 ? SeamConstraint::Outside : SeamConstraint::Free));
    }
    const SeamCutResult r = cut.cut(w, h, p.a.data(), p.b.data(), p.c.data(), 1.0, 1.0);
    const std::vector<SeamConstraint> c = effective(p.a, p.b, p.c);
    std::vector<int> freePixels;
    std::vector<std::uint8_t> label(w * h, 0);
    for (int k = 0; k < w * h; ++k)
    {
      if (c[k] == SeamConstraint::Free)
        freePixels.push_back(k);
      label[k] = c[k] == SeamConstraint::ForceNew;
    }
    ASSERT_LE(freePixels.size(), 20u);
    if (freePixels.size() > 12)
      continue;
    double best = std::numeric_limits<double>::infinity();
    for (unsigned mask = 0; mask < (1u << freePixels.size()); ++mask)
    {
      for (std::size_t f = 0; f < freePixels.size(); ++f)
        label[freePixels[f]] = (mask >> f) & 1u;
      best = std::min(best, labellingCost(w, h, cut.weights(), label));
    }
    EXPECT_NEAR(r.cost, best, 1e-9 * std::max(1.0, best)) << "trial " << trial;
    ++checked;
  }
  EXPECT_GT(checked, 100);
}

TEST(GraphCut, DegenerateConstraintSets)
{
  const int w = 8, h = 5;
  std::vector<float> a(w * h), b(w * h);
  for (int k = 0; k < w * h; ++k)
  {
    a[k] = static_cast<float>(k % 7);
    b[k] = static_cast<float>(k % 5);
  }
  SeamCut cut;
  // Everything forced old / new: no node is free, no seam.
  std::vector<SeamConstraint> c(w * h, SeamConstraint::ForceOld);
  const SeamCutResult r1 = cut.cut(w, h, a.data(), b.data(), c.data(), 1.0, 1.0);
  EXPECT_EQ(r1.cost, 0.0);
  EXPECT_EQ(r1.cutEdges, 0);
  for (auto v : r1.takeNew)
    EXPECT_EQ(v, 0);
  std::fill(c.begin(), c.end(), SeamConstraint::ForceNew);
  const SeamCutResult r2 = cut.cut(w, h, a.data(), b.data(), c.data(), 1.0, 1.0);
  EXPECT_EQ(r2.cutEdges, 0);
  for (auto v : r2.takeNew)
    EXPECT_EQ(v, 1);
  // All free, no terminal: nothing pulls to new, everything stays old.
  const SeamCutResult r3 = cut.cut(w, h, a.data(), b.data(), nullptr, 1.0, 1.0);
  EXPECT_EQ(r3.cutEdges, 0);
  for (auto v : r3.takeNew)
    EXPECT_EQ(v, 0);
  // Zero-area windows.
  EXPECT_EQ(cut.cut(0, 5, a.data(), b.data(), nullptr, 1.0, 1.0).takeNew.size(), 0u);
  EXPECT_EQ(cut.cut(8, 0, a.data(), b.data(), nullptr, 1.0, 1.0).cost, 0.0);
  // NaN in either input: those pixels are outside, never new, never seam,
  // even when forced new.
  std::vector<float> an(a), bn(b);
  std::fill(c.begin(), c.end(), SeamConstraint::Free);
  for (int j = 0; j < h; ++j)
  {
    c[j * w] = SeamConstraint::ForceOld;
    c[j * w + w - 1] = SeamConstraint::ForceNew;
    an[j * w + 3] = std::numeric_limits<float>::quiet_NaN(); // a NaN wall across the window
  }
  bn[w - 1] = std::numeric_limits<float>::quiet_NaN();
  const SeamCutResult r4 = cut.cut(w, h, an.data(), bn.data(), c.data(), 1.0, 1.0);
  for (int j = 0; j < h; ++j)
  {
    EXPECT_EQ(r4.takeNew[j * w + 3], 0);
    EXPECT_EQ(r4.seam[j * w + 3], 0);
  }
  EXPECT_EQ(r4.takeNew[w - 1], 0);
  EXPECT_TRUE(std::isfinite(r4.cost));
  // The wall separates the terminals: nothing needs cutting.
  EXPECT_EQ(r4.cost, 0.0);
  // Everything NaN.
  std::vector<float> allNan(w * h, std::numeric_limits<float>::quiet_NaN());
  const SeamCutResult r5 = cut.cut(w, h, allNan.data(), b.data(), c.data(), 1.0, 1.0);
  EXPECT_EQ(r5.cutEdges, 0);
  for (auto v : r5.takeNew)
    EXPECT_EQ(v, 0);
  // Flat identical inputs (every gradient 0): eps keeps the weights finite.
  std::vector<float> flat(w * h, 100.0f), flat2(w * h, 101.0f);
  const SeamCutResult r6 = cut.cut(w, h, flat.data(), flat2.data(), c.data(), 1.0, 1.0);
  EXPECT_TRUE(std::isfinite(r6.cost));
  EXPECT_EQ(r6.cutEdges, h);
  EXPECT_NEAR(r6.cost, h * 2.0 / 1e-6, 1e-3);
}

TEST(GraphCut, ReusedWorkspaceGivesFreshResults)
{
  std::mt19937 rng(99);
  const Problem big = randomProblem(rng, 60, 40, 20.0, 0.0);
  const Problem small = randomProblem(rng, 7, 5, 20.0, 0.0);
  SeamCut fresh;
  const SeamCutResult expected =
    fresh.cut(big.w, big.h, big.a.data(), big.b.data(), big.c.data(), 1.0, 1.0);
  SeamCut reused;
  reused.cut(small.w, small.h, small.a.data(), small.b.data(), small.c.data(), 1.0, 1.0);
  reused.cut(big.w, big.h, big.a.data(), big.b.data(), big.c.data(), 1.0, 1.0);
  reused.cut(small.w, small.h, small.a.data(), small.b.data(), small.c.data(), 1.0, 1.0);
  const SeamCutResult again =
    reused.cut(big.w, big.h, big.a.data(), big.b.data(), big.c.data(), 1.0, 1.0);
  EXPECT_EQ(again.takeNew, expected.takeNew);
  EXPECT_EQ(again.cost, expected.cost);
  EXPECT_GT(expected.cutEdges, 0);
}

TEST(GraphCut, ConstraintMapFromMasks)
{
  // 6 x 3 window: old covers columns 0-3, new covers 2-5, core at (3, 1).
  //   old-only | overlap 2 | overlap 3 | new-only
  const int w = 6, h = 3;
  std::vector<std::uint8_t> oldMask(w * h), newMask(w * h), core(w * h, 0);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
    {
      oldMask[j * w + i] = i <= 3;
      newMask[j * w + i] = i >= 2;
    }
  core[1 * w + 3] = 1;
  const auto c = buildSeamConstraints(w, h, oldMask.data(), newMask.data(), core.data());
  for (int j = 0; j < h; ++j)
  {
    EXPECT_EQ(c[j * w + 0], SeamConstraint::Outside);
    EXPECT_EQ(c[j * w + 1], SeamConstraint::Outside);
    EXPECT_EQ(c[j * w + 2], SeamConstraint::ForceOld); // next to old-only column 1
    EXPECT_EQ(c[j * w + 3], SeamConstraint::ForceNew); // next to new-only column 4
    EXPECT_EQ(c[j * w + 4], SeamConstraint::Outside);
  }
  // Wider overlap: the middle is free.
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
    {
      oldMask[j * w + i] = i <= 4;
      newMask[j * w + i] = i >= 1;
    }
  std::fill(core.begin(), core.end(), 0);
  core[1 * w + 1] = 1; // core beats the old neighbour
  const auto c2 = buildSeamConstraints(w, h, oldMask.data(), newMask.data(), core.data());
  EXPECT_EQ(c2[0 * w + 1], SeamConstraint::ForceOld);
  EXPECT_EQ(c2[1 * w + 1], SeamConstraint::ForceNew);
  EXPECT_EQ(c2[1 * w + 2], SeamConstraint::Free);
  EXPECT_EQ(c2[1 * w + 3], SeamConstraint::Free);
  EXPECT_EQ(c2[1 * w + 4], SeamConstraint::ForceNew);
}
