#include "FeatureRanking.h"

#include "FeatureCostTerms.h"
#include "Vectorise.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <omp.h>

namespace tsynth
{
using namespace featurecost;

namespace
{

// What the bounds need of one query, worked out once: the constants of every
// candidate's roughness, landform, overlap floor and profile floor.
struct BoundQuery
{
  // Roughness: the variances asked (a level asked as 0 is left out) and a_n.
  std::array<float, kNoiseLevels> noise{};
  float noiseWeight = 0.0f;
  // Landform: the samples asked, their weights, a_l and the height scale.
  std::array<float, kLandformStride> landform{};
  std::array<float, kLandformStride> landformWeight{};
  float landformWeightAll = 0.0f;
  float invScale2 = 0.0f;
  // The overlap up to a vertical offset: its floor from the summaries' ranges.
  bool offsetOverlap = false;
  double highest = 0.0;
  double lowest = 0.0;
  double overlapFloorScale = 0.0;
  // The profiles: each arm's moments, which of its profiles it has, and the
  // factor from a squared distance of profiles to a_f c_f.
  int arms = 0;
  std::array<std::array<double, FeatureRanker::kArmMoments>, kMaxArms> moments{};
  std::array<bool, kMaxArms> along{};
  std::array<bool, kMaxArms> across{};
  double profileScale = 0.0; // 0: no profile, the floor is 0
  // The angles: each arm's, and the factor from a sum of squared angle
  // differences (in half turns) to a_a c_a.
  std::array<float, kMaxArms> angles{};
  double angleScale = 0.0;
};

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

// The overlap up to a vertical offset, sum(w d^2) - sum(w d)^2 / sum(w) over
// sum(w), is never below 0, but in floats it may round below: the two sums
// take up to 34 roundings of 2^-24 each and the square and quotients a few
// more, so it lies above -140 * 2^-24 (8.3e-6) of sum(w d^2) / sum(w), which
// is at most R^2, R the largest |d|. The floor allows 12 times that.
constexpr double kOffsetOverlapRounding = 1.0e-4;
// The moments are kept in floats, rounded by at most 2^-24 of their size; a
// gap is narrowed by 2^-20 of the sizes to stay below the true one.
constexpr double kMomentRounding = 1.0e-6;
// The float profile sum of up to 4 x 33 squares rounds below the true sum by
// at most about 140 roundings of 2^-24 (8.3e-6 of it); the bound gives up 120
// times that.
constexpr double kProfileRounding = 1.0e-3;
// The float angle term (up to 4 squares of a quotient, added and divided)
// rounds below its true value by under 10 roundings of 2^-24, and a_f c_f +
// a_a c_a takes 3 more; the bound gives up over 1000 times that.
constexpr double kAngleRounding = 1.0e-3;

BoundQuery boundQuery(const ScoredQuery& s)
{
  BoundQuery b;
  const FeatureQuery& q = s.q;
  for (int l = 0; l < kNoiseLevels; ++l)
  {
    b.noise[static_cast<std::size_t>(l)] = queryAt(q.noise, l);
  }
  b.noiseWeight = static_cast<float>(s.w.noise);
  for (int k = 0; k < kLandformStride; ++k)
  {
    b.landform[static_cast<std::size_t>(k)] = queryAt(q.landform, k);
    b.landformWeight[static_cast<std::size_t>(k)] = queryAt(q.landformWeight, k);
  }
  b.landformWeightAll = static_cast<float>(s.w.landform);
  b.invScale2 = s.invScale2;
  // Without overlap, or as a weighted mean of squares, the overlap is at least 0.
  b.offsetOverlap = s.overlap.weightSum > 0.0f && s.w.verticalOffset;
  b.highest = s.overlap.highest;
  b.lowest = s.overlap.lowest;
  b.overlapFloorScale = -s.w.overlap * s.invScale2 * kOffsetOverlapRounding;
  b.arms = q.arms;
  for (int a = 0; a < q.arms; ++a)
  {
    const auto arm = static_cast<std::size_t>(a);
    const auto along = momentsOf(q.along.data() + a * kAlongSamples, kAlongSamples);
    const auto across = momentsOf(q.across.data() + a * kAcrossSamples, kAcrossSamples);
    b.moments[arm] = { along[0], along[1], across[0], across[1] };
    b.along[arm] = s.armsQuery.along[arm].size() == kAlongSamples;
    b.across[arm] = s.armsQuery.across[arm].size() == kAcrossSamples;
  }
  if (q.arms > 0 && s.armsQuery.samples > 0.0f)
  {
    b.profileScale = s.w.feature / s.armsQuery.samples * s.invScale2 * (1.0 - kProfileRounding);
  }
  for (int a = 0; a < q.arms; ++a)
  {
    b.angles[static_cast<std::size_t>(a)] = queryAt(q.angles, a);
  }
  if (q.arms > 0)
  {
    b.angleScale = static_cast<float>(s.w.angle) / q.arms * (1.0 - kAngleRounding);
  }
  return b;
}

// The squared gap between two moments, at its least.
TSYNTH_INLINE_IN_CLONES double gapSquared(double query, float candidate)
{
  double gap =
    std::abs(query - candidate) - kMomentRounding * (std::abs(query) + std::abs(candidate));
  gap = gap > 0.0 ? gap : 0.0;
  return gap * gap;
}

// Members per block of a group's bound data, one per vector lane: four
// 16-float vectors (AVX-512; eight AVX2 ones, sixteen SSE ones). The compiler
// vectorises loops over this many; it unrolls loops of 16 into scalar code.
constexpr std::size_t kBlockLanes = 64;
using Lanes = float[kBlockLanes];
using WideLanes = double[kBlockLanes];

// Where a field lies in a group's blocks (FeatureRanker::Group): its kNoiseLevels
// noise variances, its landform samples (the padding left out when it is 0 in
// every member), its kArmMoments per arm, its arms' angles, its descriptor's
// least and greatest.
struct BlockFields
{
  std::size_t landform = 0; // landform samples kept
  std::size_t moments = 0;  // moments kept: kArmMoments per arm of the group
  std::size_t arms = 0;     // the group's arms: one angle each
  std::size_t landformAt() const { return kNoiseLevels; }
  std::size_t momentsAt() const { return landformAt() + landform; }
  std::size_t anglesAt() const { return momentsAt() + moments; }
  std::size_t lowestAt() const { return anglesAt() + arms; }
  std::size_t highestAt() const { return lowestAt() + 1; }
  std::size_t count() const { return highestAt() + 1; }
};

// Where the fields of a group (FeatureRanker::Group) lie.
template<class Group>
BlockFields blockFieldsOf(const Group& group)
{
  const auto arms = static_cast<std::size_t>(group.arms);
  return { group.landformFields, arms * FeatureRanker::kArmMoments, arms };
}

// What the bound pass gives per candidate: the exact roughness and landform
// terms, the overlap's floor, and the least cost.
struct BoundTerms
{
  float* noise;
  float* landform;
  float* overlap;
  float* least;
  BoundTerms from(std::size_t k) const
  {
    return { noise + k, landform + k, overlap + k, least + k };
  }
};

// One block's roughness and landform (bit for bit as noiseTerm and
// landformTerm: each member's sums keep their lanes and order) and its least
// cost with the overlap and the arms (angles, profiles) at their floors, one
// member per vector lane.
class BlockBound
{
public:
  BlockBound(const BoundQuery& b, const BlockFields& f)
    : b_(b)
    , f_(f)
  {
  }

