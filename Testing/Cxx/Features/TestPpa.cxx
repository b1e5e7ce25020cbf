// Tests of Kernels/Features/Ppa.cxx: PPA's ridges and valleys against known answers, its spanning
// forest against Boost.Graph, and the significance test.
#include "Core/Constants.h"
#include "Core/Error.h"
#include "Core/HeightfieldIO.h"
#include "Features/Ppa.h"
#include "FeaturesTestData.h"
#include "TestData.h"

#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/kruskal_min_spanning_tree.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <random>

using namespace tsynth;
using tsynth::test::features::KnownRidges;
using tsynth::test::features::polylineDistance;
using tsynth::test::features::segmentDistance;

namespace
{

void checkKnownRidges(FeatureType type, double sign)
{
  const KnownRidges truth;
  const Heightfield hf = truth.surface(sign);
  const FeatureExtraction r = extractFeatures(hf, type, {});
  ASSERT_TRUE(r.pixels.isForest());

  std::vector<Point2> found;
  for (std::size_t idx = 0; idx < r.pixels.size(); ++idx)
  {
    if (r.pixels.links(idx) != 0)
    {
      found.push_back(
        { static_cast<double>(r.pixels.column(idx)), static_cast<double>(r.pixels.row(idx)) });
    }
  }
  ASSERT_GT(found.size(), 500u);
  std::size_t precise = 0;
  for (const Point2& p : found)
  {
    precise += truth.distance(p) <= 2.0 ? 1 : 0;
  }
  const auto cells = truth.truthCells();
  std::size_t recalled = 0;
  for (const Point2& t : cells)
  {
    bool hit = false;
    for (const Point2& p : found)
    {
      if (std::hypot(p.x - t.x, p.y - t.y) <= 2.0)
      {
        hit = true;
        break;
      }
    }
    recalled += hit ? 1 : 0;
  }
  const double precision = static_cast<double>(precise) / static_cast<double>(found.size());
  const double recall = static_cast<double>(recalled) / static_cast<double>(cells.size());
  EXPECT_GE(precision, 0.95);
  EXPECT_GE(recall, 0.95);

  // Exactly one branch node, of degree 3, at the junction.
  int branches = 0;
  for (const FeatureNode& n : r.graph.nodes)
  {
    EXPECT_EQ(n.type, type);
    if (n.kind == NodeKind::Branch)
    {
      ++branches;
      EXPECT_EQ(n.degree, 3);
      EXPECT_LE(std::hypot(n.position.x - truth.junction.x, n.position.y - truth.junction.y), 3.0);
    }
  }
  EXPECT_EQ(branches, 1);
  // The Y's three ends plus the two ends where the spanning forest opened the loop.
  EXPECT_EQ(r.graph.countKind(NodeKind::End), 5);
  EXPECT_EQ(r.graph.componentCount, 2);
}

} // namespace

TEST(Ppa, GaussianRidgesAreFoundWithTheirJunction)
{
  checkKnownRidges(FeatureType::Ridge, 1.0);
}

TEST(Ppa, ValleysOfTheNegatedSurfaceAreTheSame)
{
  checkKnownRidges(FeatureType::Valley, -1.0);
}

TEST(Ppa, ControlPointsSitOnTheCircleAlongEachArm)
{
  const KnownRidges truth;
  const FeatureExtraction r = extractFeatures(truth.surface(1.0), FeatureType::Ridge, {});
  ASSERT_FALSE(r.graph.bfsOrder.empty());
  // The breadth-first order starts at the highest-degree node: the junction.
  const FeatureNode& root = r.graph.nodes[static_cast<std::size_t>(r.graph.bfsOrder.front())];
  ASSERT_EQ(root.kind, NodeKind::Branch);
  ASSERT_EQ(root.controls.size(), 3u);
  std::vector<double> expected = {
    -90.0, std::atan2(102.0, -78.0) * 180 / kPi, std::atan2(102.0, 82.0) * 180 / kPi
  };
  for (const ControlPoint& cp : root.controls)
  {
    EXPECT_TRUE(cp.reached);
    EXPECT_NEAR(
      std::hypot(cp.position.x - root.position.x, cp.position.y - root.position.y), 40.0, 1e-6);
    double best = 360.0;
    for (double e : expected)
    {
      best = std::min(best, std::abs(std::remainder(cp.angle * 180 / kPi - e, 360.0)));
    }
    EXPECT_LT(best, 5.0) << "control point angle " << cp.angle * 180 / kPi;
  }
}

