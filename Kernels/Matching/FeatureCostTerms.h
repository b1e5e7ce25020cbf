// The terms of a feature candidate's cost (FeatureCost.h), shared by the
// reference scoring (FeatureCost.cxx) and the bounded ranking
// (FeatureRanking.cxx) so both give the same bits. Internal to the matcher.
#pragma once

#include "../Core/Constants.h"
#include "../Core/Grid.h"
#include "CandidatePool.h"
#include "FeatureCost.h"
#include "LandformTerm.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace tsynth
{
namespace featurecost
{

constexpr float kPiF = static_cast<float>(kPi);
// The overlap and landform sums run in this many lanes, added in order at the
// end, as in the OpenCL kernel, so both backends round alike.
constexpr int kLanes = 16;

// Element k of a query array; the cost counts in int, as the OpenCL kernel does.
template<class Array>
inline const float& queryAt(const Array& v, int k)
{
  return v[static_cast<std::size_t>(k)];
}

// What the overlap term needs of the query alone, worked out once per query.
struct OverlapQuery
{
  float weightSum = 0.0f; // sw: the same for every candidate
  // The descriptor blocks of kLanes cells holding any weight. A block of zero
  // weights adds exact zeros to every lane, so leaving it out changes no bit.
  std::vector<int> blocks;
  // The range of the summaries that carry weight.
  float lowest = std::numeric_limits<float>::max();
  float highest = std::numeric_limits<float>::lowest();
};

inline OverlapQuery prepareOverlap(const FeatureQuery& q)
{
  OverlapQuery o;
  float lw[kLanes] = {};
  for (int k = 0; k < kDescriptorSize; k += kLanes)
  {
    bool weighted = false;
    for (int l = 0; l < kLanes; ++l)
    {
      lw[l] += queryAt(q.weight, k + l);
      if (queryAt(q.weight, k + l) != 0.0f)
      {
        weighted = true;
        o.lowest = std::min(o.lowest, queryAt(q.descriptor, k + l));
        o.highest = std::max(o.highest, queryAt(q.descriptor, k + l));
      }
    }
    if (weighted)
    {
      o.blocks.push_back(k);
    }
  }
  for (float lane : lw)
  {
    o.weightSum += lane;
  }
  return o;
}

// The terms of a candidate's cost other than the arms', each already weighted.
struct CostTerms
{
  float noise = 0.0f;
  float overlap = 0.0f;
  float landform = 0.0f;
};

// The cost from its terms, added in the order of the OpenCL kernel. Every term
// is at least 0 but the overlap (a vertical offset may round it just below),
// and a float sum never falls when one of its terms grows: the sum with the
// arms' term taken as 0 bounds the cost from below.
inline float totalCost(float arms, const CostTerms& t)
{
  return arms + t.noise + t.overlap + t.landform;
}

// a_o c_o: weighted SSD of the summaries, optionally up to a vertical offset.
inline float overlapTerm(const float* d,
  const FeatureQuery& q,
  const OverlapQuery& oq,
  const MatchWeights& w,
  float invScale2)
{
  float overlap = 0.0f;
  const float sw = oq.weightSum;
  if (sw > 0.0f)
  {
    float lwd[kLanes] = {};
    float lwd2[kLanes] = {};
    for (const int k : oq.blocks)
    {
      for (int l = 0; l < kLanes; ++l)
      {
        const float diff = queryAt(q.descriptor, k + l) - d[k + l];
        const float wk = queryAt(q.weight, k + l);
        lwd[l] += wk * diff;
        lwd2[l] += wk * diff * diff;
      }
    }
    float swd = 0.0f;
    float swd2 = 0.0f;
    for (int l = 0; l < kLanes; ++l)
    {
      swd += lwd[l];
      swd2 += lwd2[l];
    }
    overlap = w.verticalOffset ? (swd2 - swd * swd / sw) / sw : swd2 / sw;
    overlap *= invScale2;
  }
  return static_cast<float>(w.overlap) * overlap;
}

// a_n c_n: roughness, scale-free as the fill's roughnessMisfit: per noise level
// the squared relative difference of the variances asked and found; a level
// asked as 0 is left out.
inline float noiseTerm(const float* found, const FeatureQuery& q, const MatchWeights& w)
{
  float cn = 0.0f;
  for (int l = 0; l < kNoiseLevels; ++l)
  {
    const float a = queryAt(q.noise, l);
    const float f = found[l];
    if (a > 0.0f)
    {
      const float relative = (a - f) / (a + f);
      cn += relative * relative;
    }
  }
  return static_cast<float>(w.noise) * cn;
}

// a_l c_l: the landform's weighted squared differences.
inline float landformTerm(const float* l,
  const FeatureQuery& q,
  const MatchWeights& w,
  float invScale2)
{
  float lwl2[kLanes] = {};
  for (int k = 0; k < kLandformStride; k += kLanes)
  {
    for (int m = 0; m < kLanes; ++m)
    {
      const float diff = queryAt(q.landform, k + m) - l[k + m];
      const float wk = queryAt(q.landformWeight, k + m);
      lwl2[m] += (wk * diff) * diff;
    }
  }
  float swl2 = 0.0f;
  for (int m = 0; m < kLanes; ++m)
  {
    swl2 += lwl2[m];
  }
  const float cl = swl2 / static_cast<float>(kLandformSamples) * invScale2;
  return static_cast<float>(w.landform) * cl;
}

// What the arms' term needs of the query alone: the profile samples it has
// (a sample off the target is NaN and left out), per arm.
struct ArmsQuery
{
  std::array<std::vector<int>, kMaxArms> along;
  std::array<std::vector<int>, kMaxArms> across;
  float samples = 0.0f; // how many, in all arms
};

inline ArmsQuery prepareArms(const FeatureQuery& q)
{
  ArmsQuery o;
  int samples = 0;
  for (int a = 0; a < q.arms; ++a)
  {
    const auto arm = static_cast<std::size_t>(a);
    for (int k = 0; k < kAlongSamples; ++k)
    {
      if (!std::isnan(queryAt(q.along, a * kAlongSamples + k)))
      {
        o.along[arm].push_back(k);
      }
    }
    for (int k = 0; k < kAcrossSamples; ++k)
    {
      if (!std::isnan(queryAt(q.across, a * kAcrossSamples + k)))
      {
        o.across[arm].push_back(k);
      }
    }
    samples += static_cast<int>(o.along[arm].size() + o.across[arm].size());
  }
  o.samples = static_cast<float>(samples);
  return o;
}

// The profile sums of every cyclic alignment s of a candidate's arms to the
// query's: each sums its arms and samples in the kernel's order, but the
// alignments' sums are independent and run side by side (Arms of them, known
// when compiled so they stay in registers), so no sum waits on another's
// additions.
template<int Arms>
void alignmentSums(const CandidatePool& pool,
  std::size_t c,
  const FeatureQuery& q,
  const ArmsQuery& aq,
  float (&profile)[kMaxArms],
  float (&angle)[kMaxArms])
{
  for (int a = 0; a < Arms; ++a)
  {
    const auto arm = static_cast<std::size_t>(a);
    const float* along[Arms];
    const float* across[Arms];
    for (int s = 0; s < Arms; ++s)
    {
      const std::size_t b = rowMajor((a + s) % Arms, c, kMaxArms);
      float da = queryAt(q.angles, a) - pool.angles[b];
      da = std::remainder(da, 2.0f * kPiF) / kPiF;
      angle[s] += da * da;
      along[s] = pool.along.data() + b * kAlongSamples;
      across[s] = pool.across.data() + b * kAcrossSamples;
    }
    for (const int k : aq.along[arm])
    {
      const float t = queryAt(q.along, a * kAlongSamples + k);
      for (int s = 0; s < Arms; ++s)
      {
        profile[s] += (t - along[s][k]) * (t - along[s][k]);
      }
    }
    for (const int k : aq.across[arm])
    {
      const float t = queryAt(q.across, a * kAcrossSamples + k);
      for (int s = 0; s < Arms; ++s)
      {
        profile[s] += (t - across[s][k]) * (t - across[s][k]);
      }
    }
  }
}

// min over the arms' cyclic alignments of a_f c_f + a_a c_a.
inline float armsTerm(const CandidatePool& pool,
  std::size_t c,
  const FeatureQuery& q,
  const ArmsQuery& aq,
  const MatchWeights& w,
  float invScale2)
{
  static_assert(kMaxArms == 4, "alignmentSums is instantiated for 1 to 4 arms");
  const int arms = q.arms;
  float profile[kMaxArms] = {};
  float angle[kMaxArms] = {};
  switch (arms)
  {
    case 1:
      alignmentSums<1>(pool, c, q, aq, profile, angle);
      break;
    case 2:
      alignmentSums<2>(pool, c, q, aq, profile, angle);
      break;
    case 3:
      alignmentSums<3>(pool, c, q, aq, profile, angle);
      break;
    case 4:
      alignmentSums<4>(pool, c, q, aq, profile, angle);
      break;
    default:
      break; // no arms: no profile and no angle
  }
  float best = 3.4e38f;
  for (int s = 0; s < std::max(1, arms); ++s)
  {
    const float cf = aq.samples > 0.0f ? profile[s] / aq.samples * invScale2 : 0.0f;
    const float ca = arms > 0 ? angle[s] / static_cast<float>(arms) : 0.0f;
    best = std::min(best, static_cast<float>(w.feature) * cf + static_cast<float>(w.angle) * ca);
  }
  return best;
}

// A candidate of another type, kind or number of arms is never chosen.
inline bool sameShape(const CandidatePool& pool, std::size_t c, const FeatureQuery& q)
{
  return pool.type[c] == q.type && pool.kind[c] == q.kind && pool.arms[c] == q.arms;
}

// Everything of one query a candidate's cost needs besides the candidate.
struct ScoredQuery
{
  const CandidatePool& pool;
  const FeatureQuery& q;
  const MatchWeights& w;
  OverlapQuery overlap;
  ArmsQuery armsQuery;
  float invScale2;

  ScoredQuery(const CandidatePool& p, const FeatureQuery& query, const MatchWeights& weights)
    : pool(p)
    , q(query)
    , w(weights)
    , overlap(prepareOverlap(query))
    , armsQuery(prepareArms(query))
    , invScale2(static_cast<float>(1.0 / (p.heightScale * p.heightScale)))
  {
  }

  CostTerms termsOf(std::size_t c) const
  {
    CostTerms t = cheapTermsOf(c);
    t.overlap = overlapOf(c);
    return t;
  }
  // Roughness and landform: a few hundred bytes of the candidate.
  CostTerms cheapTermsOf(std::size_t c) const
  {
    return cheapTermsAt(
      pool.noise.data() + c * kNoiseLevels, pool.landform.data() + c * kLandformStride);
  }
  // The same from the candidate's kNoiseLevels variances and kLandformStride samples.
  CostTerms cheapTermsAt(const float* noise, const float* landform) const
  {
    CostTerms t;
    t.noise = noiseTerm(noise, q, w);
    t.landform = landformTerm(landform, q, w, invScale2);
    return t;
  }
  // The overlap: a kilobyte of the candidate's summaries.
  float overlapOf(std::size_t c) const
  {
    return overlapTerm(pool.descriptor.data() + c * kDescriptorSize, q, overlap, w, invScale2);
  }

  float armsOf(std::size_t c) const { return armsTerm(pool, c, q, armsQuery, w, invScale2); }

  // One candidate's cost; the OpenCL kernel (OpenCL/FeatureCost.cl) follows
  // these terms line by line so both backends give the same numbers.
  float costOf(std::size_t c) const
  {
    // Never chosen (PatchMatcher::matchFeature skips it): the penalty alone,
    // nothing computed. Half the pool or more on any query (the other type's
    // half at least): on a DEM target's dense tree, scoring was 62% of the
    // synthesis' time.
    if (!sameShape(pool, c, q))
    {
      return kMismatchPenalty;
    }
    return totalCost(armsOf(c), termsOf(c));
  }
};

// Orders ranked candidates by cost, ties by index: the order topK ranks in.

} // namespace featurecost
} // namespace tsynth
