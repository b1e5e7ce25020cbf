#include "Profiles.h"

#include <cmath>
#include <limits>

namespace tsynth
{

float sampleBilinear(const Heightfield& hf, double x, double y)
{
  const float nan = std::numeric_limits<float>::quiet_NaN();
  if (!(x >= 0.0) || !(y >= 0.0) || x > hf.width - 1 || y > hf.height - 1)
  {
    return nan;
  }
  const int i = std::min(static_cast<int>(x), hf.width - 2 < 0 ? 0 : hf.width - 2);
  const int j = std::min(static_cast<int>(y), hf.height - 2 < 0 ? 0 : hf.height - 2);
  const int i1 = std::min(i + 1, hf.width - 1);
  const int j1 = std::min(j + 1, hf.height - 1);
  if (!hf.isValid(i, j) || !hf.isValid(i1, j) || !hf.isValid(i, j1) || !hf.isValid(i1, j1))
  {
    return nan;
  }
  const double fx = x - i;
  const double fy = y - j;
  const double top = (1 - fx) * hf.at(i, j1) + fx * hf.at(i1, j1);
  const double bottom = (1 - fx) * hf.at(i, j) + fx * hf.at(i1, j);
  return static_cast<float>((1 - fy) * bottom + fy * top);
}

std::vector<std::vector<ChainProfile>> sampleProfiles(const FeatureGraph& graph,
  const Heightfield& hf,
  const ProfileOptions& o)
{
  std::vector<std::vector<ChainProfile>> out(graph.nodes.size());
  for (std::size_t v = 0; v < graph.nodes.size(); ++v)
  {
    const FeatureNode& node = graph.nodes[v];
    for (const ControlPoint& cp : node.controls)
    {
      ChainProfile p;
      p.chain = cp.chain;
      // Along: the chain's polyline from the node to the control point, by arc length.
      const FeatureChain& ch = graph.chains[static_cast<std::size_t>(cp.chain)];
      const bool forward = std::hypot(ch.points.front().x - node.position.x,
                             ch.points.front().y - node.position.y) <= 1e-9;
      std::vector<Point2> path;
      for (std::size_t k = 0; k < ch.points.size(); ++k)
      {
        const Point2& q = forward ? ch.points[k] : ch.points[ch.points.size() - 1 - k];
        path.push_back(q);
        if (std::hypot(q.x - node.position.x, q.y - node.position.y) >=
          std::hypot(cp.position.x - node.position.x, cp.position.y - node.position.y))
        {
          path.back() = cp.position;
          break;
        }
      }
      std::vector<double> cumulative{ 0.0 };
      for (std::size_t k = 1; k < path.size(); ++k)
      {
        cumulative.push_back(
          cumulative.back() + std::hypot(path[k].x - path[k - 1].x, path[k].y - path[k - 1].y));
      }
      const int na = std::max(2, o.alongSamples);
      std::size_t seg = 1;
      for (int s = 0; s < na; ++s)
      {
        const double t = cumulative.back() * s / (na - 1);
        while (seg + 1 < path.size() && cumulative[seg] < t)
        {
          ++seg;
        }
        Point2 q = path.front();
        if (path.size() > 1)
        {
          const double len = cumulative[seg] - cumulative[seg - 1];
          const double u = len > 0.0 ? (t - cumulative[seg - 1]) / len : 0.0;
          q = { path[seg - 1].x + u * (path[seg].x - path[seg - 1].x),
            path[seg - 1].y + u * (path[seg].y - path[seg - 1].y) };
        }
        p.along.push_back(sampleBilinear(hf, q.x, q.y));
      }
      // Across: perpendicular to the node -> control point direction.
      const double nx = -std::sin(cp.angle);
      const double ny = std::cos(cp.angle);
      const int nc = std::max(1, o.acrossSamples);
      for (int s = 0; s < nc; ++s)
      {
        const double d = nc == 1 ? 0.0 : o.acrossHalfLength * (1.0 - 2.0 * s / (nc - 1));
        p.across.push_back(sampleBilinear(hf, cp.position.x + d * nx, cp.position.y + d * ny));
      }
      out[v].push_back(std::move(p));
    }
  }
  return out;
}

} // namespace tsynth
