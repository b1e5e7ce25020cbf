#include "FeatureCost.h"

#include "../Core/Constants.h"
#include "../Core/Grid.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace tsynth
{
namespace
{

constexpr float kPiF = static_cast<float>(kPi);

// Element k of a query array; candidateCost counts in int, as the OpenCL kernel does.
template<class Array>
const float& queryAt(const Array& v, int k)
{
  return v[static_cast<std::size_t>(k)];
}

// One candidate's cost; the OpenCL kernel (OpenCL/FeatureCost.cl) follows this
// function line by line so both backends give the same numbers.
float candidateCost(const CandidatePool& pool,
  std::size_t c,
  const FeatureQuery& q,
  const MatchWeights& w,
  float invScale2)
{
  // A candidate of another type, kind or number of arms is never chosen
  // (PatchMatcher::matchFeature skips it): the penalty alone, nothing computed.
  // Half the pool or more on any query (the other type's half at least): on a
  // DEM target's dense tree, scoring was 62% of the synthesis' time.
  if (pool.type[c] != q.type || pool.kind[c] != q.kind || pool.arms[c] != q.arms)
  {
    return kMismatchPenalty;
  }
  // Overlap: weighted SSD of the summaries, optionally up to a vertical offset.
  // Sixteen lanes accumulate blocks k, k + 16, ... and are added in order, as in
  // the OpenCL kernel, so both backends round alike.
  const float* d = pool.descriptor.data() + c * kDescriptorSize;
  float lw[16] = {};
  float lwd[16] = {};
  float lwd2[16] = {};
  for (int k = 0; k < kDescriptorSize; k += 16)
  {
    for (int l = 0; l < 16; ++l)
    {
      const float diff = queryAt(q.descriptor, k + l) - d[k + l];
      const float wk = queryAt(q.weight, k + l);
      lw[l] += wk;
      lwd[l] += wk * diff;
      lwd2[l] += wk * diff * diff;
    }
  }
  float sw = 0.0f;
  float swd = 0.0f;
  float swd2 = 0.0f;
  for (int l = 0; l < 16; ++l)
  {
    sw += lw[l];
    swd += lwd[l];
    swd2 += lwd2[l];
  }
  float overlap = 0.0f;
  if (sw > 0.0f)
  {
    overlap = w.verticalOffset ? (swd2 - swd * swd / sw) / sw : swd2 / sw;
    overlap *= invScale2;
  }
  const float costOverlap = static_cast<float>(w.overlap) * overlap;

  // Arms: the cyclic alignment with the lowest a_f c_f + a_a c_a.
  const int arms = q.arms;
  float best = 3.4e38f;
  for (int s = 0; s < std::max(1, arms); ++s)
  {
    float profile = 0.0f;
    float samples = 0.0f;
    float angle = 0.0f;
    for (int a = 0; a < arms; ++a)
    {
      const int b = (a + s) % arms;
      float da = queryAt(q.angles, a) - pool.angles[rowMajor(b, c, kMaxArms)];
      da = std::remainder(da, 2.0f * kPiF) / kPiF;
      angle += da * da;
      const float* ca = pool.along.data() + rowMajor(b, c, kMaxArms) * kAlongSamples;
      for (int k = 0; k < kAlongSamples; ++k)
      {
        const float t = queryAt(q.along, a * kAlongSamples + k);
        if (!std::isnan(t))
        {
          profile += (t - ca[k]) * (t - ca[k]);
          samples += 1.0f;
        }
      }
      const float* cx = pool.across.data() + rowMajor(b, c, kMaxArms) * kAcrossSamples;
      for (int k = 0; k < kAcrossSamples; ++k)
      {
        const float t = queryAt(q.across, a * kAcrossSamples + k);
        if (!std::isnan(t))
        {
          profile += (t - cx[k]) * (t - cx[k]);
          samples += 1.0f;
        }
      }
    }
    const float cf = samples > 0.0f ? profile / samples * invScale2 : 0.0f;
    const float ca = arms > 0 ? angle / static_cast<float>(arms) : 0.0f;
    best = std::min(best, static_cast<float>(w.feature) * cf + static_cast<float>(w.angle) * ca);
  }
  // Roughness, scale-free as the fill's roughnessMisfit: per noise level the
  // squared relative difference of the variances asked and found; a level
  // asked as 0 is left out.
  float cn = 0.0f;
  for (int l = 0; l < kNoiseLevels; ++l)
  {
    const float a = queryAt(q.noise, l);
    const float f = pool.noise[rowMajor(l, c, kNoiseLevels)];
    if (a > 0.0f)
    {
      const float relative = (a - f) / (a + f);
      cn += relative * relative;
    }
  }
  // Landform: weighted squared differences, 16 lanes over samples k, k + 16.
  const float* l = pool.landform.data() + c * kLandformStride;
  float lwl2[16] = {};
  for (int k = 0; k < kLandformStride; k += 16)
  {
    for (int m = 0; m < 16; ++m)
    {
      const float diff = queryAt(q.landform, k + m) - l[k + m];
      const float wk = queryAt(q.landformWeight, k + m);
      lwl2[m] += (wk * diff) * diff;
    }
  }
  float swl2 = 0.0f;
  for (int m = 0; m < 16; ++m)
  {
    swl2 += lwl2[m];
  }
  const float cl = swl2 / static_cast<float>(kLandformSamples) * invScale2;
  return best + static_cast<float>(w.noise) * cn + costOverlap +
    static_cast<float>(w.landform) * cl;
}

} // namespace

std::vector<float> scoreFeatureCandidates(const CandidatePool& pool,
  const FeatureQuery& query,
  const MatchWeights& weights)
{
  std::vector<float> costs(pool.size());
  const float invScale2 = static_cast<float>(1.0 / (pool.heightScale * pool.heightScale));
  const std::size_t n = pool.size();
#pragma omp parallel for schedule(static)
  for (std::size_t c = 0; c < n; ++c)
  {
    costs[c] = candidateCost(pool, c, query, weights, invScale2);
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
