// Feature cost c = a_f c_f + a_a c_a + a_n c_n + a_o c_o (Tasse's thesis, 3.4.1)
// of every candidate of a pool against one target site, and top-k selection.
// Every term is dimensionless: heights are divided by the pool's height scale,
// angles by pi, so the default weights mean the same on any DEM and unit.
#pragma once

#include "CandidatePool.h"

#include <vector>

namespace tsynth
{

struct MatchWeights
{
  double feature = 5.0; // a_f: profiles along and across the arms
  double angle = 2.0;   // a_a: arm directions
  // a_n: roughness, the multi-resolution noise variances compared scale-free
  // (each level's squared relative difference, as the fill's roughnessMisfit).
  // Tasse's a_n = 0.001 on squared variances over the height scale weighed
  // about 1e-7 of the cost: a DEM target's smooth valley floors then got the
  // exemplars' rough peaks. At 1 a factor two at every level (1/3) weighs as
  // much as a typical profile misfit.
  double noise = 1.0;
  double overlap = 1.0; // a_o: already-synthesised pixels
  // a_l: the landform around the site (LandformTerm.h), weighted like the
  // feature profiles: it is their context out to the patch's corners.
  double landform = 5.0;
  bool verticalOffset = false; // compare overlap heights up to a constant offset
};

// The cost of a candidate whose type (ridge/valley), kind (end, branch, path)
// or number of arms differs from the target's: never chosen, and not scored.
constexpr float kMismatchPenalty = 1.0e6f;

// Reference implementation (threads, vectorisable loops): one cost per candidate.
std::vector<float> scoreFeatureCandidates(const CandidatePool& pool,
  const FeatureQuery& query,
  const MatchWeights& weights);

struct RankedCandidate
{
  std::size_t index = 0; // into the pool
  float cost = 0.0f;
};

// The k cheapest, cost ascending, ties by index. With perExemplar, the k
// cheapest of each exemplar, merged in cost order.
std::vector<RankedCandidate> topK(const std::vector<float>& costs, std::size_t k);
std::vector<RankedCandidate> topKPerExemplar(const CandidatePool& pool,
  const std::vector<float>& costs,
  std::size_t k);

} // namespace tsynth
