// Non-feature candidates: the masked SSD of a target window (its known cells
// only) against every offset of every exemplar in every enabled variant. A
// coarse pass (heights averaged over f x f blocks) scores every offset (first a
// cheap lower bound from 2f x 2f means, then the full sum only where the bound
// leaves an offset a chance), then the best coarse offsets overall are refined
// cell by cell at full resolution: far fewer operations than exhaustive search,
// with the same winner on almost every query (Testing/Cxx/Matching/TestDenseSearch.cxx
// measures the recall).
#pragma once

#include "../Core/Heightfield.h"
#include "LandformTerm.h"
#include "NoiseVariance.h"
#include "Orientation.h"

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

namespace tsynth
{

// Neighbouring offsets scored together at full resolution.
constexpr int kRowLanes = 8;

struct DenseOptions
{
  int patchSize = 64;
  int coarseFactor = 4;        // block side of the coarse pass (1 = exhaustive)
  int refinePerVariant = 4;    // best coarse offsets kept per exemplar and variant ...
  int refineTotal = 32;        // ... of which this many (the best overall) are refined
  double overlapWeight = 10.0; // a_o (Tasse's non-feature weights)
  // a_n: the roughness term (roughnessMisfit). Without it the masked SSD
  // prefers the exemplars' smoothest windows, whose heights stray least from
  // anything, and the fill came out flatter than the exemplars (mean slope
  // 16.4 against Colorado's 18.3 degrees). At 1, a window twice or half as
  // rough as asked at every level (misfit 1/3) costs as much as an overlap
  // misfit of a fifth of the exemplars' height spread, RMS.
  double noiseWeight = 1.0;
  // a_l: the landform term (LandformTerm.h) against the overlap. Equal weights
  // make a metre of large-scale misfit on the still-empty part of a window cost
  // as much as a metre of misfit on what is already there.
  double landformWeight = 10.0;
  std::array<bool, kVariantCount>
    variants{ true, true, true, true, true, true, true, true, true, true };
};

struct DenseMatch
{
  int exemplar = 0;
  int variant = 0;
  int x = 0; // window's lower-left cell in the oriented exemplar
  int y = 0;
  double centreX = 0.0; // window centre in the exemplar's own cells
  double centreY = 0.0;
  float overlap = 0.0f;     // mean squared difference over known cells / heightScale^2
  float landform = 0.0f;    // weighted mean squared landform misfit / heightScale^2
  float landformRms = 0.0f; // root mean square landform misfit per unit of sample weight, m
  float roughness = 0.0f;   // roughnessMisfit of the query's noise and the window's
  float cost =
    0.0f; // overlapWeight * overlap + landformWeight * landform + noiseWeight * roughness
};

// The target of a dense query: a patch-sized window of heights (row-major, row
// 0 south) with a mask of the cells already known, and the noise variances to
// compare with (zeros to ignore).
struct DenseQuery
{
  std::vector<float> heights;
  std::vector<std::uint8_t> known;
  std::array<float, kNoiseLevels> noise{};
  // The low-passed target at the landform samples of the window, with its
  // confidence (empty weights: no landform term).
  LandformQuery landform;
};

// Terms of a coarse weighted SSD: blocks (row, column) of the query's coarse
// grid with their heights and weights, in the order they are summed.
struct CoarseTerms
{
  std::vector<int> row, column;
  std::vector<float> heights, weights;
  std::size_t size() const { return row.size(); }
  bool empty() const { return row.empty(); }
  void add(int r, int c, float h, float w);
};

// The coarse form of a query: block means of known cells, and the fraction of
// each block known as its weight. Side = patchSize / coarseFactor.
struct CoarseQuery
{
  int side = 0;
  std::vector<float> heights;
  std::vector<float> weights;
  CoarseTerms terms; // the blocks with a known part, row by row: only they enter the sums
  // Aligned 2 x 2 groups of equally weighted blocks, as one term each against
  // the exemplar's 2 x 2 block means: by Cauchy-Schwarz, sum w d_i^2 over a
  // group >= 4 w (mean d)^2, so this SSD is a lower bound of the one over
  // `terms` at every offset, for a quarter of the work.
  CoarseTerms bound;
  // Aligned 4 x 4 groups of equally weighted blocks against the exemplar's
  // 4 x 4 block means: by the same argument a lower bound of `bound`, for a
  // quarter of its work again. Prunes before `bound` is summed.
  CoarseTerms quadBound;
  // The landform samples, read from the low-passed exemplar's block means
  // stacked below the blocks (and pairs and quads), with weights that keep their share of
  // the cost as in refine(); they are also the last terms of `terms`, `bound`
  // and `quadBound`.
  CoarseTerms landform;
};

// Which image of an oriented exemplar a coarse SSD reads.
enum class CoarseImage
{
  Blocks, // f x f block means (then the low-passed exemplar's, see stackLandform)
  Pairs,  // means of 2 x 2 blocks (then the same)
  Quads   // means of 4 x 4 blocks (then the same)
};

// How far a window's roughness is from the one asked for: over the noise
// levels, the squared relative difference (a - f) / (a + f) of the band
// variances asked (a) and found (f). Scale-free, 0 when equal; a window with
// twice or half the variance asked costs 1/9 per level; a level asked as 0 is
// left out (nothing asked).
double roughnessMisfit(const std::array<float, kNoiseLevels>& asked,
  const std::array<float, kNoiseLevels>& found);

class DenseMatcher
{
public:
  DenseMatcher(const std::vector<const Heightfield*>& exemplars, const DenseOptions& options);

