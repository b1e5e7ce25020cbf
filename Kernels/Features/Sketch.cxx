#include "Sketch.h"

#include "../Core/Error.h"
#include "../Core/Grid.h"
#include "PixelGraph.h"
#include "Ppa.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <limits>
#include <map>
#include <unordered_map>

namespace tsynth
{
namespace
{

std::size_t pixelCount(const ColourImage& image)
{
  return cellCount(image.width, image.height);
}

// Channel c of pixel k, treating 1-2 channel images as grey. Pixels are rows
// of `channels` bytes: channel ch of pixel k is element (ch, k).
std::uint8_t channel(const ColourImage& image, std::size_t k, int c)
{
  const int ch = image.channels <= 2 ? 0 : c;
  return image.data[rowMajor(ch, k, image.channels)];
}

// Cells set to 1 in a mask (std::count's signed count, as a size).
std::size_t countOnes(const std::vector<std::uint8_t>& mask)
{
  return static_cast<std::size_t>(std::count(mask.begin(), mask.end(), 1));
}

// True if a's and b's trees are joined by a path of at most maxSteps edges.
bool connectedWithin(const PixelGraph& g, std::size_t a, std::size_t b, int maxSteps)
{
  std::deque<std::pair<std::size_t, int>> queue{ { a, 0 } };
  std::vector<std::size_t> seen{ a };
  while (!queue.empty())
  {
    const auto [c, d] = queue.front();
    queue.pop_front();
    if (c == b)
    {
      return true;
    }
    if (d == maxSteps)
    {
      continue;
    }
    for (int k = 0; k < 8; ++k)
    {
      if (g.hasLink(c, k))
      {
        const std::size_t n = g.neighbour(c, k);
        if (std::find(seen.begin(), seen.end(), n) == seen.end())
        {
          seen.push_back(n);
          queue.push_back({ n, d + 1 });
        }
      }
    }
  }
  return false;
}

// Centre lines of one stroke class (mask in grid orientation, row 0 south).
FeatureGraph strokeGraph(std::vector<std::uint8_t> mask,
  int w,
  int h,
  FeatureType type,
  const SketchOptions& o,
  double& widthOut)
{
  const std::size_t area = countOnes(mask);
  // Ragged stroke outlines thin into hairy centre lines: smooth the outline first.
  {
    std::vector<std::uint8_t> probe = mask;
    thinMask(probe, w, h);
    const double roughWidth = static_cast<double>(area) /
      std::max<double>(1.0, static_cast<double>(std::count(probe.begin(), probe.end(), 1)));
    Heightfield soft(w, h);
    for (std::size_t k = 0; k < mask.size(); ++k)
    {
      soft.z[k] = mask[k];
    }
    soft = gaussianSmooth(soft, std::max(1.0, 0.35 * roughWidth));
    for (std::size_t k = 0; k < mask.size(); ++k)
    {
      mask[k] = soft.z[k] >= 0.5f ? 1 : 0;
    }
  }
  thinMask(mask, w, h);
  const std::size_t skeleton = countOnes(mask);
  const double width =
    skeleton > 0 ? static_cast<double>(area) / static_cast<double>(skeleton) : 0.0;
  widthOut = width;

  // 8-neighbour links, skipping a diagonal when an L-shaped pair of 4-links joins the same cells.
  PixelGraph g(w, h);
  std::vector<CellEdge> edges;
  auto on = [&](int i, int j)
  { return i >= 0 && j >= 0 && i < w && j < h && mask[g.index(i, j)] != 0; };
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      if (!on(i, j))
      {
        continue;
      }
      for (int k = 0; k < 4; ++k)
      {
        const int ii = i + PixelGraph::kDx[k];
        const int jj = j + PixelGraph::kDy[k];
        if (!on(ii, jj))
        {
          continue;
        }
        if ((k == 1 || k == 3) && (on(ii, j) || on(i, jj)))
        {
          continue;
        }
        edges.push_back({ static_cast<std::uint32_t>(g.index(i, j)),
          static_cast<std::uint32_t>(g.index(ii, jj)),
          1.0f });
      }
    }
  }
  // A spanning forest removes the small cycles thinning leaves at junctions;
  // cycles longer than a few stroke widths are real loops and come back.
  PixelGraph forest = maximumSpanningForest(w, h, edges);
  const int minLoop = std::max(12, static_cast<int>(std::lround(4.0 * width)));
  std::vector<std::pair<std::size_t, int>> loops;
  for (const CellEdge& e : edges)
  {
    const int dx = g.column(e.b) - g.column(e.a);
    const int dy = g.row(e.b) - g.row(e.a);
    int k = 0;
    while (PixelGraph::kDx[k] != dx || PixelGraph::kDy[k] != dy)
    {
      ++k;
    }
    if (!forest.hasLink(e.a, k) && !connectedWithin(forest, e.a, e.b, minLoop))
    {
      loops.push_back({ e.a, k });
    }
  }
  for (const auto& [a, k] : loops)
  {
    forest.link(a, k);
  }
  const int spur = std::max(3, static_cast<int>(std::lround(2.0 * width)));
  forest.pruneShortBranches(spur);
  forest.removeSmallComponents(std::max(5, 2 * spur));

