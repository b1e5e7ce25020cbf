#include "FeatureOrder.h"

#include "../Core/Grid.h"
#include "../Core/Random.h"
#include "Finishing.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tsynth
{
namespace
{

constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();

} // namespace

std::vector<FeatureSite> featurePlacementOrder(const SynthesisTarget& target,
  int patchSize,
  std::uint64_t seed)
{
  const FeatureGraph& g = target.graph;
  std::vector<double> phases(g.chains.size());
  for (std::size_t c = 0; c < phases.size(); ++c)
  {
    phases[c] = seededUniform(seed, kStreamSites, c);
  }
  const std::vector<FeatureSite> all =
    featureSites(g, patchSize, kSiteSpacingInPatches * patchSize, &phases);
  std::vector<std::vector<std::size_t>> pathsOfChain(g.chains.size());
  std::vector<std::size_t> siteOfNode(g.nodes.size(), kNone);
  for (std::size_t s = 0; s < all.size(); ++s)
  {
    if (all[s].node >= 0)
    {
      siteOfNode[static_cast<std::size_t>(all[s].node)] = s;
    }
    else if (all[s].chain >= 0)
    {
      pathsOfChain[static_cast<std::size_t>(all[s].chain)].push_back(s);
    }
  }
  std::vector<FeatureSite> ordered;
  std::vector<char> chainDone(g.chains.size(), 0);
  for (int v : g.bfsOrder)
  {
    const std::size_t node = static_cast<std::size_t>(v);
    if (siteOfNode[node] != kNone)
    {
      ordered.push_back(all[siteOfNode[node]]);
    }
    for (int c : g.nodes[node].chains)
    {
      const std::size_t chain = static_cast<std::size_t>(c);
      if (chainDone[chain] != 0)
      {
        continue;
      }
      chainDone[chain] = 1;
      auto paths = pathsOfChain[chain];
      if (g.chains[chain].to == v)
      {
        std::reverse(paths.begin(), paths.end()); // walk away from this node
      }
      for (std::size_t s : paths)
      {
        ordered.push_back(all[s]);
      }
    }
  }
  if (!featureSitesCrowd(target, patchSize))
  {
    return ordered;
  }
  return spacedOut(
    ordered, kSiteClearanceInPatches * patchSize, target.field.width, target.field.height);
}

bool featureSitesCrowd(const SynthesisTarget& target, int patchSize)
{
  const double spacing = lineSpacing(target);
  return target.detailed || (spacing > 0.0 && spacing < kFinestDrawnSpacingInPatches * patchSize);
}

// A grid of buckets one clearance wide holds the kept sites.
std::vector<FeatureSite> spacedOut(const std::vector<FeatureSite>& sites,
  double clearance,
  int width,
  int height)
{
  const int columns = std::max(1, static_cast<int>(std::ceil(width / clearance)) + 1);
  const int rows = std::max(1, static_cast<int>(std::ceil(height / clearance)) + 1);
  std::vector<std::vector<Point2>> buckets(cellCount(columns, rows));
  auto bucketOf = [&](double v, int count)
  { return std::clamp(static_cast<int>(std::floor(v / clearance)), 0, count - 1); };
  auto bucket = [&](int x, int y) -> std::vector<Point2>&
  { return buckets[rowMajor(x, y, columns)]; };
  std::vector<FeatureSite> kept;
  for (const FeatureSite& site : sites)
  {
    const int bx = bucketOf(site.centre.x, columns);
    const int by = bucketOf(site.centre.y, rows);
    bool near = false;
    for (int y = std::max(0, by - 1); y <= std::min(rows - 1, by + 1) && !near; ++y)
    {
      for (int x = std::max(0, bx - 1); x <= std::min(columns - 1, bx + 1) && !near; ++x)
      {
        for (const Point2& q : bucket(x, y))
        {
          if (std::hypot(q.x - site.centre.x, q.y - site.centre.y) < clearance)
          {
            near = true;
            break;
          }
        }
      }
    }
    if (!near)
    {
      kept.push_back(site);
      bucket(bx, by).push_back(site.centre);
    }
  }
  return kept;
}

} // namespace tsynth
