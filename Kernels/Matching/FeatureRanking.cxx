#include "FeatureRanking.h"

#include "FeatureCostTerms.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <omp.h>

namespace tsynth
{
using namespace featurecost;

namespace
{

// The overlap up to a vertical offset, sum(w d^2) - sum(w d)^2 / sum(w) over
// sum(w), is never below 0, but in floats it may round below by a few units in
// the last place of sum(w d^2) / sum(w) <= R^2, R the largest |d| (about 70
// float roundings of 2^-24 for 256 summaries in 16 lanes: 4.2e-6 R^2). The
// floor allows 24 times that.
constexpr double kOffsetOverlapRounding = 1.0e-4;

// The least a candidate's a_o c_o can come out in floats, from the ranges of
// its summaries and of the query's weighted ones alone.
float overlapFloor(const std::array<float, 2>& range,
  const OverlapQuery& oq,
  const MatchWeights& w,
  float invScale2)
{
  if (!(oq.weightSum > 0.0f) || !w.verticalOffset)
  {
    return 0.0f; // no overlap, or a weighted mean of squares: at least 0
  }
  const double reach =
    std::max(static_cast<double>(oq.highest) - range[0], static_cast<double>(range[1]) - oq.lowest);
  return static_cast<float>(-w.overlap * invScale2 * reach * reach * kOffsetOverlapRounding);
}

// A profile's first two coordinates in an orthonormal basis of its samples:
// the constant and the straight ramp. Their squared differences between two
// profiles add up to at most the profiles' squared distance (Bessel).
std::array<double, FeatureRanker::kMoments> momentsOf(const float* v, int n)
{
  const double middle = 0.5 * (n - 1);
  double rampNorm = 0.0;
  double sum = 0.0;
  double ramp = 0.0;
  for (int k = 0; k < n; ++k)
  {
    const double x = k - middle;
    rampNorm += x * x;
    sum += v[k];
    ramp += v[k] * x;
  }
  return { sum / std::sqrt(static_cast<double>(n)), ramp / std::sqrt(rampNorm) };
}

// The moments are kept in floats, rounded by at most 2^-24 of their size; a
// gap is narrowed by 2^-20 of the sizes to stay below the true one.
constexpr double kMomentRounding = 1.0e-6;
// The float profile sum of up to 4 x 33 squares rounds below the true sum by
// at most about 140 roundings of 2^-24 (8.3e-6 of it); the bound gives up 120
// times that.
constexpr double kProfileRounding = 1.0e-3;

// The squared gap between two moments, at its least.
double gapSquared(double query, float candidate)
{
  const double gap =
    std::abs(query - candidate) - kMomentRounding * (std::abs(query) + std::abs(candidate));
  return gap > 0.0 ? gap * gap : 0.0;
}

// The query's profile moments, per arm; an arm with a sample off the target
// has none (its profile then bounds nothing but 0).
struct QueryMoments
{
  std::array<std::array<double, FeatureRanker::kArmMoments>, kMaxArms> moments{};
  std::array<bool, kMaxArms> along{};
  std::array<bool, kMaxArms> across{};
};

QueryMoments queryMoments(const FeatureQuery& q, const ArmsQuery& aq)
{
  QueryMoments m;
  for (int a = 0; a < q.arms; ++a)
  {
    const auto arm = static_cast<std::size_t>(a);
    const auto along = momentsOf(q.along.data() + a * kAlongSamples, kAlongSamples);
    const auto across = momentsOf(q.across.data() + a * kAcrossSamples, kAcrossSamples);
    m.moments[arm] = { along[0], along[1], across[0], across[1] };
    m.along[arm] = aq.along[arm].size() == kAlongSamples;
    m.across[arm] = aq.across[arm].size() == kAcrossSamples;
  }
  return m;
}

bool cheaper(const RankedCandidate& a, const RankedCandidate& b)
{
  return a.cost < b.cost || (a.cost == b.cost && a.index < b.index);
}

// The k cheapest seen so far, the dearest on top.
class KeptCandidates
{
public:
  explicit KeptCandidates(std::size_t k)
    : k_(k)
  {
  }
  bool full() const { return heap_.size() >= k_; }
  float dearestCost() const { return heap_.front().cost; }
  void offer(const RankedCandidate& r)
  {
    if (!full())
    {
      heap_.push_back(r);
      std::push_heap(heap_.begin(), heap_.end(), cheaper);
    }
    else if (cheaper(r, heap_.front()))
    {
      std::pop_heap(heap_.begin(), heap_.end(), cheaper);
      heap_.back() = r;
      std::push_heap(heap_.begin(), heap_.end(), cheaper);
    }
  }
  const std::vector<RankedCandidate>& kept() const { return heap_; }

private:
  std::size_t k_;
  std::vector<RankedCandidate> heap_;
};

// The k cheapest of several sets of kept candidates, in cost order (ties by index).
std::vector<RankedCandidate> cheapestOf(const std::vector<const KeptCandidates*>& sets,
  std::size_t k)
{
  std::vector<RankedCandidate> all;
  for (const KeptCandidates* set : sets)
  {
    all.insert(all.end(), set->kept().begin(), set->kept().end());
  }
  std::sort(all.begin(), all.end(), cheaper);
  all.resize(std::min(all.size(), k));
  return all;
}

// How many of an exemplar's candidates, those whose roughness and landform
// cost least, are scored in full before the others, per candidate kept: the
// k-th cheapest of them is the bar the rest must come under from the start.
constexpr std::size_t kWarmUpPerKept = 4;

} // namespace

FeatureRanker::FeatureRanker(const CandidatePool& pool)
  : pool_(pool)
  , descriptorRange_(pool.size())
  , moments_(pool.size() * kMaxArms * kArmMoments)
{
  for (std::size_t c = 0; c < pool.size(); ++c)
  {
    groups_[{ pool.type[c], pool.kind[c], pool.arms[c] }].push_back(c);
    const auto first = pool.descriptor.begin() + static_cast<long>(c * kDescriptorSize);
    const auto range = std::minmax_element(first, first + kDescriptorSize);
    descriptorRange_[c] = { *range.first, *range.second };
    for (int b = 0; b < kMaxArms; ++b)
    {
      const std::size_t row = rowMajor(b, c, kMaxArms);
      const auto along = momentsOf(pool.along.data() + row * kAlongSamples, kAlongSamples);
      const auto across = momentsOf(pool.across.data() + row * kAcrossSamples, kAcrossSamples);
      float* m = moments_.data() + row * kArmMoments;
      m[0] = static_cast<float>(along[0]);
      m[1] = static_cast<float>(along[1]);
      m[2] = static_cast<float>(across[0]);
      m[3] = static_cast<float>(across[1]);
    }
  }
}

struct FeatureRanker::Scratch
{
  std::vector<CostTerms> terms; // roughness, landform, the overlap at its floor
  std::vector<float> least;     // the cost with the rest at their least
  std::vector<std::size_t> order;
  std::vector<char> warmed;
  std::vector<float> warmCosts;
};

FeatureRanker::~FeatureRanker() = default;

// Ranks the candidates of one exemplar of the query's shape.
class FeatureRanker::ExemplarRanking
{
public:
  ExemplarRanking(const FeatureRanker& ranker,
    const ScoredQuery& scored,
    std::size_t k,
    Scratch& scratch)
    : r_(ranker)
    , s_(scored)
    , moments_(queryMoments(scored.q, scored.armsQuery))
    , k_(k)
    , bounded_(scored.w.feature >= 0.0 && scored.w.angle >= 0.0 && scored.w.overlap >= 0.0)
    , x_(scratch)
  {
  }

