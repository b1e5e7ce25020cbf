#include "PatchMatcher.h"

#include "../Core/Error.h"

#include <algorithm>
#include <cmath>

namespace tsynth
{

PatchMatcher::PatchMatcher(const std::vector<const Heightfield*>& exemplars,
  const std::vector<const FeatureGraph*>& graphs,
  const MatcherOptions& options,
  const std::vector<std::string>& names)
  : options_(options)
{
  if (options.pool)
  {
    if (options.pool->patchSize != options.patchSize ||
      options.pool->exemplars.size() != exemplars.size())
    {
      throw Error("Internal error: the candidate pool given was built for other exemplars or "
                  "another patch size.");
    }
    pool_ = options.pool;
  }
  else
  {
    PoolOptions po;
    po.patchSize = options.patchSize;
    po.variants = options.variants;
    pool_ = std::make_shared<const CandidatePool>(buildCandidatePool(exemplars, graphs, po, names));
  }
  ranker_ = std::make_unique<FeatureRanker>(*pool_);
  warnings_ = pool_->warnings;
  DenseOptions dopt;
  dopt.patchSize = options.patchSize;
  dopt.coarseFactor = options.patchSize % options.coarseFactor == 0 ? options.coarseFactor : 1;
  dopt.variants = options.variants;
  dopt.landformWeight = options.landformWeight;
  dense_ = std::make_unique<DenseMatcher>(exemplars, dopt);

  if (!matchesOnOpenCl(options.backend))
  {
    backend_ = Backend::Cpu;
    return;
  }
  try
  {
    device_ = OpenClDevice::create();
    featureScorer_ = std::make_unique<OpenClFeatureScorer>(device_, *pool_);
    denseScorer_ = std::make_unique<OpenClDenseScorer>(device_, *dense_);
    backend_ = Backend::OpenCL;
  }
  catch (const Error& e)
  {
    if (options.backend == Backend::OpenCL)
    {
      throw;
    }
    featureScorer_.reset();
    denseScorer_.reset();
    device_.reset();
    backend_ = Backend::Cpu;
    warnings_.push_back(std::string("OpenCL is not usable, matching on the CPU: ") + e.what());
  }
}

PatchMatcher::~PatchMatcher() = default;

std::string PatchMatcher::backendName() const
{
  return backend_ == Backend::OpenCL ? "opencl (" + device_->name() + ")" : "cpu";
}

std::vector<float> PatchMatcher::featureCosts(const FeatureQuery& query)
{
  return featureScorer_ ? featureScorer_->score(query, options_.weights)
                        : scoreFeatureCandidates(*pool_, query, options_.weights);
}

std::vector<PatchCandidate> PatchMatcher::matchFeature(const FeatureQuery& query,
  const DenseQuery* window)
{
  // The CPU scores only what can be among the k best; OpenCL scores all.
  const std::vector<RankedCandidate> ranked = featureScorer_
    ? topKPerExemplar(*pool_, featureCosts(query), options_.k)
    : ranker_->rank(query, options_.weights, options_.k);
  std::vector<PatchCandidate> out;
  for (const RankedCandidate& r : ranked)
  {
    if (r.cost >= kMismatchPenalty)
    {
      continue; // nothing of this type and kind: handled below
    }
    PatchCandidate c;
    c.exemplar = pool_->exemplar[r.index];
    c.variant = pool_->variant[r.index];
    c.centreX = pool_->centreX[r.index];
    c.centreY = pool_->centreY[r.index];
    c.cost = r.cost;
    c.poolIndex = r.index;
    out.push_back(c);
  }
  if (out.empty() && window != nullptr)
  {
    const char* what = query.type > 0 ? "ridge" : "valley";
    const std::string warning = std::string("No exemplar has a ") + what +
      " feature of this kind: using non-feature candidates instead.";
    if (std::find(warnings_.begin(), warnings_.end(), warning) == warnings_.end())
    {
      warnings_.push_back(warning);
    }
    return matchDense(*window);
  }
  return out;
}

std::vector<PatchCandidate> PatchMatcher::matchDense(const DenseQuery& window,
  const std::vector<int>* exemplars)
{
  const CoarseQuery coarse = dense_->coarseQuery(window);
  const DenseMatcher::RefineRequest request{ options_.k, exemplars };
  const auto costs = dense_->prunedCoarseCosts(
    coarse,
    [this](const CoarseTerms& t, CoarseImage i, const std::vector<std::vector<std::uint8_t>>* r)
    { return denseScorer_ ? denseScorer_->coarseSsd(t, i, r) : dense_->coarseSsd(t, i, r); },
    &request);
  std::vector<PatchCandidate> out;
  for (const DenseMatch& m : dense_->refine(window, costs, options_.k, exemplars))
  {
    PatchCandidate c;
    c.exemplar = m.exemplar;
    c.variant = m.variant;
    c.centreX = m.centreX;
    c.centreY = m.centreY;
    c.cost = m.cost;
    c.landformMisfit = m.landformRms;
    c.feature = false;
    out.push_back(c);
  }
  return out;
}

const std::vector<OptionRow>& matcherOptionRows()
{
  static const std::vector<OptionRow> rows = []
  {
    const MatcherOptions d;
    const MatchWeights& w = d.weights;
    using T = OptionType;
    return std::vector<OptionRow>{
      numberRow("PatchSize", "", T::Integer, d.patchSize, kMinSynthesisPatch, kMaxSynthesisPatch),
      numberRow("K", "", T::Integer, static_cast<double>(d.k), 1, kMaxCandidatesKept),
      choiceRow("Backend",
        "",
        static_cast<int>(d.backend),
        choicesOf(kBackendWords),
        { "Auto", "OpenCL", "CPU" }),
      numberRow("FeatureWeight", "", T::Real, w.feature, 0.0, kMaxMatchWeight),
      numberRow("AngleWeight", "", T::Real, w.angle, 0.0, kMaxMatchWeight),
      numberRow("NoiseWeight", "", T::Real, w.noise, 0.0, kMaxMatchWeight),
      numberRow("OverlapWeight", "", T::Real, w.overlap, 0.0, kMaxMatchWeight),
      switchRow("VerticalOffset", "", w.verticalOffset),
    };
  }();
  return rows;
}

} // namespace tsynth