  TSYNTH_INLINE_IN_CLONES void operator()(const float* block, const BoundTerms& out) const
  {
    Lanes arms;
    armsFloor(block, arms);
    noiseTerm(block, out.noise);
    landformTerm(block, out.landform);
    overlapFloor(block, out.overlap);
    for (std::size_t i = 0; i < kBlockLanes; ++i)
    {
      out.least[i] = totalCost(arms[i], { out.noise[i], out.overlap[i], out.landform[i] });
    }
  }

private:
  TSYNTH_INLINE_IN_CLONES const float* field(const float* block, std::size_t f) const
  {
    return block + f * kBlockLanes;
  }

  TSYNTH_INLINE_IN_CLONES void noiseTerm(const float* block, float* noise) const
  {
    Lanes sum = {};
    for (std::size_t l = 0; l < kNoiseLevels; ++l)
    {
      const float asked = b_.noise[l];
      if (!(asked > 0.0f))
      {
        continue;
      }
      const float* found = field(block, l);
      for (std::size_t i = 0; i < kBlockLanes; ++i)
      {
        const float relative = (asked - found[i]) / (asked + found[i]);
        sum[i] += relative * relative;
      }
    }
    for (std::size_t i = 0; i < kBlockLanes; ++i)
    {
      noise[i] = b_.noiseWeight * sum[i];
    }
  }

