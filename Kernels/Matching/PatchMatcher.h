// The matcher as the synthesis uses it: one object holding the candidate pool
// and the dense-search tables of a set of exemplars, on the chosen backend.
#pragma once

#include "../Core/PatchSize.h"
#include "CandidatePool.h"
#include "DenseSearch.h"
#include "FeatureCost.h"
#include "FeatureRanking.h"
#include "MatcherLimits.h"
#include "OpenClMatcher.h"

#include <memory>
#include <string>
#include <vector>

namespace tsynth
{

struct MatcherOptions
{
  int patchSize = kDefaultSynthesisPatch;
  Backend backend = Backend::Auto;
  MatchWeights weights;
  std::size_t k = 8; // candidates kept per exemplar (feature) or in all (dense)
  int coarseFactor = 4;
  double landformWeight = 10.0; // a_l of the dense search (DenseOptions)
  std::array<bool, kVariantCount>
    variants{ true, true, true, true, true, true, true, true, true, true };
  // The feature candidate pool of these exemplars and graphs at this patch size
  // with these variants, built before (Synthesis/ExemplarCache.h); null: built
  // by the matcher.
  std::shared_ptr<const CandidatePool> pool;
};

// A feature match, or a dense one when the pool has nothing of the site's type.
struct PatchCandidate
{
  int exemplar = 0;
  int variant = 0;
  double centreX = 0.0; // patch centre in the exemplar's cells
  double centreY = 0.0;
  float cost = 0.0f;
  // Dense matches: root mean square landform misfit at the samples (m).
  float landformMisfit = 0.0f;
  bool feature = true;       // false: from the dense (non-feature) search
  std::size_t poolIndex = 0; // feature matches only
};

class PatchMatcher
{
public:
  // Builds the pool and the dense tables; picks the backend (Auto: OpenCL if a
  // device builds the kernels, else the CPU with a warning naming the reason).
  // Throws tsynth::Error for unusable input (an exemplar smaller than a patch),
  // or when Backend::OpenCL is requested and does not work.
  PatchMatcher(const std::vector<const Heightfield*>& exemplars,
    const std::vector<const FeatureGraph*>& graphs,
    const MatcherOptions& options,
    const std::vector<std::string>& names = {});
  ~PatchMatcher();

  Backend backend() const { return backend_; }
  std::string backendName() const;
  const std::vector<std::string>& warnings() const { return warnings_; }
  const CandidatePool& pool() const { return *pool_; }
  const DenseMatcher& dense() const { return *dense_; }

  // Costs of every pool candidate for a query (for cost maps and tables).
  std::vector<float> featureCosts(const FeatureQuery& query);
  // The k best of each exemplar, merged by cost. If no candidate has the
  // query's type and kind, falls back to the dense search of `window` (when
  // given) and adds a warning.
  std::vector<PatchCandidate> matchFeature(const FeatureQuery& query,
    const DenseQuery* window = nullptr);
  // The k best of all exemplars, or of the listed ones only.
  std::vector<PatchCandidate> matchDense(const DenseQuery& window,
    const std::vector<int>* exemplars = nullptr);

private:
  MatcherOptions options_;
  Backend backend_ = Backend::Cpu;
  std::vector<std::string> warnings_;
  std::shared_ptr<const CandidatePool> pool_;
  std::unique_ptr<FeatureRanker> ranker_; // feature matching on the CPU
  std::unique_ptr<DenseMatcher> dense_;
  std::shared_ptr<OpenClDevice> device_;
  std::unique_ptr<OpenClFeatureScorer> featureScorer_;
  std::unique_ptr<OpenClDenseScorer> denseScorer_;
};

// The Patch Matcher filter's options (Core/OptionTable.h), their defaults a default
// MatcherOptions': the patch size, the candidates kept (K), the backend, and the cost weights
// the synthesis matches with. No tsynth command runs the matcher alone.
const std::vector<OptionRow>& matcherOptionRows();

} // namespace tsynth