TEST(Ppa, KruskalMatchesBoostGraph)
{
  // Random heights on a grid where every cell is a target: compare the forest
  // weight with Boost.Graph's kruskal_minimum_spanning_tree on negated weights.
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 100.0f);
  Heightfield hf(40, 30);
  for (float& v : hf.z)
  {
    v = u(rng);
  }
  const std::vector<std::uint8_t> all(hf.size(), 1);
  const std::vector<CellEdge> edges = connectTargets(hf, all);
  const PixelGraph forest = maximumSpanningForest(hf.width, hf.height, edges);
  double ours = 0.0;
  for (const CellEdge& e : edges)
  {
    for (int k = 0; k < 8; ++k)
    {
      if (forest.hasLink(e.a, k) && forest.neighbour(e.a, k) == e.b)
      {
        ours += e.weight;
      }
    }
  }
  using Graph = boost::adjacency_list<boost::vecS,
    boost::vecS,
    boost::undirectedS,
    boost::no_property,
    boost::property<boost::edge_weight_t, double>>;
  Graph g(hf.size());
  for (const CellEdge& e : edges)
  {
    boost::add_edge(e.a, e.b, -static_cast<double>(e.weight), g);
  }
  std::vector<boost::graph_traits<Graph>::edge_descriptor> tree;
  boost::kruskal_minimum_spanning_tree(g, std::back_inserter(tree));
  double theirs = 0.0;
  for (const auto& e : tree)
  {
    theirs -= boost::get(boost::edge_weight, g, e);
  }
  EXPECT_EQ(forest.edgeCount(), tree.size());
  EXPECT_NEAR(ours, theirs, 1e-3);
  EXPECT_TRUE(forest.isForest());
}

TEST(Ppa, CrossingDiagonalsKeepTheHeavier)
{
  Heightfield hf(2, 2);
  hf.at(0, 0) = 10; // NE diagonal 0,0 - 1,1: 10 + 1 = 11
  hf.at(1, 1) = 1;
  hf.at(1, 0) = 8; // NW diagonal 1,0 - 0,1: 8 + 7 = 15
  hf.at(0, 1) = 7;
  const std::vector<std::uint8_t> all(4, 1);
  int diagonals = 0;
  for (const CellEdge& e : connectTargets(hf, all))
  {
    const bool diagonal = (e.a == 0 && e.b == 3) || (e.a == 1 && e.b == 2);
    if (diagonal)
    {
      ++diagonals;
      EXPECT_EQ(e.a, 1u);
      EXPECT_FLOAT_EQ(e.weight, 15.0f);
    }
  }
  EXPECT_EQ(diagonals, 1);
}

TEST(Ppa, DeterministicOnARealDem)
{
  const Heightfield hf = readHeightfield((test::bundledData() / "dems" / "colorado.png").string());
  const FeatureExtraction a = extractFeatures(hf, FeatureType::Ridge, {});
  const FeatureExtraction b = extractFeatures(hf, FeatureType::Ridge, {});
  ASSERT_EQ(a.graph.nodes.size(), b.graph.nodes.size());
  ASSERT_EQ(a.graph.chains.size(), b.graph.chains.size());
  EXPECT_EQ(a.graph.bfsOrder, b.graph.bfsOrder);
  for (std::size_t c = 0; c < a.graph.chains.size(); ++c)
  {
    ASSERT_EQ(a.graph.chains[c].points.size(), b.graph.chains[c].points.size());
    for (std::size_t k = 0; k < a.graph.chains[c].points.size(); ++k)
    {
      ASSERT_EQ(a.graph.chains[c].points[k].x, b.graph.chains[c].points[k].x);
      ASSERT_EQ(a.graph.chains[c].points[k].y, b.graph.chains[c].points[k].y);
    }
  }
  // A real mountain range has a real network: many chains, branches and ends.
  EXPECT_GT(a.graph.countKind(NodeKind::Branch), 50);
  EXPECT_GT(a.graph.countKind(NodeKind::End), 50);
  EXPECT_TRUE(a.pixels.isForest());
}