  FeatureGraph graph = buildFeatureGraph(forest, type, nullptr, o.cellSize, o.cellSize);
  smoothChains(graph, o.smoothingPasses);
  computeControlPoints(graph, o.controlRadius);
  return graph;
}

SketchFeatures strokeFeatures(const ColourImage& image, const SketchOptions& o)
{
  SketchFeatures out;
  out.kind = SketchKind::Strokes;
  const int w = image.width;
  const int h = image.height;
  const std::size_t n = pixelCount(image);
  std::vector<std::uint8_t> ridge(n, 0);
  std::vector<std::uint8_t> valley(n, 0);
  std::size_t otherColoured = 0;
  for (int r = 0; r < h; ++r)
  {
    for (int i = 0; i < w; ++i)
    {
      const std::size_t k = rowMajor(i, r, w);
      const std::uint8_t rgb[3] = {
        channel(image, k, 0), channel(image, k, 1), channel(image, k, 2)
      };
      const std::size_t g = rowMajor(i, h - 1 - r, w);
      if (isRidgeColour(rgb))
      {
        ridge[g] = 1;
      }
      else if (isValleyColour(rgb))
      {
        valley[g] = 1;
      }
      else if (std::max({ rgb[0], rgb[1], rgb[2] }) - std::min({ rgb[0], rgb[1], rgb[2] }) >= 40)
      {
        ++otherColoured;
      }
    }
  }
  const std::size_t strokes = countOnes(ridge) + countOnes(valley);
  if (strokes == 0)
  {
    throw Error("The image is in colour but has no red ridge or blue valley strokes, so it is "
                "not a stroke map (ridges R>=200 G<=80 B<=80, valleys B>=200 R<=80 G<=80).");
  }
  if (otherColoured > n / 100)
  {
    out.warnings.push_back(std::to_string(100 * otherColoured / n) +
      "% of the pixels are coloured but neither ridge red nor valley blue; they are ignored.");
  }
  out.graph.width = w;
  out.graph.height = h;
  out.graph.cellX = out.graph.cellY = o.cellSize;
  double widthSum = 0.0;
  int classes = 0;
  for (FeatureType type : { FeatureType::Ridge, FeatureType::Valley })
  {
    auto& mask = type == FeatureType::Ridge ? ridge : valley;
    if (std::count(mask.begin(), mask.end(), 1) == 0)
    {
      continue;
    }
    double width = 0.0;
    appendGraph(out.graph, strokeGraph(mask, w, h, type, o, width));
    widthSum += width;
    ++classes;
  }
  out.strokeWidth = classes > 0 ? widthSum / classes : 0.0;
  return out;
}

