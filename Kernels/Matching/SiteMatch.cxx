#include "SiteMatch.h"

#include "../Core/Error.h"
#include "../Core/Grid.h"
#include "../Features/Ppa.h"
#include "CandidatePool.h"
#include "NoiseVariance.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tsynth
{
namespace
{

// The patch-sized window of the target around (cx, cy) cells, with its known mask.
DenseQuery windowAround(const Heightfield& target,
  const std::vector<std::uint8_t>& known,
  double cx,
  double cy,
  int size)
{
  DenseQuery q;
  q.heights.assign(cellCount(size, size), 0.0f);
  q.known.assign(cellCount(size, size), 0);
  const int x0 = windowCorner(cx, size);
  const int y0 = windowCorner(cy, size);
  for (int j = 0; j < size; ++j)
  {
    for (int i = 0; i < size; ++i)
    {
      const int x = x0 + i;
      const int y = y0 + j;
      if (x < 0 || y < 0 || x >= target.width || y >= target.height || !target.isValid(x, y))
      {
        continue;
      }
      const std::size_t k = rowMajor(i, j, size);
      q.heights[k] = target.at(x, y);
      q.known[k] = known[target.index(x, y)];
    }
  }
  return q;
}

// The target feature site nearest (cx, cy) within half a patch, or null.
const FeatureSite* nearestSite(const std::vector<FeatureSite>& sites,
  double cx,
  double cy,
  int patch)
{
  const FeatureSite* nearest = nullptr;
  double best = 0.5 * patch;
  for (const auto& s : sites)
  {
    const double d = std::hypot(s.centre.x - cx, s.centre.y - cy);
    if (d <= best)
    {
      best = d;
      nearest = &s;
    }
  }
  return nearest;
}

// Feature mode's map: each pool candidate of exemplar 0 at its centre.
void mapFeatureCosts(const CandidatePool& pool,
  const std::vector<float>& costs,
  int width,
  std::vector<float>& map)
{
  for (std::size_t c = 0; c < costs.size(); ++c)
  {
    if (pool.exemplar[c] != 0)
    {
      continue;
    }
    const int i = static_cast<int>(std::lround(pool.centreX[c]));
    const int j = static_cast<int>(std::lround(pool.centreY[c]));
    float& v = map[rowMajor(i, j, width)];
    v = std::isnan(v) ? costs[c] : std::min(v, costs[c]);
  }
}

// Dense mode's map: the coarse cost of the unrotated exemplar 0, block by block.
void mapDenseCosts(const DenseMatcher& dense,
  const DenseQuery& window,
  int width,
  int height,
  int patch,
  std::vector<float>& map)
{
  const auto coarse = dense.coarseCosts(dense.coarseQuery(window));
  const int f = std::max(1, dense.options().coarseFactor);
  const auto& oriented = dense.oriented();
  for (std::size_t r = 0; r < oriented.size(); ++r)
  {
    if (oriented[r].exemplar != 0 || oriented[r].variant != 0)
    {
      continue;
    }
    for (int by = 0; by < oriented[r].offsetsY; ++by)
    {
      for (int bx = 0; bx < oriented[r].offsetsX; ++bx)
      {
        const float v = coarse[r][rowMajor(bx, by, oriented[r].offsetsX)];
        for (int j = 0; j < f; ++j)
        {
          for (int i = 0; i < f; ++i)
          {
            const int ci = bx * f + i + patch / 2;
            const int cj = by * f + j + patch / 2;
            if (ci < width && cj < height && std::isfinite(v))
            {
              map[rowMajor(ci, cj, width)] = v;
            }
          }
        }
      }
    }
  }
}

} // namespace

SiteMatchResult matchAtSite(PatchMatcher& matcher,
  const Heightfield& target,
  const std::vector<std::uint8_t>& known,
  double siteX,
  double siteY,
  bool featureMode,
  int patchSize)
{
  if (target.width < patchSize || target.height < patchSize)
  {
    throw Error("The target is " + std::to_string(target.width) + " x " +
      std::to_string(target.height) + " cells, smaller than one patch (" +
      std::to_string(patchSize) + "); use a smaller patch size.");
  }
  if (known.size() != target.size())
  {
    throw Error("The known mask has " + std::to_string(known.size()) + " values for " +
      std::to_string(target.size()) + " target cells: give one per cell.");
  }
  SiteMatchResult r;
  r.centreX = siteX;
  r.centreY = siteY;
  std::vector<float> featureCosts;
  if (featureMode)
  {
    FeatureGraph graph = extractFeatures(target, FeatureType::Ridge, {}).graph;
    appendGraph(graph, extractFeatures(target, FeatureType::Valley, {}).graph);
    const std::vector<FeatureSite> sites = featureSites(graph, patchSize);
    if (const FeatureSite* site = nearestSite(sites, siteX, siteY, patchSize))
    {
      r.centreX = site->centre.x;
      r.centreY = site->centre.y;
      const NoiseVariance noise(target);
      const FeatureQuery q = makeFeatureQuery(*site, target, noise, &target, &known, patchSize);
      const DenseQuery window = windowAround(target, known, r.centreX, r.centreY, patchSize);
      featureCosts = matcher.featureCosts(q);
      r.candidates = matcher.matchFeature(q, &window);
      r.atFeature = true;
    }
    else
    {
      r.warnings.push_back(
        "No target feature within half a patch of the site: matching without features.");
    }
  }
  const DenseQuery window = windowAround(target, known, r.centreX, r.centreY, patchSize);
  if (r.candidates.empty())
  {
    r.candidates = matcher.matchDense(window);
  }
  r.warnings.insert(r.warnings.end(), matcher.warnings().begin(), matcher.warnings().end());
  const ExemplarInfo& first = matcher.pool().exemplars.front();
  r.costMap.assign(cellCount(first.width, first.height), std::numeric_limits<float>::quiet_NaN());
  if (!featureCosts.empty())
  {
    mapFeatureCosts(matcher.pool(), featureCosts, first.width, r.costMap);
  }
  else
  {
    mapDenseCosts(matcher.dense(), window, first.width, first.height, patchSize, r.costMap);
  }
  return r;
}

} // namespace tsynth