TEST(Ppa, FlatDemGivesAnEmptyGraphAndAWarning)
{
  Heightfield flat(100, 100, 500.0f);
  const FeatureExtraction r = extractFeatures(flat, FeatureType::Ridge, {});
  EXPECT_TRUE(r.graph.empty());
  EXPECT_TRUE(r.graph.chains.empty());
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].find("flat"), std::string::npos);
}

TEST(Ppa, NodataIsNeverATarget)
{
  const KnownRidges truth;
  Heightfield hf = truth.surface(1.0);
  hf.valid.assign(hf.size(), 1);
  for (int j = 0; j < hf.height; ++j)
  {
    for (int i = 100; i < 160; ++i)
    {
      hf.valid[hf.index(i, j)] = 0; // a strip of nodata across the trunk and arms
    }
  }
  normaliseMask(hf);
  const FeatureExtraction r = extractFeatures(hf, FeatureType::Ridge, {});
  for (std::size_t idx = 0; idx < r.pixels.size(); ++idx)
  {
    if (r.pixels.links(idx) != 0)
    {
      EXPECT_TRUE(hf.isValid(idx));
    }
  }
}

// PPA significance ----------------------------------------------------------------------------

namespace
{

// The case: one ridge system on a gently tilted plane with a few metres of
// noise. 512 x 512 cells of 90 m; the plane rises 0.3 degrees towards the north-east;
// Gaussian noise of 3 m (seeded); a main ridge of 1000 m (sigma 12 cells) along a
// gentle curve of about 400 cells and three side ridges leaving its crest (1000 m
// there, 300 m at their ends, sigma 8 cells). Most of the grid is plain noisy plane.
class NoisyRidgeSystem
{
public:
  static constexpr int kSize = 512;
  static constexpr double kCell = 90.0;
  static constexpr double kTiltDeg = 0.3;
  static constexpr double kNoise = 3.0;     // metres, standard deviation
  static constexpr double kTolerance = 3.0; // cells: a feature cell this close is on a crest

  NoisyRidgeSystem()
  {
    constexpr int kSegments = 60;
    std::vector<Point2> main;
    for (int k = 0; k <= kSegments; ++k)
    {
      const double s = static_cast<double>(k) / kSegments;
      main.push_back({ 90.0 + 280.0 * s, 110.0 + 260.0 * s + 40.0 * std::sin(3.0 * s) });
    }
    add(main, 1000.0, 1000.0, 12.0);
    const Point2 a = main[18];
    const Point2 b = main[33];
    const Point2 c = main[48];
    add({ a, { a.x + 75.0, a.y - 65.0 } }, 1000.0, 300.0, 8.0);
    add({ b, { b.x - 85.0, b.y + 55.0 } }, 1000.0, 300.0, 8.0);
    add({ c, { c.x + 80.0, c.y - 50.0 } }, 1000.0, 300.0, 8.0);
  }

  Heightfield surface(bool withRidges) const
  {
    Heightfield hf(kSize, kSize);
    hf.cellX = hf.cellY = kCell;
    const double rise = std::tan(kTiltDeg * kPi / 180.0) * kCell; // metres per cell
    std::mt19937 rng(2024);
    std::normal_distribution<double> noise(0.0, kNoise);
    for (int j = 0; j < kSize; ++j)
    {
      for (int i = 0; i < kSize; ++i)
      {
        const double plane = 200.0 + rise * (0.8 * i + 0.6 * j);
        const double ridges = withRidges ? ridgeHeight({ double(i), double(j) }) : 0.0;
        hf.at(i, j) = static_cast<float>(plane + ridges + noise(rng));
      }
    }
    return hf;
  }