  std::vector<RankedCandidate> rank(const std::size_t* members,
    std::size_t n,
    RankingCounts& counts)
  {
    members_ = members;
    boundTerms(n);
    const KeptCandidates warm = warmUp(n);
    const float bar = bounded_ && warm.full() ? warm.dearestCost() : kUnbounded;
    std::vector<KeptCandidates> perThread;
    std::size_t beforeMoments = 0;
    std::size_t beforeArms = 0;
    std::size_t beforeOverlap = 0;
#pragma omp parallel reduction(+ : beforeMoments, beforeArms, beforeOverlap)
    {
#pragma omp single
      perThread.assign(static_cast<std::size_t>(omp_get_num_threads()), KeptCandidates(k_));
      KeptCandidates& kept = perThread[static_cast<std::size_t>(omp_get_thread_num())];
      // Dearer than k candidates already at its least: never among the k cheapest.
      auto outranked = [&](float least)
      { return least > bar || (bounded_ && kept.full() && least > kept.dearestCost()); };
#pragma omp for schedule(static)
      for (std::size_t i = 0; i < n; ++i)
      {
        if (x_.warmed[i] != 0)
        {
          continue;
        }
        if (outranked(x_.least[i]))
        {
          ++beforeMoments;
          continue;
        }
        const std::size_t c = members_[i];
        CostTerms terms = x_.terms[i];
        if (outranked(totalCost(profileFloor(c), terms)))
        {
          ++beforeArms;
          continue;
        }
        const float arms = s_.armsOf(c);
        if (outranked(totalCost(arms, terms)))
        {
          ++beforeOverlap;
          continue;
        }
        terms.overlap = s_.overlapOf(c);
        kept.offer({ c, totalCost(arms, terms) });
      }
    }
    counts.shaped += n;
    counts.beforeMoments += beforeMoments;
    counts.beforeArms += beforeArms;
    counts.beforeOverlap += beforeOverlap;
    counts.scored += n - beforeMoments - beforeArms - beforeOverlap;
    std::vector<const KeptCandidates*> sets{ &warm };
    for (const KeptCandidates& kept : perThread)
    {
      sets.push_back(&kept);
    }
    return cheapestOf(sets, k_);
  }

private:
  static constexpr float kUnbounded = std::numeric_limits<float>::infinity();

