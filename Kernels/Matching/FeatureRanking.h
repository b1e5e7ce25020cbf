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
// roughness and landform (a few samples); the arms' profiles at their least
// from two moments of each profile; the arms' profiles and angles; the
// overlap's 256 summaries.
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
  std::size_t beforeMoments = 0; // left on roughness and landform alone
  std::size_t beforeArms = 0;    // left on the profiles' moments
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
  // of each is copied in the same order, so a ranking streams through it.
  struct Group
  {
    std::vector<std::size_t> members;
    std::vector<std::pair<std::size_t, std::size_t>> runs;
    std::vector<float> cheap;                 // per member: noise variances, landform samples
    std::vector<float> moments;               // per member and arm: kArmMoments
    std::vector<std::array<float, 2>> ranges; // per member: its descriptor's least and greatest
  };
  void addBoundData(Group& group, std::size_t c) const;

  std::map<std::array<int, 3>, Group> groups_;        // by type, kind, arms
  std::vector<std::array<float, 2>> descriptorRange_; // per candidate
  std::vector<float> moments_;                        // per candidate and arm, kArmMoments
  std::vector<Scratch> scratch_;                      // per thread
};

} // namespace tsynth