  struct Score
  {
    double precision = 0.0; // share of feature cells within kTolerance of a crest line
    double recall = 0.0;    // share of the crest lines with a feature cell within kTolerance
    std::size_t cells = 0;
  };

  Score score(const PixelGraph& features) const
  {
    Score out;
    std::size_t onCrest = 0;
    for (std::size_t idx = 0; idx < features.size(); ++idx)
    {
      if (features.links(idx) != 0)
      {
        ++out.cells;
        onCrest += crestDistance(cellPoint(features, idx)) <= kTolerance ? 1 : 0;
      }
    }
    std::size_t samples = 0;
    std::size_t found = 0;
    for (const Ridge& r : ridges_)
    {
      for (std::size_t k = 1; k < r.crest.size(); ++k)
      {
        const Point2& p = r.crest[k - 1];
        const Point2& q = r.crest[k];
        const double len = std::hypot(q.x - p.x, q.y - p.y);
        for (double t = 0.0; t < len; t += 0.5)
        {
          ++samples;
          found +=
            featureNear(features, { p.x + (q.x - p.x) * t / len, p.y + (q.y - p.y) * t / len }) ? 1
                                                                                                : 0;
        }
      }
    }
    out.precision = out.cells > 0 ? double(onCrest) / double(out.cells) : 0.0;
    out.recall = samples > 0 ? double(found) / double(samples) : 0.0;
    return out;
  }

private:
  struct Ridge
  {
    std::vector<Point2> crest;
    std::vector<double> arc; // arc length at each crest point
    double startHeight = 0.0;
    double endHeight = 0.0;
    double sigma = 0.0;
  };

  void add(const std::vector<Point2>& crest, double start, double end, double sigma)
  {
    Ridge r{ crest, { 0.0 }, start, end, sigma };
    for (std::size_t k = 1; k < crest.size(); ++k)
    {
      r.arc.push_back(
        r.arc.back() + std::hypot(crest[k].x - crest[k - 1].x, crest[k].y - crest[k - 1].y));
    }
    ridges_.push_back(std::move(r));
  }

  static Point2 cellPoint(const PixelGraph& g, std::size_t idx)
  {
    return { static_cast<double>(g.column(idx)), static_cast<double>(g.row(idx)) };
  }

  // Height of the ridges at p: the highest of the Gaussian cross-sections, each
  // with the crest height interpolated along its line.
  double ridgeHeight(const Point2& p) const
  {
    double z = 0.0;
    for (const Ridge& r : ridges_)
    {
      double best = std::numeric_limits<double>::infinity();
      double along = 0.0;
      for (std::size_t k = 1; k < r.crest.size(); ++k)
      {
        const double d = segmentDistance(p, r.crest[k - 1], r.crest[k]);
        if (d < best)
        {
          best = d;
          const double seg = r.arc[k] - r.arc[k - 1];
          const double dx = r.crest[k].x - r.crest[k - 1].x;
          const double dy = r.crest[k].y - r.crest[k - 1].y;
          const double t = std::clamp(
            ((p.x - r.crest[k - 1].x) * dx + (p.y - r.crest[k - 1].y) * dy) / (seg * seg),
            0.0,
            1.0);
          along = (r.arc[k - 1] + t * seg) / r.arc.back();
        }
      }
      const double crest = r.startHeight + (r.endHeight - r.startHeight) * along;
      z = std::max(z, crest * std::exp(-best * best / (2.0 * r.sigma * r.sigma)));
    }
    return z;
  }

  double crestDistance(const Point2& p) const
  {
    double d = std::numeric_limits<double>::infinity();
    for (const Ridge& r : ridges_)
    {
      d = std::min(d, polylineDistance(p, r.crest));
    }
    return d;
  }

