#include "FeatureCost.h"

#include "FeatureCostTerms.h"

#include <algorithm>
#include <numeric>

namespace tsynth
{

std::vector<float> scoreFeatureCandidates(const CandidatePool& pool,
  const FeatureQuery& query,
  const MatchWeights& weights)
{
  std::vector<float> costs(pool.size());
  const featurecost::ScoredQuery scored(pool, query, weights);
  const std::size_t n = pool.size();
#pragma omp parallel for schedule(static)
  for (std::size_t c = 0; c < n; ++c)
  {
    costs[c] = scored.costOf(c);
  }
  return costs;
}

std::vector<RankedCandidate> topK(const std::vector<float>& costs, std::size_t k)
{
  std::vector<std::size_t> idx(costs.size());
  std::iota(idx.begin(), idx.end(), 0);
  k = std::min(k, idx.size());
  auto less = [&](std::size_t a, std::size_t b)
  { return costs[a] < costs[b] || (costs[a] == costs[b] && a < b); };
  std::partial_sort(idx.begin(), idx.begin() + static_cast<long>(k), idx.end(), less);
  std::vector<RankedCandidate> out;
  for (std::size_t r = 0; r < k; ++r)
  {
    out.push_back({ idx[r], costs[idx[r]] });
  }
  return out;
}

std::vector<RankedCandidate> topKPerExemplar(const CandidatePool& pool,
  const std::vector<float>& costs,
  std::size_t k)
{
  std::vector<RankedCandidate> merged;
  for (const ExemplarInfo& e : pool.exemplars)
  {
    std::vector<float> part(costs.begin() + static_cast<long>(e.firstCandidate),
      costs.begin() + static_cast<long>(e.firstCandidate + e.candidateCount));
    for (RankedCandidate r : topK(part, k))
    {
      r.index += e.firstCandidate;
      merged.push_back(r);
    }
  }
  std::stable_sort(merged.begin(),
    merged.end(),
    [](const RankedCandidate& a, const RankedCandidate& b)
    { return a.cost < b.cost || (a.cost == b.cost && a.index < b.index); });
  return merged;
}

} // namespace tsynth