SketchFeatures greyFeatures(const ColourImage& image, const SketchOptions& o)
{
  SketchFeatures out;
  out.kind = SketchKind::Grey;
  const int w = image.width;
  const int h = image.height;
  Heightfield hf(w, h);
  hf.cellX = hf.cellY = o.cellSize;
  std::vector<std::size_t> histogram(256, 0);
  for (int r = 0; r < h; ++r)
  {
    for (int i = 0; i < w; ++i)
    {
      const std::size_t k = rowMajor(i, r, w);
      const std::uint8_t v = channel(image, k, 0);
      hf.at(i, h - 1 - r) = v;
      ++histogram[v];
    }
  }
  const int background =
    static_cast<int>(std::max_element(histogram.begin(), histogram.end()) - histogram.begin());
  float contrast = 0.0f;
  for (float v : hf.z)
  {
    contrast = std::max(contrast, std::abs(v - static_cast<float>(background)));
  }
  out.graph.width = w;
  out.graph.height = h;
  out.graph.cellX = out.graph.cellY = o.cellSize;
  if (contrast < 1.0f)
  {
    out.warnings.push_back("The sketch is a single shade of grey: it has no features.");
    return out;
  }
  // Stroke width from the marked area and its centre line.
  std::vector<std::uint8_t> mask(hf.size(), 0);
  for (std::size_t k = 0; k < hf.size(); ++k)
  {
    mask[k] = std::abs(hf.z[k] - static_cast<float>(background)) > 0.25f * contrast ? 1 : 0;
  }
  const double area = static_cast<double>(std::count(mask.begin(), mask.end(), 1));
  thinMask(mask, w, h);
  const double centre =
    std::max<double>(1.0, static_cast<double>(std::count(mask.begin(), mask.end(), 1)));
  out.strokeWidth = area / centre;

  // Flat-topped strokes become rounded ridges once smoothed by half their width.
  PpaOptions p;
  p.presmoothSigma = std::max(1.0, 0.5 * out.strokeWidth);
  p.halfProfileLength = std::max(3, static_cast<int>(std::ceil(out.strokeWidth)) + 1);
  p.minDip = 0.02 * contrast;
  // A drawn sketch has no noise to reject (minDip above already ignores faint
  // shading), and its strokes may cover under 1% of the image, where the DEM
  // significance's percentile relief would not see them at all.
  p.significance = 0.0;
  p.endReductions = 2;
  p.minBranchLength = std::max(7, static_cast<int>(std::lround(2.0 * out.strokeWidth)));
  p.minTreeSize = std::max(20, static_cast<int>(std::lround(4.0 * out.strokeWidth)));
  p.smoothingPasses = o.smoothingPasses;
  p.controlRadius = o.controlRadius;
  // Ridges come from strokes brighter than the background, valleys from darker
  // ones; the trough between two bright strokes is not a valley of the sketch.
  bool brighter = false;
  bool darker = false;
  for (float v : hf.z)
  {
    brighter = brighter || v > static_cast<float>(background) + 0.25f * contrast;
    darker = darker || v < static_cast<float>(background) - 0.25f * contrast;
  }
  for (FeatureType type : { FeatureType::Ridge, FeatureType::Valley })
  {
    if ((type == FeatureType::Ridge && brighter) || (type == FeatureType::Valley && darker))
    {
      FeatureExtraction e = extractFeatures(hf, type, p);
      appendGraph(out.graph, e.graph);
    }
  }
  if (out.graph.empty())
  {
    out.warnings.push_back("No ridges or valleys were found in the grey sketch.");
  }
  return out;
}

} // namespace

FeatureGraph centreLines(std::vector<std::uint8_t> mask,
  int width,
  int height,
  FeatureType type,
  const SketchOptions& options)
{
  double strokeWidth = 0.0;
  return strokeGraph(std::move(mask), width, height, type, options, strokeWidth);
}

Heightfield greyField(const ColourImage& image)
{
  Heightfield hf(image.width, image.height);
  for (int r = 0; r < image.height; ++r)
  {
    for (int i = 0; i < image.width; ++i)
    {
      hf.at(i, image.height - 1 - r) = image.pixel(i, r)[0];
    }
  }
  return hf;
}

bool isRidgeColour(const std::uint8_t* rgb)
{
  return rgb[0] >= 200 && rgb[1] <= 80 && rgb[2] <= 80;
}

bool isValleyColour(const std::uint8_t* rgb)
{
  return rgb[2] >= 200 && rgb[0] <= 80 && rgb[1] <= 80;
}