  static bool featureNear(const PixelGraph& g, const Point2& p)
  {
    const int reach = static_cast<int>(std::ceil(kTolerance));
    const auto ci = static_cast<int>(std::lround(p.x));
    const auto cj = static_cast<int>(std::lround(p.y));
    for (int j = std::max(0, cj - reach); j <= std::min(g.height() - 1, cj + reach); ++j)
    {
      for (int i = std::max(0, ci - reach); i <= std::min(g.width() - 1, ci + reach); ++i)
      {
        if (g.links(g.index(i, j)) != 0 && std::hypot(i - p.x, j - p.y) <= kTolerance)
        {
          return true;
        }
      }
    }
    return false;
  }

  std::vector<Ridge> ridges_;
};

PpaOptions significanceOff()
{
  PpaOptions o;
  o.significance = 0.0;
  return o;
}

Heightfield scaled(Heightfield hf, double factor)
{
  for (float& v : hf.z)
  {
    v = static_cast<float>(v * factor);
  }
  return hf;
}

// Cells where exactly one of the two forests has a feature cell.
std::size_t differingCells(const PixelGraph& a, const PixelGraph& b)
{
  std::size_t n = 0;
  for (std::size_t idx = 0; idx < a.size(); ++idx)
  {
    n += (a.links(idx) != 0) != (b.links(idx) != 0) ? 1 : 0;
  }
  return n;
}

// Trees whose chains add up to at least minLength cells.
int longTrees(const FeatureGraph& g, double minLength)
{
  std::vector<double> length(static_cast<std::size_t>(g.componentCount), 0.0);
  for (const FeatureChain& c : g.chains)
  {
    length[static_cast<std::size_t>(g.nodes[static_cast<std::size_t>(c.from)].component)] +=
      c.length();
  }
  return static_cast<int>(
    std::count_if(length.begin(), length.end(), [&](double l) { return l >= minLength; }));
}

bool anyFeatureWithin(const PixelGraph& g, int ci, int cj, int reach)
{
  for (int j = std::max(0, cj - reach); j <= std::min(g.height() - 1, cj + reach); ++j)
  {
    for (int i = std::max(0, ci - reach); i <= std::min(g.width() - 1, ci + reach); ++i)
    {
      if (g.links(g.index(i, j)) != 0)
      {
        return true;
      }
    }
  }
  return false;
}

} // namespace

TEST(PpaSignificance, ANoisyPlaneKeepsOnlyItsRidgeSystem)
{
  // Without the test about 1 feature cell in 50 lies on a crest (the noise grows
  // trees over the whole plane); with it 0.94, the precision PPA has on the same
  // ridges without noise (the other cells are where side ridges meet the main one
  // and at the rounded ends), and 99.6% of the crest length is found.
  const NoisyRidgeSystem scene;
  const Heightfield hf = scene.surface(true);
  const FeatureExtraction before = extractFeatures(hf, FeatureType::Ridge, significanceOff());
  const NoisyRidgeSystem::Score b = scene.score(before.pixels);
  EXPECT_LT(b.precision, 0.1);
  EXPECT_GT(b.cells, 20000u);

  const FeatureExtraction after = extractFeatures(hf, FeatureType::Ridge, {});
  const NoisyRidgeSystem::Score a = scene.score(after.pixels);
  EXPECT_GE(a.precision, 0.9);
  EXPECT_GE(a.recall, 0.95);
  EXPECT_LT(a.cells, 1000u);                // the crests are about 650 cells long
  EXPECT_LE(after.graph.componentCount, 4); // the main ridge and its three side ridges
  EXPECT_GT(after.statistics.insignificant, after.statistics.targets);
  std::cout << "noisy plane: precision " << b.precision << " -> " << a.precision << ", recall "
            << b.recall << " -> " << a.recall << ", feature cells " << b.cells << " -> " << a.cells
            << "\n";
}

