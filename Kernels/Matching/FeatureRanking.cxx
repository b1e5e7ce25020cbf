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
// sum(w), is never below 0, but in floats it may round below: the two sums
// take up to 34 roundings of 2^-24 each and the square and quotients a few
// more, so it lies above -140 * 2^-24 (8.3e-6) of sum(w d^2) / sum(w), which
// is at most R^2, R the largest |d|. The floor allows 12 times that.
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

// Orders ranked candidates by cost, ties by index: the order topK ranks in.
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
  std::size_t capacity() const { return k_; }
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

// What the bounds read of a candidate, kept per group member: its kNoiseLevels
// noise variances, then its kLandformStride landform samples.
constexpr std::size_t kCheapStride = kNoiseLevels + kLandformStride;
// Its profiles' moments: kArmMoments per arm.
constexpr std::size_t kMomentStride = kMaxArms * FeatureRanker::kArmMoments;

// How many of a thread's share of an exemplar's candidates, those whose
// roughness and landform cost least, are scored in full before the others,
// per candidate kept: the k-th cheapest of them is the bar the rest must come
// under from the start.
constexpr std::size_t kWarmUpPerKept = 4;

} // namespace

FeatureRanker::FeatureRanker(const CandidatePool& pool)
  : pool_(pool)
{
  for (std::size_t c = 0; c < pool.size(); ++c)
  {
    Group& group = groups_[{ pool.type[c], pool.kind[c], pool.arms[c] }];
    // Candidates ascend, and each exemplar's are one run of indices.
    if (group.members.empty() || pool.exemplar[group.members.back()] != pool.exemplar[c])
    {
      group.runs.push_back({ group.members.size(), group.members.size() });
    }
    group.members.push_back(c);
    group.runs.back().second = group.members.size();
    addBoundData(group, c);
  }
}

void FeatureRanker::addBoundData(Group& group, std::size_t c) const
{
  const float* noise = pool_.noise.data() + c * kNoiseLevels;
  group.cheap.insert(group.cheap.end(), noise, noise + kNoiseLevels);
  const float* landform = pool_.landform.data() + c * kLandformStride;
  group.cheap.insert(group.cheap.end(), landform, landform + kLandformStride);
  const auto first = pool_.descriptor.begin() + static_cast<long>(c * kDescriptorSize);
  const auto range = std::minmax_element(first, first + kDescriptorSize);
  group.ranges.push_back({ *range.first, *range.second });
  for (int b = 0; b < kMaxArms; ++b)
  {
    const std::size_t row = rowMajor(b, c, kMaxArms);
    const auto along = momentsOf(pool_.along.data() + row * kAlongSamples, kAlongSamples);
    const auto across = momentsOf(pool_.across.data() + row * kAcrossSamples, kAcrossSamples);
    for (const double m : { along[0], along[1], across[0], across[1] })
    {
      group.moments.push_back(static_cast<float>(m));
    }
  }
}

struct FeatureRanker::Scratch
{
  std::vector<CostTerms> terms; // roughness, landform, the overlap at its floor
  std::vector<float> least;     // the cost with the rest at their least
  std::vector<std::size_t> order;
  std::vector<char> warmed;
};

FeatureRanker::~FeatureRanker() = default;

// Ranks a run of candidates of one exemplar, all of the query's shape, on one
// thread. Every thread ranks its own share of each exemplar's candidates in
// one parallel region: with passive OpenMP waits (tsynth's default) each
// parallel region costs a wake-up, which the ranking's work per query does
// not pay for three times over.
class FeatureRanker::ExemplarRanking
{
public:
  ExemplarRanking(const FeatureRanker& ranker,
    const ScoredQuery& scored,
    const QueryMoments& moments)
    : r_(ranker)
    , s_(scored)
    , moments_(moments)
    , bounded_(scored.w.feature >= 0.0 && scored.w.angle >= 0.0 && scored.w.overlap >= 0.0)
  {
  }

  // Offers the run's candidates to `kept`, leaving those that cannot be among its k.
  void rank(const Group& group,
    std::size_t from,
    std::size_t n,
    KeptCandidates& kept,
    Scratch& x,
    RankingCounts& counts) const
  {
    const std::size_t* members = group.members.data() + from;
    boundTerms(group, from, n, x);
    warmUp(members, n, kept, x);
    // Dearer than k candidates already at its least: never among the k cheapest.
    auto outranked = [&](float least)
    { return bounded_ && kept.full() && least > kept.dearestCost(); };
    for (std::size_t i = 0; i < n; ++i)
    {
      if (x.warmed[i] != 0)
      {
        continue;
      }
      if (outranked(x.least[i]))
      {
        ++counts.beforeMoments;
        continue;
      }
      const std::size_t c = members[i];
      CostTerms terms = x.terms[i];
      if (outranked(
            totalCost(profileFloor(group.moments.data() + (from + i) * kMomentStride), terms)))
      {
        ++counts.beforeArms;
        continue;
      }
      const float arms = s_.armsOf(c);
      if (outranked(totalCost(arms, terms)))
      {
        ++counts.beforeOverlap;
        continue;
      }
      terms.overlap = s_.overlapOf(c);
      kept.offer({ c, totalCost(arms, terms) });
      ++counts.scored;
    }
    counts.shaped += n;
  }

private:
  // Each candidate's roughness and landform, the overlap at its floor, and so its least cost.
  void boundTerms(const Group& group, std::size_t from, std::size_t n, Scratch& x) const
  {
    x.terms.resize(n);
    x.least.resize(n);
    for (std::size_t i = 0; i < n; ++i)
    {
      const float* cheap = group.cheap.data() + (from + i) * kCheapStride;
      CostTerms t = s_.cheapTermsAt(cheap, cheap + kNoiseLevels);
      t.overlap = overlapFloor(group.ranges[from + i], s_.overlap, s_.w, s_.invScale2);
      x.terms[i] = t;
      x.least[i] = totalCost(0.0f, t);
    }
  }

