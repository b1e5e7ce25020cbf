#include "Finishing.h"

#include "../Core/Smoothing.h"
#include "../Distance/DistanceField.h"
#include "../Merging/Poisson.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>

namespace tsynth
{
namespace
{

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr std::array<int, 8> kDx{ 1, 1, 0, -1, -1, -1, 0, 1 };
constexpr std::array<int, 8> kDy{ 0, 1, 1, 1, 0, -1, -1, -1 };

// Visits the valid 8-neighbours of (i, j) with their distance in metres.
template<typename Visit>
void forNeighbours(const Heightfield& hf, int i, int j, Visit visit)
{
  for (std::size_t n = 0; n < 8; ++n)
  {
    const int x = i + kDx[n];
    const int y = j + kDy[n];
    if (x >= 0 && y >= 0 && x < hf.width && y < hf.height && hf.isValid(x, y))
    {
      visit(hf.index(x, y), std::hypot(kDx[n] * hf.cellX, kDy[n] * hf.cellY));
    }
  }
}

// Lowers each line cell below every line cell upstream of it by the minimum
// gradient; `order` lists the line cells upstream first.
void descendAlongLines(Heightfield& out,
  const std::vector<std::size_t>& order,
  const std::vector<float>& downstream,
  double gradient)
{
  for (std::size_t c : order)
  {
    const int i = static_cast<int>(c % static_cast<std::size_t>(out.width));
    const int j = static_cast<int>(c / static_cast<std::size_t>(out.width));
    forNeighbours(out,
      i,
      j,
      [&](std::size_t u, double dist)
      {
        if (downstream[u] > downstream[c])
        {
          out.z[c] = std::min(out.z[c], static_cast<float>(out.z[u] - gradient * dist));
        }
      });
  }
}

} // namespace

double correctLandform(Heightfield& out,
  const Heightfield& target,
  const std::vector<float>& confidence,
  double sigma)
{
  if (!(sigma > 0.0))
  {
    return 0.0;
  }
  const Heightfield lowOut = smoothLarge(out, sigma);
  const Heightfield lowTarget = smoothLarge(target, sigma);
  double largest = 0.0;
  for (std::size_t c = 0; c < out.size(); ++c)
  {
    if (out.isValid(c) && lowTarget.isValid(c))
    {
      const double w = confidence.empty() ? 1.0 : confidence[c];
      const double change = w * (lowTarget.z[c] - lowOut.z[c]);
      out.z[c] = static_cast<float>(out.z[c] + change);
      largest = std::max(largest, std::abs(change));
    }
  }
  return largest;
}

DrainageReport drainValleys(Heightfield& out,
  const std::vector<float>& downstream,
  const DrainageOptions& o)
{
  DrainageReport report;
  std::vector<std::size_t> order;
  std::vector<std::uint8_t> line(out.size(), 0);
  for (std::size_t c = 0; c < out.size() && c < downstream.size(); ++c)
  {
    if (std::isfinite(downstream[c]) && out.isValid(c))
    {
      order.push_back(c);
      line[c] = 1;
    }
  }
  if (order.empty())
  {
    return report;
  }
  std::sort(order.begin(),
    order.end(),
    [&](std::size_t a, std::size_t b)
    { return downstream[a] > downstream[b] || (downstream[a] == downstream[b] && a < b); });
  const Heightfield before = out;

  // 1. Floors that descend, the cut spread smoothly beside the line.
  Heightfield floors = out;
  descendAlongLines(floors, order, downstream, o.minimumGradient);
  const NearestSeeds near = nearestSeeds(line, out.width, out.height);
  for (std::size_t c = 0; c < out.size(); ++c)
  {
    if (!out.isValid(c) || near.nearest[c] < 0 || !(near.distance[c] < o.reach))
    {
      continue;
    }
    // A biweight: flat across the floor, no kink at the line or at the reach.
    const std::size_t at = static_cast<std::size_t>(near.nearest[c]);
    const double t = near.distance[c] / o.reach;
    const double fade = (1.0 - t * t) * (1.0 - t * t);
    out.z[c] = static_cast<float>(out.z[c] + (floors.z[at] - before.z[at]) * fade);
  }
  // 2. A channel: each line cell below the cells beside the line, then the
  // floors made to descend again (lowering never undoes the channel).
  const double depth = o.channelDepth * std::min(out.cellX, out.cellY);
  for (std::size_t c : order)
  {
    const int i = static_cast<int>(c % static_cast<std::size_t>(out.width));
    const int j = static_cast<int>(c / static_cast<std::size_t>(out.width));
    double side = std::numeric_limits<double>::infinity();
    forNeighbours(out,
      i,
      j,
      [&](std::size_t n, double)
      {
        if (line[n] == 0)
        {
          side = std::min(side, static_cast<double>(out.z[n]));
        }
      });
    if (std::isfinite(side) && out.z[c] > side - depth)
    {
      out.z[c] = static_cast<float>(side - depth);
    }
  }
  descendAlongLines(out, order, downstream, o.minimumGradient);

  report.cells = order.size();
  double sum = 0.0;
  for (std::size_t c : order)
  {
    const double cut = before.z[c] - out.z[c];
    report.lowered += cut > 0.0 ? 1 : 0;
    report.largest = std::max(report.largest, cut);
    sum += cut;
  }
  report.mean = sum / static_cast<double>(order.size());
  return report;
}

void meetConstraints(Heightfield& out, const FeatureGraph& graph, double reach)
{
  const int w = out.width;
  const int h = out.height;
  std::vector<double> correction(out.size(), kNaN);
  std::vector<std::uint8_t> onLine(out.size(), 0);
  bool any = false;
  for (const FeatureChain& c : graph.chains)
  {
    if (c.constraint.size() != c.points.size())
    {
      continue;
    }
    // Heights along the chain: given values, linear in between, none past the ends.
    std::vector<double> z(c.points.size(), kNaN);
    std::size_t last = c.points.size();
    for (std::size_t k = 0; k < c.points.size(); ++k)
    {
      if (std::isnan(c.constraint[k]))
      {
        continue;
      }
      z[k] = c.constraint[k];
      if (last < c.points.size())
      {
        for (std::size_t m = last + 1; m < k; ++m)
        {
          const double t = static_cast<double>(m - last) / static_cast<double>(k - last);
          z[m] = (1 - t) * c.constraint[last] + t * c.constraint[k];
        }
      }
      last = k;
    }
    for (std::size_t k = 1; k < c.points.size(); ++k)
    {
      if (std::isnan(z[k - 1]) || std::isnan(z[k]))
      {
        continue;
      }
      const Point2& a = c.points[k - 1];
      const Point2& b = c.points[k];
      const int steps =
        std::max(1, static_cast<int>(std::ceil(2.0 * std::hypot(b.x - a.x, b.y - a.y))));
      for (int s = 0; s <= steps; ++s)
      {
        const double t = static_cast<double>(s) / steps;
        const int i = static_cast<int>(std::lround(a.x + t * (b.x - a.x)));
        const int j = static_cast<int>(std::lround(a.y + t * (b.y - a.y)));
        if (i >= 0 && j >= 0 && i < w && j < h && out.isValid(i, j))
        {
          const std::size_t cell = out.index(i, j);
          correction[cell] = (1 - t) * z[k - 1] + t * z[k] - out.z[cell];
          onLine[cell] = 1;
          any = true;
        }
      }
    }
  }
  if (!any)
  {
    return;
  }
  const std::vector<float> d = distanceTransform(onLine, w, h);
  std::vector<std::uint8_t> unknown(out.size(), 0);
  for (std::size_t c = 0; c < out.size(); ++c)
  {
    if (onLine[c] == 0)
    {
      // Unknown within reach, else Dirichlet: no change.
      unknown[c] = d[c] < reach && out.isValid(c) ? 1 : 0;
      correction[c] = 0.0;
    }
  }
  std::vector<double> zero(out.size(), 0.0);
  MaskedPoissonSolver solver;
  PoissonOptions po;
  po.tolerance = 1e-6;
  solver.solveLaplacian(
    w, h, out.cellX, out.cellY, unknown.data(), zero.data(), correction.data(), po);
  for (std::size_t c = 0; c < out.size(); ++c)
  {
    if (out.isValid(c) && std::isfinite(correction[c]))
    {
      out.z[c] = static_cast<float>(out.z[c] + correction[c]);
    }
  }
}

} // namespace tsynth
