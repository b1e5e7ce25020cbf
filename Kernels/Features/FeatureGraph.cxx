#include "FeatureGraph.h"

#include "../Core/Grid.h"
#include "../Core/Heightfield.h"
#include "PixelGraph.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <numeric>

namespace tsynth
{
namespace
{

float heightAt(const Heightfield* hf, int i, int j)
{
  if (hf == nullptr || !hf->isValid(i, j))
  {
    return std::numeric_limits<float>::quiet_NaN();
  }
  return hf->at(i, j);
}

} // namespace

void forEachChainCell(const FeatureChain& chain,
  int width,
  int height,
  const std::function<void(int, int, std::size_t, double)>& visit)
{
  for (std::size_t k = 1; k < chain.points.size(); ++k)
  {
    const Point2& a = chain.points[k - 1];
    const Point2& b = chain.points[k];
    const int steps =
      std::max(1, static_cast<int>(std::ceil(2.0 * std::hypot(b.x - a.x, b.y - a.y))));
    for (int s = 0; s <= steps; ++s)
    {
      const double t = static_cast<double>(s) / steps;
      const int i = static_cast<int>(std::lround(a.x + t * (b.x - a.x)));
      const int j = static_cast<int>(std::lround(a.y + t * (b.y - a.y)));
      if (i >= 0 && j >= 0 && i < width && j < height)
      {
        visit(i, j, k, t);
      }
    }
  }
}

std::vector<std::uint8_t> rasteriseChains(const FeatureGraph& graph, int width, int height)
{
  std::vector<std::uint8_t> cells(cellCount(width, height), 0);
  for (const FeatureChain& c : graph.chains)
  {
    forEachChainCell(c,
      width,
      height,
      [&](int i, int j, std::size_t, double) { cells[rowMajor(i, j, width)] = 1; });
  }
  return cells;
}

double FeatureChain::length() const
{
  double sum = 0.0;
  for (std::size_t k = 1; k < points.size(); ++k)
  {
    sum += std::hypot(points[k].x - points[k - 1].x, points[k].y - points[k - 1].y);
  }
  return sum;
}

int FeatureGraph::countKind(NodeKind kind) const
{
  return static_cast<int>(std::count_if(
    nodes.begin(), nodes.end(), [&](const FeatureNode& n) { return n.kind == kind; }));
}

int FeatureGraph::countKind(NodeKind kind, FeatureType type) const
{
  return static_cast<int>(std::count_if(nodes.begin(),
    nodes.end(),
    [&](const FeatureNode& n) { return n.kind == kind && n.type == type; }));
}

FeatureGraph buildFeatureGraph(const PixelGraph& pixels,
  FeatureType type,
  const Heightfield* heights,
  double cellX,
  double cellY)
{
  FeatureGraph g;
  g.width = pixels.width();
  g.height = pixels.height();
  g.cellX = cellX;
  g.cellY = cellY;

  std::vector<int> nodeOf(pixels.size(), -1);
  auto addNode = [&](std::size_t idx)
  {
    FeatureNode n;
    n.position = { static_cast<double>(pixels.column(idx)), static_cast<double>(pixels.row(idx)) };
    n.elevation = heightAt(heights, pixels.column(idx), pixels.row(idx));
    n.degree = pixels.degree(idx);
    n.kind = n.degree == 1 ? NodeKind::End : (n.degree >= 3 ? NodeKind::Branch : NodeKind::Path);
    n.type = type;
    nodeOf[idx] = static_cast<int>(g.nodes.size());
    g.nodes.push_back(n);
  };
  for (std::size_t idx = 0; idx < pixels.size(); ++idx)
  {
    const int d = pixels.degree(idx);
    if (d == 1 || d >= 3)
    {
      addNode(idx);
    }
  }

  // visited[idx] bit k: the edge from idx in direction k is already in a chain.
  std::vector<std::uint8_t> visited(pixels.size(), 0);
  auto markEdge = [&](std::size_t idx, int k)
  {
    visited[idx] = static_cast<std::uint8_t>(visited[idx] | (1U << k));
    const std::size_t n = pixels.neighbour(idx, k);
    visited[n] = static_cast<std::uint8_t>(visited[n] | (1U << PixelGraph::opposite(k)));
  };
  auto walk = [&](std::size_t start, int firstDirection)
  {
    FeatureChain c;
    c.type = type;
    c.from = nodeOf[start];
    std::size_t cur = start;
    int k = firstDirection;
    c.points.push_back(
      { static_cast<double>(pixels.column(cur)), static_cast<double>(pixels.row(cur)) });
    c.elevation.push_back(heightAt(heights, pixels.column(cur), pixels.row(cur)));
    while (true)
    {
      markEdge(cur, k);
      cur = pixels.neighbour(cur, k);
      c.points.push_back(
        { static_cast<double>(pixels.column(cur)), static_cast<double>(pixels.row(cur)) });
      c.elevation.push_back(heightAt(heights, pixels.column(cur), pixels.row(cur)));
      if (nodeOf[cur] >= 0)
      {
        break;
      }
      int next = -1;
      for (int m = 0; m < 8; ++m)
      {
        if (pixels.hasLink(cur, m) && ((visited[cur] >> m) & 1U) == 0)
        {
          next = m;
          break;
        }
      }
      if (next < 0)
      {
        break; // cannot happen in a consistent graph; stop rather than loop
      }
      k = next;
    }
    c.to = nodeOf[cur];
    const int id = static_cast<int>(g.chains.size());
    byId(g.nodes, c.from).chains.push_back(id);
    byId(g.nodes, c.to).chains.push_back(id);
    g.chains.push_back(std::move(c));
  };

  for (std::size_t n = 0; n < g.nodes.size(); ++n)
  {
    const auto& p = g.nodes[n].position;
    const std::size_t idx = pixels.index(static_cast<int>(p.x), static_cast<int>(p.y));
    for (int k = 0; k < 8; ++k)
    {
      if (pixels.hasLink(idx, k) && ((visited[idx] >> k) & 1U) == 0)
      {
        walk(idx, k);
      }
    }
  }
  // Closed loops of degree-2 cells: anchor each at its first cell in raster order.
  for (std::size_t idx = 0; idx < pixels.size(); ++idx)
  {
    if (pixels.links(idx) != 0 && visited[idx] == 0)
    {
      addNode(idx);
      for (int k = 0; k < 8; ++k)
      {
        if (pixels.hasLink(idx, k))
        {
          walk(idx, k);
          break;
        }
      }
    }
  }
  computeBreadthFirstOrder(g);
  return g;
}

void smoothChains(FeatureGraph& graph, int passes)
{
  for (FeatureChain& c : graph.chains)
  {
    const std::size_t n = c.points.size();
    if (n < 3)
    {
      continue;
    }
    std::vector<Point2> next = c.points;
    for (int pass = 0; pass < passes; ++pass)
    {
      for (std::size_t k = 1; k + 1 < n; ++k)
      {
        next[k].x = 0.25 * c.points[k - 1].x + 0.5 * c.points[k].x + 0.25 * c.points[k + 1].x;
        next[k].y = 0.25 * c.points[k - 1].y + 0.5 * c.points[k].y + 0.25 * c.points[k + 1].y;
      }
      c.points = next;
    }
  }
}

void computeBreadthFirstOrder(FeatureGraph& g)
{
  const std::size_t n = g.nodes.size();
  std::vector<int> component(n, -1);
  std::vector<std::vector<int>> members;
  for (std::size_t s = 0; s < n; ++s)
  {
    if (component[s] >= 0)
    {
      continue;
    }
    const int id = static_cast<int>(members.size());
    members.emplace_back();
    std::vector<int> stack{ static_cast<int>(s) };
    component[s] = id;
    while (!stack.empty())
    {
      const int v = stack.back();
      stack.pop_back();
      members.back().push_back(v);
      for (int c : byId(g.nodes, v).chains)
      {
        const FeatureChain& ch = byId(g.chains, c);
        const int w = ch.from == v ? ch.to : ch.from;
        if (byId(component, w) < 0)
        {
          byId(component, w) = id;
          stack.push_back(w);
        }
      }
    }
  }
  std::vector<double> length(members.size(), 0.0);
  for (const FeatureChain& c : g.chains)
  {
    byId(length, byId(component, c.from)) += c.length();
  }
  std::vector<std::size_t> order(members.size());
  std::iota(order.begin(), order.end(), std::size_t{ 0 });
  std::stable_sort(order.begin(),
    order.end(),
    [&](std::size_t a, std::size_t b) { return length[a] > length[b]; });

  g.bfsOrder.clear();
  g.componentCount = static_cast<int>(members.size());
  std::vector<char> seen(n, 0);
  for (std::size_t rank = 0; rank < order.size(); ++rank)
  {
    const auto& m = members[order[rank]];
    int root = m.front();
    for (int v : m)
    {
      const FeatureNode& a = byId(g.nodes, v);
      const FeatureNode& b = byId(g.nodes, root);
      const float ea =
        std::isnan(a.elevation) ? -std::numeric_limits<float>::infinity() : a.elevation;
      const float eb =
        std::isnan(b.elevation) ? -std::numeric_limits<float>::infinity() : b.elevation;
      if (a.degree > b.degree || (a.degree == b.degree && (ea > eb || (ea == eb && v < root))))
      {
        root = v;
      }
    }
    std::deque<int> queue{ root };
    byId(seen, root) = 1;
    while (!queue.empty())
    {
      const int v = queue.front();
      queue.pop_front();
      byId(g.nodes, v).component = static_cast<int>(rank);
      g.bfsOrder.push_back(v);
      for (int c : byId(g.nodes, v).chains)
      {
        const FeatureChain& ch = byId(g.chains, c);
        const int w = ch.from == v ? ch.to : ch.from;
        if (byId(seen, w) == 0)
        {
          byId(seen, w) = 1;
          queue.push_back(w);
        }
      }
    }
  }
}

void computeControlPoints(FeatureGraph& g, double radius)
{
  for (std::size_t v = 0; v < g.nodes.size(); ++v)
  {
    FeatureNode& node = g.nodes[v];
    node.controls.clear();
    // A loop chain (from == to == v) is listed twice: leave by its start, then by its end.
    std::vector<int> usedLoopStart;
    for (int c : node.chains)
    {
      const FeatureChain& ch = byId(g.chains, c);
      bool forward = ch.from == static_cast<int>(v);
      if (ch.from == ch.to)
      {
        forward = std::find(usedLoopStart.begin(), usedLoopStart.end(), c) == usedLoopStart.end();
        if (forward)
        {
          usedLoopStart.push_back(c);
        }
      }
      const std::size_t n = ch.points.size();
      auto at = [&](std::size_t k) { return forward ? ch.points[k] : ch.points[n - 1 - k]; };
      ControlPoint cp;
      cp.chain = c;
      cp.position = at(n - 1);
      const Point2 o = node.position;
      for (std::size_t k = 1; k < n; ++k)
      {
        const Point2 a = at(k - 1);
        const Point2 b = at(k);
        const double db = std::hypot(b.x - o.x, b.y - o.y);
        if (db >= radius)
        {
          // Exact crossing: |a + t (b - a) - o| = radius; a is inside, b is not.
          const double ux = b.x - a.x;
          const double uy = b.y - a.y;
          const double wx = a.x - o.x;
          const double wy = a.y - o.y;
          const double qa = ux * ux + uy * uy;
          const double qb = 2.0 * (ux * wx + uy * wy);
          const double qc = wx * wx + wy * wy - radius * radius;
          const double t =
            qa > 0.0 ? (-qb + std::sqrt(std::max(0.0, qb * qb - 4.0 * qa * qc))) / (2.0 * qa) : 1.0;
          cp.position = { a.x + t * ux, a.y + t * uy };
          cp.reached = true;
          break;
        }
      }
      cp.angle = std::atan2(cp.position.y - o.y, cp.position.x - o.x);
      node.controls.push_back(cp);
    }
  }
}

namespace
{

// Union-find over the nodes, by path halving.
class NodeSets
{
public:
  explicit NodeSets(std::size_t n)
    : parent_(n)
  {
    std::iota(parent_.begin(), parent_.end(), std::size_t{ 0 });
  }
  std::size_t root(std::size_t k)
  {
    while (parent_[k] != k)
    {
      parent_[k] = parent_[parent_[k]];
      k = parent_[k];
    }
    return k;
  }
  void join(std::size_t a, std::size_t b) { parent_[root(a)] = root(b); }

private:
  std::vector<std::size_t> parent_;
};

} // namespace

std::vector<std::size_t> connectedChainSets(const FeatureGraph& graph, std::size_t* count)
{
  const std::size_t nodes = graph.nodes.size();
  auto valid = [&](int id) { return id >= 0 && static_cast<std::size_t>(id) < nodes; };
  NodeSets sets(nodes);
  for (const FeatureChain& c : graph.chains)
  {
    if (valid(c.from) && valid(c.to))
    {
      sets.join(static_cast<std::size_t>(c.from), static_cast<std::size_t>(c.to));
    }
  }
  constexpr std::size_t kUnnumbered = std::numeric_limits<std::size_t>::max();
  std::vector<std::size_t> numberOfRoot(nodes, kUnnumbered);
  std::vector<std::size_t> out(graph.chains.size());
  std::size_t next = 0;
  for (std::size_t c = 0; c < graph.chains.size(); ++c)
  {
    const int from = graph.chains[c].from;
    const int to = graph.chains[c].to;
    if (!valid(from) || !valid(to))
    {
      out[c] = next++;
      continue;
    }
    std::size_t& number = numberOfRoot[sets.root(static_cast<std::size_t>(from))];
    if (number == kUnnumbered)
    {
      number = next++;
    }
    out[c] = number;
  }
  if (count != nullptr)
  {
    *count = next;
  }
  return out;
}

void appendGraph(FeatureGraph& a, const FeatureGraph& b)
{
  const int nodeOffset = static_cast<int>(a.nodes.size());
  const int chainOffset = static_cast<int>(a.chains.size());
  if (a.nodes.empty() && a.chains.empty())
  {
    a.width = b.width;
    a.height = b.height;
    a.cellX = b.cellX;
    a.cellY = b.cellY;
  }
  for (FeatureNode n : b.nodes)
  {
    for (int& c : n.chains)
    {
      c += chainOffset;
    }
    for (ControlPoint& cp : n.controls)
    {
      cp.chain += chainOffset;
    }
    a.nodes.push_back(std::move(n));
  }
  for (FeatureChain c : b.chains)
  {
    c.from += nodeOffset;
    c.to += nodeOffset;
    a.chains.push_back(std::move(c));
  }
  computeBreadthFirstOrder(a);
}

} // namespace tsynth