TEST(PpaSignificance, APureNoisePlaneHasNoFeatures)
{
  const NoisyRidgeSystem scene;
  const Heightfield plane = scene.surface(false);
  EXPECT_GT(
    extractFeatures(plane, FeatureType::Ridge, significanceOff()).pixels.nodeCount(), 20000u);
  for (FeatureType type : { FeatureType::Ridge, FeatureType::Valley })
  {
    const FeatureExtraction r = extractFeatures(plane, type, {});
    EXPECT_EQ(r.pixels.nodeCount(), 0u);
    EXPECT_TRUE(r.graph.empty());
    ASSERT_EQ(r.warnings.size(), 1u);
    EXPECT_NE(r.warnings[0].find("significance"), std::string::npos);
  }
}

TEST(PpaSignificance, TheNoiseFloorDecidesWhereTheReliefIsSmall)
{
  // The plane's relief (290 m, the tilt) makes 0.02 of it 5.8 m, under the noise's
  // reach: the floor of 4 sigmas (12 m) is the drop asked for, and without the
  // floor the noise covers the plane with trees again.
  const NoisyRidgeSystem scene;
  const Heightfield plane = scene.surface(false);
  const FeatureExtraction r = extractFeatures(plane, FeatureType::Ridge, {});
  EXPECT_NEAR(r.statistics.noise, NoisyRidgeSystem::kNoise, 0.05 * NoisyRidgeSystem::kNoise);
  EXPECT_DOUBLE_EQ(
    r.statistics.significantDrop, PpaOptions{}.significanceNoise * r.statistics.noise);
  EXPECT_GT(r.statistics.significantDrop, 2.0 * PpaOptions{}.significance * r.statistics.relief);
  PpaOptions noFloor;
  noFloor.significanceNoise = 0.0;
  const FeatureExtraction f = extractFeatures(plane, FeatureType::Ridge, noFloor);
  EXPECT_EQ(f.statistics.noise, 0.0);
  EXPECT_GT(f.pixels.nodeCount(), 10000u);
}

TEST(PpaSignificance, CellNoiseIsTheNoiseNotTheTerrain)
{
  // A smooth surface (any quadric, here a dome and a tilt) has no cell-scale
  // noise; white noise of sigma 2 on top of it is measured as 2.
  Heightfield hf(300, 300);
  for (int j = 0; j < hf.height; ++j)
  {
    for (int i = 0; i < hf.width; ++i)
    {
      hf.at(i, j) = static_cast<float>(500.0 + 0.7 * i - 0.3 * j - 0.01 * (i - 150) * (i - 150) -
        0.02 * (j - 150) * (j - 150) + 0.005 * i * j);
    }
  }
  EXPECT_LT(cellNoise(hf), 1e-3);
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, 2.0);
  for (float& v : hf.z)
  {
    v = static_cast<float>(v + noise(rng));
  }
  EXPECT_NEAR(cellNoise(hf), 2.0, 0.05);
  // Blocks that touch nodata do not count; an all-nodata grid has no noise.
  hf.valid.assign(hf.size(), 0);
  EXPECT_EQ(cellNoise(hf), 0.0);
  EXPECT_EQ(cellNoise(Heightfield(2, 50, 1.0f)), 0.0);
}

TEST(PpaSignificance, FeaturesDoNotDependOnTheHeightUnit)
{
  // Scaled heights round differently in float, which flips a few exact ties of
  // the profile test, the significance test and the edge weights (the DEM's
  // heights are 16-bit steps in feet); measured: at most 72 of 15691 Colorado
  // cells differ (none on the noisy plane). An absolute threshold would change
  // everything.
  const NoisyRidgeSystem scene;
  const Heightfield metres = scene.surface(true);
  const Heightfield colorado =
    readHeightfield((test::bundledData() / "dems" / "colorado.png").string());
  for (const Heightfield* hf : { &metres, &colorado })
  {
    const FeatureExtraction m = extractFeatures(*hf, FeatureType::Ridge, {});
    ASSERT_GT(m.statistics.insignificant, 10000u);
    for (double factor : { 1000.0, 1.0 / 0.3048 }) // kilo-units; feet
    {
      const FeatureExtraction f = extractFeatures(scaled(*hf, factor), FeatureType::Ridge, {});
      EXPECT_NEAR(f.statistics.significantDrop,
        factor * m.statistics.significantDrop,
        1e-5 * factor * m.statistics.significantDrop);
      EXPECT_NEAR(double(f.statistics.insignificant),
        double(m.statistics.insignificant),
        5e-3 * double(m.statistics.insignificant));
      EXPECT_LE(differingCells(f.pixels, m.pixels), m.pixels.nodeCount() / 200);
      EXPECT_NEAR(f.graph.componentCount, m.graph.componentCount, 2);
      std::cout << "x" << factor << ": " << differingCells(f.pixels, m.pixels) << " of "
                << m.pixels.nodeCount() << " cells differ\n";
    }
  }
}