  // Each candidate's roughness and landform, the overlap at its floor, and so its least cost.
  void boundTerms(std::size_t n)
  {
    x_.terms.resize(n);
    x_.least.resize(n);
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i)
    {
      const std::size_t c = members_[i];
      CostTerms t = s_.cheapTermsOf(c);
      t.overlap = overlapFloor(r_.descriptorRange_[c], s_.overlap, s_.w, s_.invScale2);
      x_.terms[i] = t;
      x_.least[i] = totalCost(0.0f, t);
    }
  }

  // The least a_f c_f + a_a c_a of a candidate can be: the angles at 0 and
  // each arm's profiles at the distance of their moments.
  float profileFloor(std::size_t c) const
  {
    const int arms = s_.q.arms;
    if (arms == 0 || !(s_.armsQuery.samples > 0.0f))
    {
      return 0.0f;
    }
    double least = std::numeric_limits<double>::infinity();
    for (int s = 0; s < arms; ++s)
    {
      double sum = 0.0;
      for (int a = 0; a < arms; ++a)
      {
        const auto arm = static_cast<std::size_t>(a);
        const auto& q = moments_.moments[arm];
        const float* m = r_.moments_.data() + rowMajor((a + s) % arms, c, kMaxArms) * kArmMoments;
        if (moments_.along[arm])
        {
          sum += gapSquared(q[0], m[0]) + gapSquared(q[1], m[1]);
        }
        if (moments_.across[arm])
        {
          sum += gapSquared(q[2], m[2]) + gapSquared(q[3], m[3]);
        }
      }
      least = std::min(least, sum);
    }
    return static_cast<float>(
      s_.w.feature * least / s_.armsQuery.samples * s_.invScale2 * (1.0 - kProfileRounding));
  }

  // The candidates of least bound, scored in full.
  KeptCandidates warmUp(std::size_t n)
  {
    x_.warmed.assign(n, 0);
    KeptCandidates warm(k_);
    if (!bounded_)
    {
      return warm;
    }
    x_.order.resize(n);
    std::iota(x_.order.begin(), x_.order.end(), 0);
    const std::size_t count = std::min(n, kWarmUpPerKept * k_);
    const std::vector<float>& least = x_.least;
    std::nth_element(x_.order.begin(),
      x_.order.begin() + static_cast<long>(count),
      x_.order.end(),
      [&](std::size_t a, std::size_t b)
      { return least[a] < least[b] || (least[a] == least[b] && a < b); });
    x_.warmCosts.resize(count);
#pragma omp parallel for schedule(static)
    for (std::size_t j = 0; j < count; ++j)
    {
      const std::size_t c = members_[x_.order[j]];
      CostTerms terms = x_.terms[x_.order[j]];
      terms.overlap = s_.overlapOf(c);
      x_.warmCosts[j] = totalCost(s_.armsOf(c), terms);
    }
    for (std::size_t j = 0; j < count; ++j)
    {
      x_.warmed[x_.order[j]] = 1;
      warm.offer({ members_[x_.order[j]], x_.warmCosts[j] });
    }
    return warm;
  }

  const FeatureRanker& r_;
  const ScoredQuery& s_;
  QueryMoments moments_;
  std::size_t k_;
  bool bounded_;
  Scratch& x_;
  const std::size_t* members_ = nullptr;
};

std::vector<RankedCandidate> FeatureRanker::rank(const FeatureQuery& query,
  const MatchWeights& weights,
  std::size_t k,
  RankingCounts* counts)
{
  const auto found = groups_.find({ query.type, query.kind, query.arms });
  RankingCounts tally;
  std::vector<RankedCandidate> ranked;
  if (k > 0 && found != groups_.end())
  {
    const std::vector<std::size_t>& members = found->second;
    if (!scratch_)
    {
      scratch_ = std::make_unique<Scratch>();
    }
    const ScoredQuery scored(pool_, query, weights);
    ExemplarRanking ranking(*this, scored, k, *scratch_);
    // Members ascend, and each exemplar's candidates are one run of indices.
    for (std::size_t first = 0; first < members.size();)
    {
      const int exemplar = pool_.exemplar[members[first]];
      std::size_t last = first;
      while (last < members.size() && pool_.exemplar[members[last]] == exemplar)
      {
        ++last;
      }
      const std::vector<RankedCandidate> mine = ranking.rank(&members[first], last - first, tally);
      ranked.insert(ranked.end(), mine.begin(), mine.end());
      first = last;
    }
    std::sort(ranked.begin(), ranked.end(), cheaper);
  }
  if (counts != nullptr)
  {
    *counts = tally;
  }
  return ranked;
}

} // namespace tsynth