SketchKind classifySketch(const ColourImage& image)
{
  if (image.channels <= 2)
  {
    return SketchKind::Grey;
  }
  const std::size_t n = pixelCount(image);
  for (std::size_t k = 0; k < n; ++k)
  {
    const int r = channel(image, k, 0);
    const int g = channel(image, k, 1);
    const int b = channel(image, k, 2);
    if (std::max({ r, g, b }) - std::min({ r, g, b }) > 8)
    {
      return SketchKind::Strokes;
    }
  }
  return SketchKind::Grey;
}

SketchFeatures sketchFeatures(const ColourImage& image, const SketchOptions& o)
{
  if (image.width < o.patchSize || image.height < o.patchSize)
  {
    throw Error("The sketch is " + std::to_string(image.width) + " x " +
      std::to_string(image.height) + " pixels, smaller than one patch (" +
      std::to_string(o.patchSize) + " x " + std::to_string(o.patchSize) + ").");
  }
  return classifySketch(image) == SketchKind::Grey ? greyFeatures(image, o)
                                                   : strokeFeatures(image, o);
}

void thinMask(std::vector<std::uint8_t>& m, int w, int h)
{
  // Zhang and Suen (1984): two sub-iterations peel boundary cells that are
  // neither end points nor needed for connectivity.
  auto at = [&](int i, int j) -> int
  { return (i >= 0 && j >= 0 && i < w && j < h && m[rowMajor(i, j, w)] != 0) ? 1 : 0; };
  std::vector<std::size_t> remove;
  for (bool changed = true; changed;)
  {
    changed = false;
    for (int step = 0; step < 2; ++step)
    {
      remove.clear();
      for (int j = 0; j < h; ++j)
      {
        for (int i = 0; i < w; ++i)
        {
          if (at(i, j) == 0)
          {
            continue;
          }
          // P2..P9 clockwise from north (y grows north here; the rule is symmetric).
          const int p[8] = { at(i, j + 1),
            at(i + 1, j + 1),
            at(i + 1, j),
            at(i + 1, j - 1),
            at(i, j - 1),
            at(i - 1, j - 1),
            at(i - 1, j),
            at(i - 1, j + 1) };
          int neighbours = 0;
          int transitions = 0;
          for (int k = 0; k < 8; ++k)
          {
            neighbours += p[k];
            transitions += (p[k] == 0 && p[(k + 1) % 8] == 1) ? 1 : 0;
          }
          if (neighbours < 2 || neighbours > 6 || transitions != 1)
          {
            continue;
          }
          const bool first = step == 0 ? (p[0] * p[2] * p[4] == 0 && p[2] * p[4] * p[6] == 0)
                                       : (p[0] * p[2] * p[6] == 0 && p[0] * p[4] * p[6] == 0);
          if (first)
          {
            remove.push_back(rowMajor(i, j, w));
          }
        }
      }
      for (std::size_t k : remove)
      {
        m[k] = 0;
      }
      changed = changed || !remove.empty();
    }
  }
}

namespace
{

// The grid's cells reach half a cell beyond the first and last cell centres.
constexpr double kCellHalf = 0.5;

} // namespace

SegmentPart partOnGrid(const Point2& a, const Point2& b, int width, int height)
{
  const double dx = b.x - a.x;
  const double dy = b.y - a.y;
  const std::array<double, 4> p{ -dx, dx, -dy, dy };
  const std::array<double, 4> q{
    a.x + kCellHalf, width - kCellHalf - a.x, a.y + kCellHalf, height - kCellHalf - a.y
  };
  SegmentPart part;
  for (std::size_t k = 0; k < p.size(); ++k)
  {
    if (p[k] == 0.0)
    {
      if (q[k] < 0.0)
      {
        return { 1.0, 0.0 }; // parallel to this side and outside it
      }
      continue;
    }
    const double t = q[k] / p[k];
    if (p[k] < 0.0)
    {
      part.t0 = std::max(part.t0, t);
    }
    else
    {
      part.t1 = std::min(part.t1, t);
    }
  }
  return part;
}