TEST(PpaSignificance, ZeroIsPpaAsBefore)
{
  // extractFeatures on the bundled Colorado DEM before the significance test existed
  // (commit 67bd935): targets, candidate edges, forest edges, cells kept, nodes,
  // chains, trees.
  struct Before
  {
    FeatureType type;
    std::size_t targets, edges, forest, kept, nodes, chains;
    int trees;
  };
  const Heightfield hf = readHeightfield((test::bundledData() / "dems" / "colorado.png").string());
  const PpaOptions d = significanceOff();
  for (const Before& b :
    { Before{ FeatureType::Ridge, 133263, 310588, 130761, 19176, 768, 692, 76 },
      Before{ FeatureType::Valley, 132769, 306601, 130125, 21904, 794, 694, 100 } })
  {
    const FeatureExtraction r = extractFeatures(hf, b.type, d);
    EXPECT_EQ(r.statistics.targets, b.targets);
    EXPECT_EQ(r.statistics.insignificant, 0u);
    EXPECT_EQ(r.statistics.candidateEdges, b.edges);
    EXPECT_EQ(r.statistics.forestEdges, b.forest);
    EXPECT_EQ(r.statistics.prunedCells, b.kept);
    EXPECT_EQ(r.graph.nodes.size(), b.nodes);
    EXPECT_EQ(r.graph.chains.size(), b.chains);
    EXPECT_EQ(r.graph.componentCount, b.trees);
    // The same forest, cell for cell, as the steps composed without the test.
    const Heightfield work = b.type == FeatureType::Valley ? scaled(hf, -1.0) : hf;
    const auto targets = profileTargets(work, d.halfProfileLength, d.minDip, d.relativeDip);
    PixelGraph forest = maximumSpanningForest(hf.width, hf.height, connectTargets(work, targets));
    forest.removeEndSegments(d.endReductions);
    forest.pruneShortBranches(d.minBranchLength);
    forest.removeSmallComponents(d.minTreeSize);
    EXPECT_EQ(differingCells(r.pixels, forest), 0u);
  }
}

TEST(PpaSignificance, ARealDemKeepsItsMajorRidges)
{
  // Measured on the bundled Mont Blanc DEM: 15811 ridge cells without the test,
  // 13513 with it (0.85: short spurs on the flanks and lines over glaciers go;
  // 0.80 at significance 0.03, 0.92 at 0.01); 17 trees of 200 cells or more (15
  // without: noise bridges across valleys no longer join two ridges); 96% of the
  // ridge cells in the highest tenth of the DEM keep a ridge cell within 2 cells
  // (91% at significance 0.05, 84% at 0.08).
  const Heightfield hf =
    readHeightfield((test::bundledData() / "dems" / "alps-montblanc.png").string());
  const FeatureExtraction off = extractFeatures(hf, FeatureType::Ridge, significanceOff());
  const FeatureExtraction on = extractFeatures(hf, FeatureType::Ridge, {});
  const double kept =
    double(on.pixels.nodeCount()) / double(std::max<std::size_t>(1, off.pixels.nodeCount()));
  EXPECT_GT(kept, 0.82);
  EXPECT_LT(kept, 0.89);
  EXPECT_GE(longTrees(on.graph, 200.0), 14);
  EXPECT_LE(longTrees(on.graph, 200.0), 20);

  std::vector<float> sorted = hf.z;
  std::sort(sorted.begin(), sorted.end());
  const float highest = sorted[sorted.size() * 9 / 10];
  std::size_t high = 0;
  std::size_t stay = 0;
  for (std::size_t idx = 0; idx < off.pixels.size(); ++idx)
  {
    if (off.pixels.links(idx) != 0 && hf.z[idx] >= highest)
    {
      ++high;
      stay += anyFeatureWithin(on.pixels, off.pixels.column(idx), off.pixels.row(idx), 2) ? 1 : 0;
    }
  }
  ASSERT_GT(high, 1000u);
  EXPECT_GE(double(stay) / double(high), 0.94);
}