  // One exemplar seen through one variant, at full and coarse resolution.
  struct Oriented
  {
    int exemplar = 0;
    int variant = 0;
    Heightfield full; // invalid outside the rotated exemplar and in kRowLanes padding columns
    double centreX = 0.0, centreY = 0.0; // where the exemplar's centre lies in `full`
    int coarseWidth = 0, coarseHeight = 0;
    int coarseStride = 0;      // row length, padded so 16 offsets can be read at once
    std::vector<float> coarse; // coarseHeight x coarseStride block means (0 where invalid),
                               // then the landform's (landformBlocks) from a shared row
    std::vector<float>
      pairs; // same layout: mean of the 2 x 2 blocks from (a, b) on, then the same landform rows
    std::vector<float> quads; // same layout: mean of the 4 x 4 blocks from (a, b) on, then the same
    Heightfield landform;     // the low-passed exemplar (LandformTerm.h), laid out as `full`;
                              // its mask dropped once landformBlocks are made
    std::vector<float> landformBlocks;     // its block means, laid out as `coarse`
    std::vector<std::uint8_t> coarseValid; // per coarse offset: whole window valid
    std::vector<std::uint8_t> groupValid;  // per run of 16 coarse offsets: any of them valid
    std::vector<std::uint8_t> fullValid;   // per full offset: whole window valid
    int offsetsX = 0, offsetsY = 0;        // coarse offsets per row / column
  };

  const std::vector<Oriented>& oriented() const { return oriented_; }
  const DenseOptions& options() const { return options_; }
  double heightScale() const { return heightScale_; }
  // The exemplars' median noise variances per level over patch-sized windows
  // on a grid half a patch apart: what a window of their land typically holds.
  std::array<float, kNoiseLevels> typicalNoise() const;

