#include "Core/Error.h"
#include "Core/HeightfieldIO.h"
#include "Features/Ppa.h"
#include "Features/Profiles.h"
#include "Features/Sketch.h"
#include "TestData.h"

#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/kruskal_min_spanning_tree.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace tsynth;

namespace
{

constexpr double kPi = 3.14159265358979323846;

double segmentDistance(const Point2& p, const Point2& a, const Point2& b)
{
  const double dx = b.x - a.x;
  const double dy = b.y - a.y;
  const double len2 = dx * dx + dy * dy;
  double t = len2 > 0 ? ((p.x - a.x) * dx + (p.y - a.y) * dy) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(p.x - (a.x + t * dx), p.y - (a.y + t * dy));
}

double polylineDistance(const Point2& p, const std::vector<Point2>& line)
{
  double d = std::numeric_limits<double>::infinity();
  for (std::size_t k = 1; k < line.size(); ++k)
  {
    d = std::min(d, segmentDistance(p, line[k - 1], line[k]));
  }
  return d;
}

// Ridge lines with a known answer: a Y junction and a closed loop.
struct KnownRidges
{
  std::vector<std::vector<Point2>> lines;
  Point2 junction{ 128, 128 };
  KnownRidges()
  {
    lines.push_back({ { 128, 20 }, { 128, 128 } });  // trunk, pointing south
    lines.push_back({ { 128, 128 }, { 50, 230 } });  // left arm
    lines.push_back({ { 128, 128 }, { 210, 230 } }); // right arm
    std::vector<Point2> ring;
    for (int k = 0; k <= 72; ++k)
    {
      ring.push_back(
        { 55 + 32 * std::cos(2 * kPi * k / 72), 62 + 32 * std::sin(2 * kPi * k / 72) });
    }
    lines.push_back(ring);
  }
  double distance(const Point2& p) const
  {
    double d = std::numeric_limits<double>::infinity();
    for (const auto& l : lines)
    {
      d = std::min(d, polylineDistance(p, l));
    }
    return d;
  }
  // Gaussian ridges of 300 m, sigma 6 cells, on a gentle tilt; 30 m cells.
  Heightfield surface(double sign) const
  {
    Heightfield hf(256, 256);
    hf.cellX = hf.cellY = 30.0;
    for (int j = 0; j < hf.height; ++j)
    {
      for (int i = 0; i < hf.width; ++i)
      {
        const double d = distance({ static_cast<double>(i), static_cast<double>(j) });
        const double z = 1000.0 + 0.4 * i + 300.0 * std::exp(-d * d / (2.0 * 36.0));
        hf.at(i, j) = static_cast<float>(sign * z);
      }
    }
    return hf;
  }
  // Cells on the true lines (sampled every quarter cell).
  std::vector<Point2> truthCells() const
  {
    std::vector<Point2> cells;
    for (const auto& l : lines)
    {
      for (std::size_t k = 1; k < l.size(); ++k)
      {
        const double len = std::hypot(l[k].x - l[k - 1].x, l[k].y - l[k - 1].y);
        for (double t = 0; t <= len; t += 0.25)
        {
          cells.push_back({ std::round(l[k - 1].x + (l[k].x - l[k - 1].x) * t / len),
            std::round(l[k - 1].y + (l[k].y - l[k - 1].y) * t / len) });
        }
      }
    }
    return cells;
  }
};

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

TEST(Ppa, ProfilesAcrossARidgeAreSymmetricAndPeakOnIt)
{
  const KnownRidges truth;
  const Heightfield hf = truth.surface(1.0);
  const FeatureExtraction r = extractFeatures(hf, FeatureType::Ridge, {});
  const auto profiles = sampleProfiles(r.graph, hf);
  const int root = r.graph.bfsOrder.front();
  for (const ChainProfile& p : profiles[static_cast<std::size_t>(root)])
  {
    ASSERT_EQ(p.across.size(), 17u);
    ASSERT_EQ(p.along.size(), 16u);
    const auto peak = std::max_element(p.across.begin(), p.across.end()) - p.across.begin();
    EXPECT_NEAR(static_cast<double>(peak), 8.0, 1.0);
    // 20 cells either side of a sigma-6 ridge: down by ~300 m on both sides (minus the tilt).
    EXPECT_GT(p.across[8] - p.across.front(), 250.0f);
    EXPECT_GT(p.across[8] - p.across.back(), 250.0f);
    for (float a : p.along)
    {
      EXPECT_GT(a, 1250.0f); // on the crest all the way to the circle
    }
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

// Sketches ------------------------------------------------------------------------------------

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