  TSYNTH_INLINE_IN_CLONES void landformTerm(const float* block, float* landform) const
  {
    Lanes sum = {};
    for (std::size_t m = 0; m < static_cast<std::size_t>(kLanes); ++m)
    {
      Lanes lane = {};
      for (std::size_t k = m; k < static_cast<std::size_t>(kLandformStride); k += kLanes)
      {
        const float asked = b_.landform[k];
        const float weight = b_.landformWeight[k];
        if (k >= f_.landform)
        {
          // Left out: 0 in every member, the same square for each.
          const float square = (weight * asked) * asked;
          for (std::size_t i = 0; i < kBlockLanes; ++i)
          {
            lane[i] += square;
          }
          continue;
        }
        const float* found = field(block, f_.landformAt() + k);
        for (std::size_t i = 0; i < kBlockLanes; ++i)
        {
          const float diff = asked - found[i];
          lane[i] += (weight * diff) * diff;
        }
      }
      for (std::size_t i = 0; i < kBlockLanes; ++i)
      {
        sum[i] += lane[i];
      }
    }
    for (std::size_t i = 0; i < kBlockLanes; ++i)
    {
      landform[i] =
        b_.landformWeightAll * (sum[i] / static_cast<float>(kLandformSamples) * b_.invScale2);
    }
  }

  // a_f c_f + a_a c_a at its least: per cyclic alignment of the arms, the
  // profiles at the distance of their moments and the angles as they are.
  TSYNTH_INLINE_IN_CLONES void armsFloor(const float* block, float* floor) const
  {
    if (b_.arms == 0)
    {
      std::fill(floor, floor + kBlockLanes, 0.0f);
      return;
    }
    WideLanes least;
    std::fill(least, least + kBlockLanes, std::numeric_limits<double>::infinity());
    const auto arms = static_cast<std::size_t>(b_.arms);
    for (std::size_t s = 0; s < arms; ++s)
    {
      WideLanes profile = {};
      WideLanes angle = {};
      for (std::size_t a = 0; a < arms; ++a)
      {
        const std::size_t arm = (a + s) % arms;
        addProfileGaps(block, a, arm, profile);
        addAngleGap(block, a, arm, angle);
      }
      for (std::size_t i = 0; i < kBlockLanes; ++i)
      {
        const double aligned = b_.profileScale * profile[i] + b_.angleScale * angle[i];
        least[i] = aligned < least[i] ? aligned : least[i];
      }
    }
    for (std::size_t i = 0; i < kBlockLanes; ++i)
    {
      floor[i] = static_cast<float>(least[i]);
    }
  }

  // The squared gaps of the query's arm a's moments to the candidate's arm `arm`'s.
  TSYNTH_INLINE_IN_CLONES void addProfileGaps(const float* block,
    std::size_t a,
    std::size_t arm,
    double* sum) const
  {
    if (!(b_.profileScale > 0.0))
    {
      return;
    }
    const std::size_t first = f_.momentsAt() + arm * FeatureRanker::kArmMoments;
    for (std::size_t j = 0; j < FeatureRanker::kArmMoments; ++j)
    {
      if (!(j < FeatureRanker::kMoments ? b_.along[a] : b_.across[a]))
      {
        continue;
      }
      const double asked = b_.moments[a][j];
      const float* found = field(block, first + j);
      for (std::size_t i = 0; i < kBlockLanes; ++i)
      {
        sum[i] += gapSquared(asked, found[i]);
      }
    }
  }

  // The squared difference of the query's arm a's angle and the candidate's
  // arm `arm`'s, the nearest way round, in half turns, as the cost takes it.
  TSYNTH_INLINE_IN_CLONES void addAngleGap(const float* block,
    std::size_t a,
    std::size_t arm,
    double* sum) const
  {
    // Adding and taking away 1.5 * 2^52 rounds a double of magnitude under
    // 2^51 to the nearest integer, ties to even, as std::remainder does.
    constexpr double kRoundingShift = 6755399441055744.0;
    const double turn = 2.0 * static_cast<double>(kPiF);
    const float asked = b_.angles[a];
    const float* found = field(block, f_.anglesAt() + arm);
    for (std::size_t i = 0; i < kBlockLanes; ++i)
    {
      const double d = asked - found[i]; // in floats, as the cost
      const double turns = (d / turn + kRoundingShift) - kRoundingShift;
      const double r = (d - turns * turn) / static_cast<double>(kPiF);
      sum[i] += r * r;
    }
  }