namespace
{

// A height constraint at t along a segment (NaN if either end has none).
float constraintAt(const Polyline& line, std::size_t k, double t)
{
  if (line.elevation.size() <= k + 1)
  {
    return k < line.elevation.size() && t == 0.0 ? line.elevation[k]
                                                 : std::numeric_limits<float>::quiet_NaN();
  }
  const float a = line.elevation[k];
  const float b = line.elevation[k + 1];
  return t == 0.0 ? a : t == 1.0 ? b : static_cast<float>(a + t * (b - a));
}

// The parts of the lines inside the grid (cells -0.5 to width - 0.5): a line
// that leaves and comes back becomes two pieces; lines wholly inside are kept
// as they are. Refuses points that are not finite numbers.
std::vector<Polyline> clipToGrid(const std::vector<Polyline>& lines, int width, int height)
{
  const std::array<double, 4> box{ -kCellHalf, width - kCellHalf, -kCellHalf, height - kCellHalf };
  std::vector<Polyline> out;
  for (const Polyline& line : lines)
  {
    Polyline piece;
    piece.type = line.type;
    auto flush = [&]()
    {
      if (!piece.points.empty())
      {
        out.push_back(std::move(piece));
      }
      piece = Polyline{};
      piece.type = line.type;
    };
    auto add = [&](const Point2& p, float constraint)
    {
      piece.points.push_back(p);
      piece.elevation.push_back(constraint);
    };
    for (const Point2& p : line.points)
    {
      if (!std::isfinite(p.x) || !std::isfinite(p.y))
      {
        throw Error("A poly-line point is not a finite number; the sketch is damaged.");
      }
    }
    if (line.points.size() == 1)
    {
      const Point2& p = line.points.front();
      if (p.x >= box[0] && p.x <= box[1] && p.y >= box[2] && p.y <= box[3])
      {
        add(p, constraintAt(line, 0, 0.0));
      }
    }
    for (std::size_t k = 0; k + 1 < line.points.size(); ++k)
    {
      const Point2& a = line.points[k];
      const Point2& b = line.points[k + 1];
      const SegmentPart part = partOnGrid(a, b, width, height);
      if (part.missed())
      {
        flush();
        continue;
      }
      const double t0 = part.t0;
      const double t1 = part.t1;
      const auto at = [&](double t) {
        return t == 0.0 ? a : t == 1.0 ? b : Point2{ a.x + t * (b.x - a.x), a.y + t * (b.y - a.y) };
      };
      const Point2 from = at(t0);
      if (!piece.points.empty() &&
        (piece.points.back().x != from.x || piece.points.back().y != from.y))
      {
        flush(); // came back in elsewhere
      }
      if (piece.points.empty())
      {
        add(from, constraintAt(line, k, t0));
      }
      add(at(t1), constraintAt(line, k, t1));
      if (t1 < 1.0)
      {
        flush(); // leaves the grid here
      }
    }
    flush();
  }
  return out;
}

// The drawn lines as a graph of vertices: points closer than the snap tolerance
// are one vertex (so strokes drawn to meet do meet), each segment an edge of
// its line's type, a segment drawn twice kept once.
class SnappedLines
{
public:
  struct Vertex
  {
    Point2 p;
    float constraint = std::numeric_limits<float>::quiet_NaN();
    std::vector<std::pair<int, FeatureType>> adjacent; // (vertex, type of the segment)
  };

  SnappedLines(const std::vector<Polyline>& lines, double snapTolerance)
    : snap_(snapTolerance)
    , bucketSide_(std::max(snapTolerance, 1e-9))
  {
    for (const Polyline& line : lines)
    {
      int prev = -1;
      for (std::size_t k = 0; k < line.points.size(); ++k)
      {
        const float c =
          k < line.elevation.size() ? line.elevation[k] : std::numeric_limits<float>::quiet_NaN();
        const int v = vertexFor(line.points[k], c);
        if (prev >= 0)
        {
          addSegment(prev, v, line.type);
        }
        prev = v;
      }
    }
  }