TEST(PpaSignificance, RobustReliefIgnoresSpikesAndNodata)
{
  Heightfield hf(100, 100);
  for (std::size_t k = 0; k < hf.size(); ++k)
  {
    hf.z[k] = static_cast<float>(k); // 0 .. 9999: 1st and 99th percentiles 99 and 9899
  }
  EXPECT_DOUBLE_EQ(robustRelief(hf), 9800.0);
  hf.z[5000] = 1.0e9f; // one spike shifts the 99th percentile by one rank only
  EXPECT_DOUBLE_EQ(robustRelief(hf), 9801.0);
  hf.valid.assign(hf.size(), 1);
  for (std::size_t k = 5000; k < hf.size(); ++k)
  {
    hf.valid[k] = 0; // nodata: the valid heights are 0 .. 4999
  }
  EXPECT_DOUBLE_EQ(robustRelief(hf), 4949.0 - 49.0);

  Heightfield almostFlat(100, 100, 7.0f);
  almostFlat.at(3, 3) = 17.0f; // percentiles equal: the full range
  EXPECT_DOUBLE_EQ(robustRelief(almostFlat), 10.0);
  almostFlat.valid.assign(almostFlat.size(), 0);
  EXPECT_DOUBLE_EQ(robustRelief(almostFlat), 0.0);
}

TEST(PpaSignificance, ATargetMustDropBeforeItRises)
{
  // One row: only the E-W axis fits. The centre (column 10) drops 4 a cell each way.
  Heightfield hf(21, 1);
  for (int i = 0; i < 21; ++i)
  {
    hf.at(i, 0) = static_cast<float>(100 - 4 * std::abs(i - 10));
  }
  auto keeps = [&](const Heightfield& h, int radius, double drop)
  {
    std::vector<std::uint8_t> targets(h.size(), 0);
    targets[10] = 1;
    const std::size_t removed = removeInsignificantTargets(h, targets, radius, drop);
    EXPECT_EQ(removed + targets[10], 1u);
    return targets[10] != 0;
  };
  EXPECT_TRUE(keeps(hf, 5, 20.0));
  EXPECT_FALSE(keeps(hf, 5, 20.5));
  EXPECT_FALSE(keeps(hf, 4, 20.0)); // 16 within 4 cells
  hf.at(9, 0) = 125.0f;             // a step up of 25 before the west side falls away
  EXPECT_FALSE(keeps(hf, 5, 20.0));
  hf.valid.assign(hf.size(), 1);
  hf.valid[9] = 0; // the step is nodata: stepped over
  EXPECT_TRUE(keeps(hf, 5, 20.0));
}

TEST(PpaSignificance, OutOfRangeIsAnError)
{
  Heightfield hf(40, 40, 1.0f);
  for (double bad : { -0.1, 1.5, std::nan("") })
  {
    PpaOptions o;
    o.significance = bad;
    EXPECT_THROW(extractFeatures(hf, FeatureType::Ridge, o), Error);
  }
  PpaOptions o;
  o.significanceRadius = 0;
  EXPECT_THROW(extractFeatures(hf, FeatureType::Ridge, o), Error);
  PpaOptions n;
  n.significanceNoise = -1.0;
  EXPECT_THROW(extractFeatures(hf, FeatureType::Ridge, n), Error);
}