  // The least a_f c_f + a_a c_a of a candidate can be: the angles at 0 and
  // each arm's profiles at the distance of their moments.
  float profileFloor(const float* candidateMoments) const
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
        const float* m = candidateMoments + ((a + s) % arms) * kArmMoments;
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

  // Scores in full the candidates of least bound and offers them first, so
  // the bar the rest must come under is low from the start.
  void warmUp(const std::size_t* members, std::size_t n, KeptCandidates& kept, Scratch& x) const
  {
    x.warmed.assign(n, 0);
    if (!bounded_)
    {
      return;
    }
    x.order.resize(n);
    std::iota(x.order.begin(), x.order.end(), 0);
    const std::size_t count = std::min(n, kWarmUpPerKept * kept.capacity());
    const std::vector<float>& least = x.least;
    std::nth_element(x.order.begin(),
      x.order.begin() + static_cast<long>(count),
      x.order.end(),
      [&](std::size_t a, std::size_t b)
      { return least[a] < least[b] || (least[a] == least[b] && a < b); });
    for (std::size_t j = 0; j < count; ++j)
    {
      const std::size_t i = x.order[j];
      CostTerms terms = x.terms[i];
      terms.overlap = s_.overlapOf(members[i]);
      kept.offer({ members[i], totalCost(s_.armsOf(members[i]), terms) });
      x.warmed[i] = 1;
    }
  }

  const FeatureRanker& r_;
  const ScoredQuery& s_;
  const QueryMoments& moments_;
  bool bounded_;
};

std::vector<RankedCandidate> FeatureRanker::rank(const FeatureQuery& query,
  const MatchWeights& weights,
  std::size_t k,
  RankingCounts* counts)
{
  const auto found = groups_.find({ query.type, query.kind, query.arms });
  if (k == 0 || found == groups_.end())
  {
    if (counts != nullptr)
    {
      *counts = {};
    }
    return {};
  }
  const Group& group = found->second;
  const ScoredQuery scored(pool_, query, weights);
  const QueryMoments moments = queryMoments(query, scored.armsQuery);
  const ExemplarRanking ranking(*this, scored, moments);
  const std::size_t runs = group.runs.size();
  std::vector<std::vector<KeptCandidates>> perThread;
  std::vector<RankingCounts> tallies;
#pragma omp parallel
  {
#pragma omp single
    {
      const auto threads = static_cast<std::size_t>(omp_get_num_threads());
      perThread.assign(threads, std::vector<KeptCandidates>(runs, KeptCandidates(k)));
      tallies.assign(threads, {});
      scratch_.resize(std::max(scratch_.size(), threads));
    }
    const auto thread = static_cast<std::size_t>(omp_get_thread_num());
    const auto threads = perThread.size();
    // Each thread its own share of every exemplar's run, whatever the count:
    // the k cheapest of the shares' k cheapest are those of the run.
    for (std::size_t r = 0; r < runs; ++r)
    {
      const auto [first, last] = group.runs[r];
      const std::size_t from = first + (last - first) * thread / threads;
      const std::size_t to = first + (last - first) * (thread + 1) / threads;
      ranking.rank(group, from, to - from, perThread[thread][r], scratch_[thread], tallies[thread]);
    }
  }
  std::vector<RankedCandidate> ranked;
  for (std::size_t r = 0; r < runs; ++r)
  {
    std::vector<const KeptCandidates*> shares;
    for (const std::vector<KeptCandidates>& thread : perThread)
    {
      shares.push_back(&thread[r]);
    }
    const std::vector<RankedCandidate> mine = cheapestOf(shares, k);
    ranked.insert(ranked.end(), mine.begin(), mine.end());
  }
  std::sort(ranked.begin(), ranked.end(), cheaper);
  if (counts != nullptr)
  {
    *counts = {};
    for (const RankingCounts& t : tallies)
    {
      counts->shaped += t.shaped;
      counts->beforeMoments += t.beforeMoments;
      counts->beforeArms += t.beforeArms;
      counts->beforeOverlap += t.beforeOverlap;
      counts->scored += t.scored;
    }
  }
  return ranked;
}

} // namespace tsynth