  const std::vector<Vertex>& vertices() const { return vertices_; }
  const Vertex& at(int v) const { return byId(vertices_, v); }

private:
  // The vertex within the tolerance of p (the first one made, which takes the
  // constraint if it has none), or a new one.
  int vertexFor(const Point2& p, float constraint)
  {
    const long bx = static_cast<long>(std::floor(p.x / bucketSide_));
    const long by = static_cast<long>(std::floor(p.y / bucketSide_));
    for (long dx = -1; dx <= 1; ++dx)
    {
      for (long dy = -1; dy <= 1; ++dy)
      {
        auto it = buckets_.find({ bx + dx, by + dy });
        if (it == buckets_.end())
        {
          continue;
        }
        for (int v : it->second)
        {
          Vertex& q = byId(vertices_, v);
          if (std::hypot(q.p.x - p.x, q.p.y - p.y) <= snap_)
          {
            if (std::isnan(q.constraint))
            {
              q.constraint = constraint;
            }
            return v;
          }
        }
      }
    }
    const int id = static_cast<int>(vertices_.size());
    vertices_.push_back({ p, constraint, {} });
    buckets_[{ bx, by }].push_back(id);
    return id;
  }

  void addSegment(int a, int b, FeatureType type)
  {
    if (a == b)
    {
      return;
    }
    auto& adj = byId(vertices_, a).adjacent;
    if (std::any_of(adj.begin(), adj.end(), [&](const auto& e) { return e.first == b; }))
    {
      return; // the same segment drawn twice
    }
    adj.push_back({ b, type });
    byId(vertices_, b).adjacent.push_back({ a, type });
  }

  double snap_;
  double bucketSide_; // buckets of this side: a vertex's match lies in its 3 x 3 neighbourhood
  std::vector<Vertex> vertices_;
  std::map<std::pair<long, long>, std::vector<int>> buckets_;
};

// The feature graph of snapped lines: a node at every end and branch vertex,
// a chain along the vertices between two nodes, and each closed loop anchored
// at its first vertex.
class ChainWalker
{
public:
  ChainWalker(const SnappedLines& lines, FeatureGraph& g)
    : lines_(lines)
    , g_(g)
    , nodeOf_(lines.vertices().size(), -1)
  {
  }

  void walkAll()
  {
    const std::size_t count = lines_.vertices().size();
    for (std::size_t v = 0; v < count; ++v)
    {
      const std::size_t d = lines_.vertices()[v].adjacent.size();
      if (d == 1 || d >= 3)
      {
        addNode(static_cast<int>(v));
      }
    }
    const int realNodes = static_cast<int>(g_.nodes.size());
    for (std::size_t v = 0; v < count; ++v)
    {
      if (nodeOf_[v] >= 0 && nodeOf_[v] < realNodes)
      {
        walkFrom(static_cast<int>(v));
      }
    }
    // Closed poly-lines: anchor each loop at its first vertex.
    for (std::size_t v = 0; v < count; ++v)
    {
      const int vertex = static_cast<int>(v);
      const auto& adj = lines_.at(vertex).adjacent;
      const bool unused =
        std::any_of(adj.begin(), adj.end(), [&](const auto& e) { return !used(vertex, e.first); });
      if (nodeOf_[v] < 0 && unused)
      {
        addNode(vertex);
        walk(vertex, adj.front().first);
      }
    }
  }

private:
  void addNode(int v)
  {
    const SnappedLines::Vertex& vx = lines_.at(v);
    FeatureNode n;
    n.position = vx.p;
    n.elevation = vx.constraint;
    n.degree = static_cast<int>(vx.adjacent.size());
    n.kind = n.degree == 1 ? NodeKind::End : (n.degree >= 3 ? NodeKind::Branch : NodeKind::Path);
    n.type = vx.adjacent.empty() ? FeatureType::Ridge : vx.adjacent.front().second;
    byId(nodeOf_, v) = static_cast<int>(g_.nodes.size());
    g_.nodes.push_back(n);
  }

  static std::pair<int, int> edge(int a, int b) { return { std::min(a, b), std::max(a, b) }; }
  bool used(int a, int b) const { return used_.count(edge(a, b)) > 0; }

  // Every chain leaving vertex v along a segment not yet walked.
  void walkFrom(int v)
  {
    for (const auto& e : lines_.at(v).adjacent)
    {
      if (!used(v, e.first))
      {
        walk(v, e.first);
      }
    }
  }

