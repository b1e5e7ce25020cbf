// Feature candidates: every feature site of the exemplars (end and branch nodes,
// and path points every quarter patch along chains) in all 10 variants, with the
// descriptors the matcher compares: arm angles, height profiles along and across
// each arm, multi-resolution noise variance and a 16 x 16 summary of the patch.
// Stored as flat arrays (one entry per candidate variant) so the CPU loop and
// the OpenCL kernel read them the same way.
// In ParaView: vtkTerrainCandidateBuilder (Terrain Candidate Builder), in Filters/.
#pragma once

#include "../Core/Heightfield.h"
#include "../Core/PatchSize.h"
#include "../Features/FeatureGraph.h"
#include "LandformTerm.h"
#include "NoiseVariance.h"
#include "Orientation.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace tsynth
{

constexpr int kMaxArms = 4;
constexpr int kAlongSamples = 16;
constexpr int kAcrossSamples = 17;
constexpr int kDescriptorSide = 16;
constexpr int kDescriptorSize = kDescriptorSide * kDescriptorSide;

// A place to match: a feature node, or a point on a chain (kind Path, 2 arms).
struct FeatureSite
{
  Point2 centre;
  FeatureType type = FeatureType::Ridge;
  NodeKind kind = NodeKind::End;
  int node = -1;  // the graph node, or -1 for a path point
  int chain = -1; // for a path point: its chain
  std::vector<ControlPoint> arms;
};

// End and branch nodes of a graph plus path points along its chains every
// `spacing` cells (0: a quarter patch, dense enough for candidates; placement
// uses kSiteSpacingInPatches), not closer than a quarter patch to a chain's ends, each
// with arms where its chains cross the circle of half a patch. `phases`, when
// given, shifts each chain's first path point by that share (0..1) of the spacing.
std::vector<FeatureSite> featureSites(const FeatureGraph& graph,
  int patchSize,
  double spacing = 0.0,
  const std::vector<double>* phases = nullptr);

struct PoolOptions
{
  int patchSize = kDefaultSynthesisPatch;
  std::array<bool, kVariantCount>
    variants{ true, true, true, true, true, true, true, true, true, true };
};

struct ExemplarInfo
{
  std::string name;
  int width = 0;
  int height = 0;
  std::size_t firstCandidate = 0;
  std::size_t candidateCount = 0;
  // hashHeightfield of the heights the candidates were cut from, when the pool
  // came with it (the Candidate Builder's table); 0: not known.
  std::uint64_t heightsChecksum = 0;
};

struct CandidatePool
{
  int patchSize = kDefaultSynthesisPatch;
  double heightScale =
    1.0; // standard deviation of all exemplar heights (m): costs are divided by it
  std::vector<ExemplarInfo> exemplars;
  std::vector<std::string> warnings;

  // One entry per candidate variant.
  std::vector<int> exemplar;
  std::vector<int> site; // index into sites
  std::vector<int> variant;
  std::vector<int> kind;               // NodeKind
  std::vector<int> type;               // +1 ridge, -1 valley
  std::vector<int> arms;               // number of arms (<= kMaxArms)
  std::vector<float> centreX, centreY; // in the exemplar, cells
  std::vector<float> angles;           // size * kMaxArms, placed frame, counter-clockwise order
  std::vector<float> along;      // size * kMaxArms * kAlongSamples, heights minus the centre height
  std::vector<float> across;     // size * kMaxArms * kAcrossSamples, same
  std::vector<float> noise;      // size * kNoiseLevels
  std::vector<float> descriptor; // size * kDescriptorSize block means of the placed patch (m)
  // size * kLandformStride: the low-passed exemplar at the landform samples of
  // the placed patch, minus its value at the centre (m); padding 0.
  std::vector<float> landform;

  std::vector<FeatureSite> sites;

  std::size_t size() const { return variant.size(); }
};

// Builds the pool from exemplars and their feature graphs (same order). Sites
// whose patch (in any rotation) would leave the exemplar or touch nodata are
// excluded. Throws tsynth::Error if an exemplar is smaller than the patch.
CandidatePool buildCandidatePool(const std::vector<const Heightfield*>& exemplars,
  const std::vector<const FeatureGraph*>& graphs,
  const PoolOptions& options = {},
  const std::vector<std::string>& names = {});

// Refuses a pool handed in from outside (the table the Candidate Builder
// writes, read back by the Patch Matcher) that does not fit these exemplars at
// this patch size, or whose arrays do not hold together: another patch size,
// exemplar count or exemplar size, arrays of the wrong length, candidates out
// of their exemplar or out of order, values that are not finite, exemplars
// whose heights' checksum (where the pool knows it) is not the given ones'.
// Throws tsynth::Error with one sentence saying what disagrees.
void checkGivenPool(const CandidatePool& pool,
  const std::vector<const Heightfield*>& exemplars,
  int patchSize);

// Adds b's candidates after a's (exemplar indices shifted); heightScale pooled.
void mergePools(CandidatePool& a, const CandidatePool& b);

// What a target site looks like, in the same terms as a candidate.
struct FeatureQuery
{
  int type = 1;
  int kind = 1;
  int arms = 0;
  std::array<float, kMaxArms> angles{};
  std::array<float, kMaxArms * kAlongSamples> along{};
  std::array<float, kMaxArms * kAcrossSamples> across{};
  std::array<float, kNoiseLevels> noise{};
  std::array<float, kDescriptorSize> descriptor{}; // already-synthesised heights
  std::array<float, kDescriptorSize> weight{};     // fraction of each descriptor cell known (0..1)
  // The low-passed target at the landform samples minus its value at the
  // centre, and the confidence in each (0 where the output is already known).
  std::array<float, kLandformStride> landform{};
  std::array<float, kLandformStride> landformWeight{};
};

// Profiles from the target heightfield (the sketch's field), noise from its
// prepared NoiseVariance, overlap descriptor from the output synthesised so far
// (`known` marks its filled cells; both may be null for "nothing known yet"),
// landform samples from the low-passed target with their confidence (both may
// be null: no landform term).
FeatureQuery makeFeatureQuery(const FeatureSite& site,
  const Heightfield& target,
  const NoiseVariance& targetNoise,
  const Heightfield* output,
  const std::vector<std::uint8_t>* known,
  int patchSize,
  const Heightfield* lowTarget = nullptr,
  const std::vector<float>* confidence = nullptr);

} // namespace tsynth
