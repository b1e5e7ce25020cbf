// Feature matching on the CPU without scoring every candidate in full. The
// ranker finds, per exemplar, the k cheapest candidates of a query's type,
// kind and number of arms: topKPerExemplar(scoreFeatureCandidates(...)) less
// the candidates never chosen, the same candidates and costs bit for bit.
//
// A candidate's cost is a float sum of terms that are each at least 0 (the
// overlap up to a vertical offset at least a known floor), and a float sum
// never falls when a term grows. So a sum with the dearer terms at their least
// bounds the cost from below, and a candidate whose bound is already dearer
// than k candidates of its exemplar cannot be among the k cheapest: it is left
// before its dearer terms are worked out. The terms, from cheap to dear:
// roughness, landform, and the arms' angles with their profiles at their
// least from two moments of each profile (a few dozen numbers, bounded for
// many candidates at once, one per vector lane); the arms' profiles in full;
// the overlap's 256 summaries.
#pragma once

#include "CandidatePool.h"
#include "FeatureCost.h"

#include <array>
#include <map>
#include <utility>
#include <vector>

namespace tsynth
{

// How far a ranking went with its candidates.
struct RankingCounts
{
  std::size_t shaped = 0;        // candidates of the query's type, kind and arms
  std::size_t beforeArms = 0;    // left on roughness, landform, angles and profiles' moments
  std::size_t beforeOverlap = 0; // left on the arms
  std::size_t scored = 0;        // scored in full
};

class FeatureRanker
{
public:
  explicit FeatureRanker(const CandidatePool& pool);
  ~FeatureRanker();

  // The k cheapest candidates of each exemplar, merged in cost order (ties by
  // index). One query at a time: the ranker keeps its working space. The
  // same for any number of threads.
  std::vector<RankedCandidate> rank(const FeatureQuery& query,
    const MatchWeights& weights,
    std::size_t k,
    RankingCounts* counts = nullptr);

  // The two moments kept per profile: its mean and its straight slope.
  static constexpr int kMoments = 2;
  // Per arm: the along profile's moments, then the across profile's.
  static constexpr int kArmMoments = 2 * kMoments;

private:
  class ExemplarRanking;
  struct Scratch; // a query's working space, kept for the next

  const CandidatePool& pool_;
  // The candidates of one type, kind and number of arms, index ascending, and
  // the runs of them [first, last) of one exemplar each. What the bounds read
  // of them is copied in blocks of 64 members: in a block, each field (a noise
  // variance, a landform sample, a moment...) holds its 64 members' numbers
  // side by side, so they fill a vector's lanes, and a ranking streams
  // through the blocks in order.
  struct Group
  {
    std::vector<std::size_t> members;
    std::vector<std::pair<std::size_t, std::size_t>> runs;
    int arms = 0;
    std::size_t landformFields = 0; // landform samples kept per member
    std::vector<float> blocks;      // the last block padded with zeros
  };
  void layOutBoundData(Group& group) const;

  std::map<std::array<int, 3>, Group> groups_; // by type, kind, arms
  std::vector<Scratch> scratch_;               // per thread
};

} // namespace tsynth