  // The chain from node `start` through `first` to the next node (or to a
  // dead end of segments already walked).
  void walk(int start, int first)
  {
    FeatureChain c;
    c.from = byId(nodeOf_, start);
    c.type = FeatureType::Ridge;
    for (const auto& e : lines_.at(start).adjacent)
    {
      if (e.first == first)
      {
        c.type = e.second;
      }
    }
    auto push = [&](int v)
    {
      c.points.push_back(lines_.at(v).p);
      c.elevation.push_back(lines_.at(v).constraint);
      c.constraint.push_back(lines_.at(v).constraint);
    };
    int prev = start;
    int cur = first;
    push(start);
    while (true)
    {
      used_[edge(prev, cur)] = true;
      push(cur);
      if (byId(nodeOf_, cur) >= 0)
      {
        break;
      }
      int next = -1;
      for (const auto& e : lines_.at(cur).adjacent)
      {
        if (e.first != prev && !used(cur, e.first))
        {
          next = e.first;
          break;
        }
      }
      if (next < 0)
      {
        break;
      }
      prev = cur;
      cur = next;
    }
    c.to = byId(nodeOf_, cur);
    const int id = static_cast<int>(g_.chains.size());
    byId(g_.nodes, c.from).chains.push_back(id);
    byId(g_.nodes, c.to).chains.push_back(id);
    g_.chains.push_back(std::move(c));
  }

  const SnappedLines& lines_;
  FeatureGraph& g_;
  std::vector<int> nodeOf_; // per vertex: its node, -1 for none
  std::map<std::pair<int, int>, bool> used_;
};

} // namespace

FeatureGraph polylineFeatures(const std::vector<Polyline>& drawn,
  int width,
  int height,
  double cellX,
  double cellY,
  double snapTolerance,
  double controlRadius)
{
  // Beyond the grid nothing is sketched, and lines of any length or position
  // cost no more than the grid's own size.
  const SnappedLines lines(clipToGrid(drawn, width, height), snapTolerance);
  FeatureGraph g;
  g.width = width;
  g.height = height;
  g.cellX = cellX;
  g.cellY = cellY;
  ChainWalker(lines, g).walkAll();
  computeBreadthFirstOrder(g);
  computeControlPoints(g, controlRadius);
  return g;
}

const std::vector<OptionRow>& sketchOptionRows()
{
  static const std::vector<OptionRow> rows = []
  {
    const SketchOptions d;
    using T = OptionType;
    return std::vector<OptionRow>{
      numberRow(
        "PatchSize", "--patch", T::Integer, d.patchSize, kMinSynthesisPatch, kMaxSynthesisPatch),
      numberRow("ControlRadius", "", T::Real, 0.0, 0.0, kMaxControlRadius),
      numberRow("CellSize", "--cell", T::Real, 0.0, 0.0, kMaxCellSizeMetres),
      numberRow("SnapTolerance", "", T::Real, kDefaultSnapCells, 0.0, kMaxSnapCells),
      numberRow("SmoothingPasses", "", T::Integer, d.smoothingPasses, 0, kMaxSmoothingPasses),
    };
  }();
  return rows;
}

namespace
{
const char* const kFeatureTypeWords[] = { "ridge", "valley" };
const int kFeatureTypeValues[] = { static_cast<int>(FeatureType::Ridge),
  static_cast<int>(FeatureType::Valley) };
const char* const kLineElevationWords[] = { "none", "z", "constant" }; // by LineElevation
} // namespace

const std::vector<OptionRow>& sketchLineOptionRows()
{
  static const std::vector<OptionRow> rows = {
    choiceRow("FeatureType",
      "",
      static_cast<int>(FeatureType::Ridge),
      choicesOf(kFeatureTypeWords, kFeatureTypeValues),
      { "Ridge", "Valley" }),
    choiceRow("ElevationMode",
      "",
      static_cast<int>(LineElevation::None),
      choicesOf(kLineElevationWords),
      { "None", "From Z", "Constant" }),
    numberRow("Elevation", "", OptionType::Real, 0.0, kLowestLineElevation, kHighestLineElevation),
  };
  return rows;
}

} // namespace tsynth