  CoarseQuery coarseQuery(const DenseQuery& query) const;
  // Coarse weighted SSD of `terms` read from `image`, per oriented exemplar:
  // costs[o][y * offsetsX + x], +inf at invalid offsets and, when `runs` is
  // given, in runs of 16 offsets it does not mark (runs[o][y * groups + x / 16]);
  // empty for an oriented exemplar of which `runs` marks no run.
  // The CPU reference of OpenClDenseScorer::coarseSsd.
  std::vector<std::vector<float>> coarseSsd(const CoarseTerms& terms,
    CoarseImage image,
    const std::vector<std::vector<std::uint8_t>>* runs = nullptr) const;
  // Every offset of every oriented exemplar (overlap and landform terms).
  std::vector<std::vector<float>> coarseCosts(const CoarseQuery& query) const;
  // What refine() needs, exactly, for far less work: the query.bound SSD (a
  // quarter of the terms) everywhere; the full SSD at its best headSize()
  // offsets of each oriented exemplar, whose worst is a threshold; then the full
  // SSD only in runs of offsets whose bound is under that threshold. Every
  // offset among the headSize() best of its oriented exemplar keeps its exact
  // cost; others may be +inf. `ssd` is coarseSsd or the OpenCL one.
  using CoarseSsdFunction = std::function<std::vector<std::vector<float>>(const CoarseTerms&,
    CoarseImage,
    const std::vector<std::vector<std::uint8_t>>*)>;
  //
  // Given what refine() will be asked (`request`), it also prunes across
  // oriented exemplars: only offsets that could still be among refine()'s
  // seeds are scored, so refine(query, costs, k, exemplars) is the same as on
  // the full costs, while an oriented exemplar's own head may be lost (and its
  // costs empty). With many exemplars most of them have no offset good enough.
  struct RefineRequest
  {
    std::size_t k = 0;
    const std::vector<int>* exemplars = nullptr; // as refine()'s
  };
  std::vector<std::vector<float>> prunedCoarseCosts(const CoarseQuery& query,
    const CoarseSsdFunction& ssd,
    const RefineRequest* request = nullptr) const;
  // Coarse offsets per oriented exemplar that refine() looks at.
  std::size_t headSize() const;
  // Seeds refine() refines when asked for the k best.
  std::size_t seedCount(std::size_t k) const;
  // An offset whose full coarse cost is known before the full pass.
  struct ScoredOffset
  {
    float cost;
    std::size_t oriented;
    int cx, cy;
  };
  // Full-resolution refinement around the best coarse offsets; the k best.
  std::vector<DenseMatch> refine(const DenseQuery& query,
    const std::vector<std::vector<float>>& coarse,
    std::size_t k,
    const std::vector<int>* exemplars = nullptr) const; // only these exemplars, when given
  // coarseCosts + refine on the CPU.
  std::vector<DenseMatch> search(const DenseQuery& query, std::size_t k) const;
  // Every full-resolution offset (the reference the fast search is tested
  // against): the best offset of each row of each variant, the k best of those.
  std::vector<DenseMatch> bruteForce(const DenseQuery& query, std::size_t k) const;

private:
  // Exemplar `ex` (number e, low-passed as `smooth`) turned as variant v, with
  // its images and validity for the search.
  Oriented orient(const Heightfield& ex, const Heightfield& smooth, int e, int v) const;
  // The full cost of each oriented exemplar's `head` best offsets by `bound`,
  // added to `known` (an offset already there keeps its cost). Where `head` is
  // headSize() and there are that many, the worst of them lowers the
  // exemplar's threshold `local`: its whole head costs no more.
  void scoreHeads(const CoarseTerms& terms,
    const std::vector<std::vector<float>>& bound,
    std::size_t head,
    std::vector<float>& local,
    std::vector<std::vector<ScoredOffset>>& known) const;
  // The least cost under which refine() is sure to find `needed` seeds, from
  // the offsets whose full costs are `known` (+inf if they cannot tell).
  float seedThreshold(const std::vector<std::vector<ScoredOffset>>& known,
    std::size_t needed) const;
  // Mean squared difference over the known cells (listed as cell index and
  // height) at offsets (x .. x + kRowLanes - 1, y .. y + rows - 1), over
  // heightScale^2: out[r * kRowLanes + l] for offset (x + l, y + r).
  void overlapRows(const std::vector<int>& cells,
    const std::vector<float>& heights,
    std::size_t o,
    int x,
    int y,
    int rows,
    float* out) const;
  // The landform samples as offsets into an oriented exemplar's rows, and
  // their target heights and weights (samples of zero weight left out).
  struct LandformCells
  {
    std::vector<int> offset;
    std::vector<double> height, weight;
  };
  LandformCells landformCells(const DenseQuery& query, int stride) const;
  // Sum of weight * misfit^2 at the landform samples at offset (x, y), m^2.
  double landformMisfit(const LandformCells& cells, std::size_t o, int x, int y) const;
  // overlapWeight * overlap + landformWeight * landform (both over heightScale^2).
  float combined(float overlap, double landformSquares) const;
  DenseMatch describe(const DenseQuery& query,
    std::size_t o,
    int x,
    int y,
    float overlap,
    double landformSquares,
    double landformWeight) const;

  void stackLandform();

  DenseOptions options_;
  int landformRow_ = 0; // where the landform block means start in coarse, pairs and quads
  double heightScale_ = 1.0;
  std::vector<Oriented> oriented_;
  std::vector<NoiseVariance> noise_; // per exemplar
  std::vector<std::array<int, 2>> exemplarSize_;
};

} // namespace tsynth