  // The overlap's floor (kOffsetOverlapRounding) from the candidate's
  // summaries' range and the query's.
  TSYNTH_INLINE_IN_CLONES void overlapFloor(const float* block, float* floor) const
  {
    if (!b_.offsetOverlap)
    {
      std::fill(floor, floor + kBlockLanes, 0.0f);
      return;
    }
    const float* lowest = field(block, f_.lowestAt());
    const float* highest = field(block, f_.highestAt());
    for (std::size_t i = 0; i < kBlockLanes; ++i)
    {
      const double above = b_.highest - lowest[i];
      const double below = highest[i] - b_.lowest;
      const double reach = above < below ? below : above;
      floor[i] = static_cast<float>(b_.overlapFloorScale * reach * reach);
    }
  }

  const BoundQuery& b_;
  const BlockFields& f_;
};

// Bounds `blocks` consecutive blocks: kBlockLanes results each.
TSYNTH_VECTOR_CLONES void boundBlocks(const BoundQuery& b,
  const BlockFields& f,
  const float* blocks,
  std::size_t count,
  const BoundTerms& out)
{
  const BlockBound bound(b, f);
  for (std::size_t k = 0; k < count; ++k)
  {
    bound(blocks + k * f.count() * kBlockLanes, out.from(k * kBlockLanes));
  }
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
  // Empty, to keep k (its storage kept for the next use).
  void reset(std::size_t k)
  {
    k_ = k;
    heap_.clear();
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

// How many of a thread's share of an exemplar's candidates, those of least
// bound, are scored in full before the others, per candidate kept: the k-th cheapest of them is the
// bar the rest must come under from the start.
constexpr std::size_t kWarmUpPerKept = 4;

} // namespace

FeatureRanker::FeatureRanker(const CandidatePool& pool)
  : pool_(pool)
{
  for (std::size_t c = 0; c < pool.size(); ++c)
  {
    Group& group = groups_[{ pool.type[c], pool.kind[c], pool.arms[c] }];
    group.arms = pool.arms[c];
    // Candidates ascend, and each exemplar's are one run of indices.
    if (group.members.empty() || pool.exemplar[group.members.back()] != pool.exemplar[c])
    {
      group.runs.push_back({ group.members.size(), group.members.size() });
    }
    group.members.push_back(c);
    group.runs.back().second = group.members.size();
  }
  for (auto& entry : groups_)
  {
    layOutBoundData(entry.second);
  }
}

void FeatureRanker::layOutBoundData(Group& group) const
{
  const std::size_t n = group.members.size();
  auto landformAt = [&](std::size_t i, std::size_t k)
  { return pool_.landform[group.members[i] * kLandformStride + k]; };
  // The landform's padding is kept only where some member has it other than 0.
  group.landformFields = static_cast<std::size_t>(kLandformSamples);
  for (std::size_t i = 0; i < n; ++i)
  {
    for (std::size_t k = group.landformFields; k < kLandformStride; ++k)
    {
      group.landformFields = landformAt(i, k) != 0.0f ? kLandformStride : group.landformFields;
    }
  }
  const BlockFields fields = blockFieldsOf(group);
  const std::size_t blocks = (n + kBlockLanes - 1) / kBlockLanes;
  group.blocks.assign(blocks * fields.count() * kBlockLanes, 0.0f); // the last block padded with 0
  auto at = [&](std::size_t i, std::size_t field) -> float&
  {
    const std::size_t block = i / kBlockLanes;
    return group.blocks[(block * fields.count() + field) * kBlockLanes + i % kBlockLanes];
  };
  for (std::size_t i = 0; i < n; ++i)
  {
    const std::size_t c = group.members[i];
    for (std::size_t l = 0; l < kNoiseLevels; ++l)
    {
      at(i, l) = pool_.noise[c * kNoiseLevels + l];
    }
    for (std::size_t k = 0; k < fields.landform; ++k)
    {
      at(i, fields.landformAt() + k) = landformAt(i, k);
    }
    for (std::size_t b = 0; b < static_cast<std::size_t>(group.arms); ++b)
    {
      const std::size_t row = rowMajor(b, c, kMaxArms);
      const auto along = momentsOf(pool_.along.data() + row * kAlongSamples, kAlongSamples);
      const auto across = momentsOf(pool_.across.data() + row * kAcrossSamples, kAcrossSamples);
      std::size_t field = fields.momentsAt() + b * kArmMoments;
      for (const double m : { along[0], along[1], across[0], across[1] })
      {
        at(i, field++) = static_cast<float>(m);
      }
      at(i, fields.anglesAt() + b) = pool_.angles[row];
    }
    const auto first = pool_.descriptor.begin() + static_cast<long>(c * kDescriptorSize);
    const auto range = std::minmax_element(first, first + kDescriptorSize);
    at(i, fields.lowestAt()) = *range.first;
    at(i, fields.highestAt()) = *range.second;
  }
}

struct FeatureRanker::Scratch
{
  std::vector<float> noise;       // each candidate's roughness term
  std::vector<float> landform;    // and landform term
  std::vector<float> overlap;     // the overlap's floor
  std::vector<float> least;       // its cost with the rest at their least
  KeptCandidates leastBound{ 0 }; // the warm-up: indices i of leastOf(i), least costs
  std::vector<char> warmed;
  std::size_t first = 0; // where the ranked members start in the arrays above
  // Member `from + i`'s terms and least cost.
  float noiseOf(std::size_t i) const { return noise[first + i]; }
  float landformOf(std::size_t i) const { return landform[first + i]; }
  float overlapFloorOf(std::size_t i) const { return overlap[first + i]; }
  float leastOf(std::size_t i) const { return least[first + i]; }
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
  ExemplarRanking(const ScoredQuery& scored, const BoundQuery& bounds)
    : s_(scored)
    , b_(bounds)
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
    bound(group, from, n, x);
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
      if (outranked(x.leastOf(i)))
      {
        ++counts.beforeArms;
        continue;
      }
      const std::size_t c = members[i];
      CostTerms terms{ x.noiseOf(i), x.overlapFloorOf(i), x.landformOf(i) };
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
  // Each candidate's roughness, landform, overlap floor and least cost, from the
  // blocks holding members [from, from + n): x's arrays start at the first
  // block's first member, x.first before `from`.
  void bound(const Group& group, std::size_t from, std::size_t n, Scratch& x) const
  {
    const std::size_t first = from / kBlockLanes;
    const std::size_t last = (from + n + kBlockLanes - 1) / kBlockLanes;
    const std::size_t lanes = (last - first) * kBlockLanes;
    x.first = from - first * kBlockLanes;
    x.noise.resize(lanes);
    x.landform.resize(lanes);
    x.overlap.resize(lanes);
    x.least.resize(lanes);
    const BlockFields fields = blockFieldsOf(group);
    boundBlocks(b_,
      fields,
      group.blocks.data() + first * fields.count() * kBlockLanes,
      last - first,
      { x.noise.data(), x.landform.data(), x.overlap.data(), x.least.data() });
  }

  // Scores in full the candidates of least bound and offers them first, so
  // the bar the rest must come under is low from the start: the count of
  // least bound, ties by index.
  void warmUp(const std::size_t* members, std::size_t n, KeptCandidates& kept, Scratch& x) const
  {
    x.warmed.assign(n, 0);
    const std::size_t count = std::min(n, kWarmUpPerKept * kept.capacity());
    if (!bounded_ || count == 0)
    {
      return;
    }
    // The count of least bound, ties by index, in one pass: a candidate
    // enters only when it beats the dearest of those held.
    x.leastBound.reset(count);
    for (std::size_t i = 0; i < n; ++i)
    {
      if (!std::isnan(x.leastOf(i))) // never outranked: the main loop scores it
      {
        x.leastBound.offer({ i, x.leastOf(i) });
      }
    }
    for (const RankedCandidate& r : x.leastBound.kept())
    {
      const std::size_t i = r.index;
      CostTerms terms{ x.noiseOf(i), s_.overlapOf(members[i]), x.landformOf(i) };
      kept.offer({ members[i], totalCost(s_.armsOf(members[i]), terms) });
      x.warmed[i] = 1;
    }
  }

  const ScoredQuery& s_;
  const BoundQuery& b_;
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
  const BoundQuery bounds = boundQuery(scored);
  const ExemplarRanking ranking(scored, bounds);
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
      counts->beforeArms += t.beforeArms;
      counts->beforeOverlap += t.beforeOverlap;
      counts->scored += t.scored;
    }
  }
  return ranked;
}

} // namespace tsynth
