// Ridge and valley lines as a graph: end and branch nodes joined by chains
// (polylines), with the breadth-first order and control points the matcher and
// the placement use.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace tsynth
{

// Element `id` of a vector indexed by int ids (nodes, chains, components,
// vertices; -1 = none), which must be valid here: the one place the id
// becomes an index.
template<class Vector>
auto& byId(Vector& v, int id)
{
  return v[static_cast<std::size_t>(id)];
}

struct Heightfield;
class PixelGraph;

enum class FeatureType : std::int8_t
{
  Ridge = 1,
  Valley = -1
};

enum class NodeKind : std::uint8_t
{
  Path = 0,  // a degree-2 anchor on a closed loop with no other node
  End = 1,   // degree 1
  Branch = 2 // degree >= 3
};

struct Point2
{
  double x = 0.0; // grid columns (cell units), x east
  double y = 0.0; // grid rows (cell units), y north
};

// Where a chain leaving a node crosses the circle of the control radius.
struct ControlPoint
{
  Point2 position;
  double angle = 0.0; // direction from the node, radians counter-clockwise from east (cell units)
  int chain = -1;
  bool reached = false; // false: the chain ended inside the circle; position is its end
};

struct FeatureNode
{
  Point2 position;
  float elevation = 0.0f;
  NodeKind kind = NodeKind::End;
  int degree = 0;
  int component = -1;
  FeatureType type = FeatureType::Ridge;
  std::vector<int> chains;            // incident chain ids (a loop chain appears twice)
  std::vector<ControlPoint> controls; // one per incident chain end, in the order of `chains`
};

struct FeatureChain
{
  int from = -1;
  int to = -1;
  FeatureType type = FeatureType::Ridge;
  std::vector<Point2> points;    // from node .. to node, inclusive
  std::vector<float> elevation;  // height at each point (NaN where unknown)
  std::vector<float> constraint; // requested height (poly-line Elevation); empty or NaN = none

  double length() const; // in cells
};

struct FeatureGraph
{
  int width = 0; // the grid the cell coordinates refer to
  int height = 0;
  double cellX = 1.0;
  double cellY = 1.0;
  std::vector<FeatureNode> nodes;
  std::vector<FeatureChain> chains;
  std::vector<int> bfsOrder; // node ids, component by component
  int componentCount = 0;

  bool empty() const { return nodes.empty(); }
  int countKind(NodeKind kind) const;
  int countKind(NodeKind kind, FeatureType type) const;
};

// Turns a pixel graph into nodes and chains. Node and chain positions are cell
// centres; elevations come from `heights` when given (else NaN).
FeatureGraph buildFeatureGraph(const PixelGraph& pixels,
  FeatureType type,
  const Heightfield* heights,
  double cellX,
  double cellY);

// Moves chain interior points towards their neighbours' average (nodes stay),
// `passes` times: removes the staircase of cell-centre polylines.
void smoothChains(FeatureGraph& graph, int passes);

// Components and breadth-first order: components by decreasing total chain
// length, each walked from its highest-degree node (ties: higher elevation,
// then lower id). Fills node.component, bfsOrder and componentCount.
void computeBreadthFirstOrder(FeatureGraph& graph);

// Control points of every node on a circle of `radius` cells.
void computeControlPoints(FeatureGraph& graph, double radius);

// Visits the cells (i, j) under a chain's polyline, drawn in steps of at most
// half a cell, with the segment k (points k - 1 to k) and the position t (0..1)
// along it; cells off the width x height grid are skipped.
void forEachChainCell(const FeatureChain& chain,
  int width,
  int height,
  const std::function<void(int i, int j, std::size_t k, double t)>& visit);

// The cells under the chains of a graph (forEachChainCell's), 1 on a
// width x height grid of 0.
std::vector<std::uint8_t> rasteriseChains(const FeatureGraph& graph, int width, int height);

// Per chain, the number of the connected set of chains it belongs to (chains
// joined at their nodes: all of a letter's strokes, a whole valley network),
// numbered from 0 in the order of their first chains; `count`, if given,
// receives the number of sets. A chain whose nodes are missing is a set alone.
std::vector<std::size_t> connectedChainSets(const FeatureGraph& graph,
  std::size_t* count = nullptr);

// Appends b's nodes and chains to a (renumbered) and recomputes the order.
void appendGraph(FeatureGraph& a, const FeatureGraph& b);

} // namespace tsynth
