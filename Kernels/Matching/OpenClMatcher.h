// The matcher's two heavy loops on an OpenCL device (PoCL on this machine's CPU,
// or any GPU): feature-cost scoring of a whole pool, and the coarse pass of the
// dense search. Kernels live in Kernels/Matching/OpenCL/*.cl, embedded at build
// time; results equal the CPU reference (FeatureCost.cxx, DenseSearch.cxx).
#pragma once

#include "CandidatePool.h"
#include "DenseSearch.h"
#include "FeatureCost.h"

#include "../Core/OptionTable.h"

#include <cstddef>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

namespace tsynth
{

enum class Backend
{
  // OpenCL on a GPU or accelerator (openClHasAccelerator), else the CPU; a GPU
  // that does not work falls back to the CPU with one line of warning.
  Auto,
  OpenCL,
  Cpu
};

// The backends' words, by value (Core/OptionTable.h).
inline constexpr const char* kBackendWords[] = { "auto", "opencl", "cpu" };
static_assert(std::size(kBackendWords) == static_cast<std::size_t>(Backend::Cpu) + 1);

// One of kBackendWords; throws tsynth::Error naming them otherwise.
Backend parseBackend(const std::string& text);

// Whether an OpenCL platform offers a GPU or an accelerator (false when none
// is installed). Where OpenCL's only device is a CPU (PoCL), it runs the same
// kernels on the same cores as the CPU backend, which is quicker there (a
// 1024^2 synthesis 5.4 s against 6.4 s, here), so Backend::Auto takes the CPU.
// Asked once per process and remembered: loading the platforms takes 0.1 s
// here (PoCL loads LLVM), so a synthesis asks only when it must (the memory
// check of the whole run, the matcher's set-up), after its preview.
bool openClHasAccelerator();

// Whether the matcher will run on OpenCL with this backend choice (for Auto,
// whether there is an accelerator): what the memory estimate counts.
bool matchesOnOpenCl(Backend backend);

class OpenClRuntime;

// Shared device, context, queue and built programs. create() throws
// tsynth::Error naming the reason (no platform, no device, or the compiler's
// build log) so callers can fall back to the CPU.
class OpenClDevice
{
public:
  // `extraSource` is compiled with the kernels (tests use it to check that a
  // build error is reported with the compiler's log).
  static std::shared_ptr<OpenClDevice> create(const std::string& extraSource = {});
  ~OpenClDevice();
  OpenClDevice(const OpenClDevice&) = delete;
  OpenClDevice& operator=(const OpenClDevice&) = delete;
  std::string name() const;
  OpenClRuntime& runtime() { return *runtime_; }

private:
  OpenClDevice();
  std::unique_ptr<OpenClRuntime> runtime_;
};

// Uploads a pool once; scores queries on the device.
class OpenClFeatureScorer
{
public:
  OpenClFeatureScorer(std::shared_ptr<OpenClDevice> device, const CandidatePool& pool);
  ~OpenClFeatureScorer();
  std::vector<float> score(const FeatureQuery& query, const MatchWeights& weights);

private:
  struct Buffers;
  std::shared_ptr<OpenClDevice> device_;
  std::unique_ptr<Buffers> buffers_;
  std::size_t size_ = 0;
  float invScale2_ = 1.0f;
};

// Uploads a dense matcher's coarse images once; computes coarse costs on the device.
class OpenClDenseScorer
{
public:
  OpenClDenseScorer(std::shared_ptr<OpenClDevice> device, const DenseMatcher& matcher);
  ~OpenClDenseScorer();
  // Same layout and values as DenseMatcher::coarseCosts and coarseSsd.
  std::vector<std::vector<float>> coarseCosts(const CoarseQuery& query);
  std::vector<std::vector<float>> coarseSsd(const CoarseTerms& terms,
    CoarseImage image,
    const std::vector<std::vector<std::uint8_t>>* runs);

private:
  struct Buffers;
  std::shared_ptr<OpenClDevice> device_;
  const DenseMatcher& matcher_;
  std::unique_ptr<Buffers> buffers_;
};

} // namespace tsynth
