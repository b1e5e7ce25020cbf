#include "DenseSearch.h"

#include "../Core/Error.h"
#include "../Core/Grid.h"
#include "Vectorise.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>

namespace tsynth
{
namespace
{

constexpr float kInf = std::numeric_limits<float>::infinity();
// The coarse pass's landform samples: every kCoarseLandformStep-th of each row
// and column of the kLandformSide x kLandformSide grid.
constexpr int kCoarseLandformStep = 2;
constexpr int kCoarseLandformSide = (kLandformSide + kCoarseLandformStep - 1) / kCoarseLandformStep;
constexpr int kCoarseLandformSamples = kCoarseLandformSide * kCoarseLandformSide;

// valid[y * (w - side + 1) + x] = 1 when the side x side window at (x, y) has
// no invalid cell, from a summed-area table of invalid cells.
std::vector<std::uint8_t> windowValidity(int w,
  int h,
  int side,
  const std::vector<std::uint8_t>& cellValid)
{
  // Counts of invalid cells up to the whole grid: 64-bit, since a grid may hold more than
  // 2^31 cells.
  Grid<std::int64_t> sat(w + 1, h + 1, 0);
  for (int j = 0; j < h; ++j)
  {
    std::int64_t row = 0;
    for (int i = 0; i < w; ++i)
    {
      row += cellValid[rowMajor(i, j, w)] != 0 ? 0 : 1;
      sat.at(i + 1, j + 1) = sat.at(i + 1, j) + row;
    }
  }
  const int nx = std::max(0, w - side + 1);
  const int ny = std::max(0, h - side + 1);
  std::vector<std::uint8_t> valid(cellCount(nx, ny), 0);
  for (int y = 0; y < ny; ++y)
  {
    for (int x = 0; x < nx; ++x)
    {
      const std::int64_t bad =
        sat.at(x + side, y + side) - sat.at(x, y + side) - sat.at(x + side, y) + sat.at(x, y);
      valid[rowMajor(x, y, nx)] = bad == 0 ? 1 : 0;
    }
  }
  return valid;
}

// The oriented exemplar with kRowLanes invalid columns added on the right, so
// that a run of neighbouring offsets can always be read in one piece.
Heightfield padRight(const Heightfield& in, int columns)
{
  Heightfield out(in.width + columns, in.height, std::numeric_limits<float>::quiet_NaN());
  out.cellX = in.cellX;
  out.cellY = in.cellY;
  out.cellSizeKnown = in.cellSizeKnown;
  out.valid.assign(out.size(), 0);
  for (int j = 0; j < in.height; ++j)
  {
    for (int i = 0; i < in.width; ++i)
    {
      if (in.isValid(i, j))
      {
        out.at(i, j) = in.at(i, j);
        out.valid[out.index(i, j)] = 1;
      }
    }
  }
  return out;
}

// Candidates gathered under the bar before they are cut back to `count`: the
// cut (nth_element) is linear in what was gathered, so a few times `count`
// spreads its cost over many admissions, where a heap paid a logarithmic
// re-ordering for each one (the offsets' costs often fall along a row, and
// then most of them get in).
constexpr std::size_t kSelectionBuffer = 4;

// Indices of the `count` smallest finite costs, by (cost, index), in that order.
std::vector<std::size_t> smallestOffsets(const std::vector<float>& costs, std::size_t count)
{
  if (count == 0)
  {
    return {};
  }
  auto before = [&](std::size_t a, std::size_t b)
  { return costs[a] < costs[b] || (costs[a] == costs[b] && a < b); };
  std::vector<std::size_t> kept;
  kept.reserve(kSelectionBuffer * count);
  // Offsets come in increasing order, so one that ties with the worst kept is
  // later, hence worse: only a strictly smaller cost gets in once `count` are
  // kept. Runs of 16 with none below the bar are skipped in one vector test.
  float bar = kInf;
  auto cut = [&]
  {
    std::nth_element(
      kept.begin(), kept.begin() + static_cast<std::ptrdiff_t>(count - 1), kept.end(), before);
    kept.resize(count);
    bar = costs[kept.back()];
  };
  const std::size_t n = costs.size();
  std::size_t i = 0;
  while (i < n)
  {
    if (i + 16 <= n)
    {
      bool any = false;
      for (std::size_t l = 0; l < 16; ++l)
      {
        any |= costs[i + l] < bar;
      }
      if (!any)
      {
        i += 16;
        continue;
      }
    }
    const std::size_t end = std::min(n, i + 16);
    for (; i < end; ++i)
    {
      if (!(costs[i] < bar))
      {
        continue;
      }
      kept.push_back(i);
      if (kept.size() == kSelectionBuffer * count)
      {
        cut();
      }
    }
  }
  if (kept.size() > count)
  {
    cut();
  }
  std::sort(kept.begin(), kept.end(), before);
  return kept;
}

// The same sum at one offset (a lane of ssdRuns, in the same order).
float offsetSsd(const CoarseTerms& q, const std::vector<float>& pixels, int stride, int x, int y)
{
  float acc = 0.0f;
  for (std::size_t e = 0; e < q.size(); ++e)
  {
    const float d = q.heights[e] - pixels[rowMajor(x + q.column[e], y + q.row[e], stride)];
    acc += q.weights[e] * d * d;
  }
  return acc;
}

// Runs of 16 offsets whose coarse SSD is summed at once.
constexpr int kRunsAtOnce = 4;
// 16 floats as one value of GCC's vector extension.
using Lanes16 = float __attribute__((vector_size(16 * sizeof(float))));

// Coarse weighted SSD of the terms at 16 neighbouring offsets (x0s[n] .. x0s[n]
// + 15, y) for each of Runs runs, each run like one work-item of the OpenCL
// kernel (DenseSsd.cl), in the same order. The runs' sums are independent, so
// their additions overlap in the pipeline instead of waiting on one another.
template<int Runs>
inline __attribute__((always_inline)) void ssdRuns(const CoarseTerms& q,
  const std::vector<float>& pixels,
  int stride,
  const int* x0s,
  int y,
  float* out)
{
  // Local accumulators, one vector of 16 lanes per run (GCC's vector
  // extension: one AVX-512 register, two AVX2 ones, four SSE ones; the lanes
  // are computed as the scalar expression would be). Plain arrays of 16 x Runs
  // floats were left scalar by the vectoriser.
  Lanes16 acc[Runs] = {};
  int x0[Runs];
  std::copy(x0s, x0s + Runs, x0);
  for (std::size_t e = 0; e < q.size(); ++e)
  {
    const float* row = pixels.data() + rowMajor(q.column[e], y + q.row[e], stride);
    const float h = q.heights[e];
    const float m = q.weights[e];
    for (int n = 0; n < Runs; ++n)
    {
      Lanes16 cells;
      std::memcpy(&cells, row + x0[n], sizeof cells);
      const Lanes16 d = h - cells;
      acc[n] += m * d * d;
    }
  }
  std::memcpy(out, acc, sizeof acc);
}

TSYNTH_VECTOR_CLONES void ssdRuns4(const CoarseTerms& q,
  const std::vector<float>& pixels,
  int stride,
  const int* x0s,
  int y,
  float* out)
{
  ssdRuns<kRunsAtOnce>(q, pixels, stride, x0s, y, out);
}

TSYNTH_VECTOR_CLONES void ssdRuns2(const CoarseTerms& q,
  const std::vector<float>& pixels,
  int stride,
  const int* x0s,
  int y,
  float* out)
{
  ssdRuns<2>(q, pixels, stride, x0s, y, out);
}

TSYNTH_VECTOR_CLONES void ssdRuns1(const CoarseTerms& q,
  const std::vector<float>& pixels,
  int stride,
  const int* x0s,
  int y,
  float* out)
{
  ssdRuns<1>(q, pixels, stride, x0s, y, out);
}

// ssdRuns over any number of runs, kRunsAtOnce at a time where there are as many.
void ssdOfRuns(const CoarseTerms& q,
  const std::vector<float>& pixels,
  int stride,
  const std::vector<int>& x0s,
  int y,
  float* out)
{
  const int count = static_cast<int>(x0s.size());
  for (int done = 0; done < count;)
  {
    const int left = count - done;
    const int step = left >= kRunsAtOnce ? kRunsAtOnce : left >= 2 ? 2 : 1;
    float* sums = out + static_cast<std::size_t>(done) * 16;
    if (step == kRunsAtOnce)
    {
      ssdRuns4(q, pixels, stride, &x0s[static_cast<std::size_t>(done)], y, sums);
    }
    else if (step == 2)
    {
      ssdRuns2(q, pixels, stride, &x0s[static_cast<std::size_t>(done)], y, sums);
    }
    else
    {
      ssdRuns1(q, pixels, stride, &x0s[static_cast<std::size_t>(done)], y, sums);
    }
    done += step;
  }
}

// Means of f x f blocks of an image, rows of `stride` values (0 where a block
// has an invalid cell); `valid` (if given) receives 1 per whole block.
std::vector<float> blockMeans(const Heightfield& image,
  int f,
  int blocksX,
  int blocksY,
  int stride,
  std::vector<std::uint8_t>* valid)
{
  std::vector<float> means(cellCount(stride, blocksY), 0.0f);
  if (valid != nullptr)
  {
    valid->assign(cellCount(blocksX, blocksY), 0);
  }
  for (int b = 0; b < blocksY; ++b)
  {
    for (int a = 0; a < blocksX; ++a)
    {
      double s = 0.0;
      bool ok = true;
      for (int j = b * f; j < (b + 1) * f && ok; ++j)
      {
        for (int i = a * f; i < (a + 1) * f; ++i)
        {
          if (!image.isValid(i, j))
          {
            ok = false;
            break;
          }
          s += image.at(i, j);
        }
      }
      if (ok)
      {
        means[rowMajor(a, b, stride)] = static_cast<float>(s / (f * f));
        if (valid != nullptr)
        {
          (*valid)[rowMajor(a, b, blocksX)] = 1;
        }
      }
    }
  }
  return means;
}

bool better(const DenseMatch& a, const DenseMatch& b)
{
  if (a.cost != b.cost)
  {
    return a.cost < b.cost;
  }
  if (a.exemplar != b.exemplar)
  {
    return a.exemplar < b.exemplar;
  }
  if (a.variant != b.variant)
  {
    return a.variant < b.variant;
  }
  return a.y != b.y ? a.y < b.y : a.x < b.x;
}

} // namespace

DenseMatcher::DenseMatcher(const std::vector<const Heightfield*>& exemplars, const DenseOptions& o)
  : options_(o)
{
  const int P = o.patchSize;
  const int f = std::max(1, o.coarseFactor);
  if (P % f != 0)
  {
    throw Error("The patch size (" + std::to_string(P) +
      ") must be a multiple of the coarse factor (" + std::to_string(f) + ").");
  }
  double sum = 0.0;
  double square = 0.0;
  double count = 0.0;
  std::vector<std::pair<int, int>> wanted; // (exemplar, variant) of each oriented exemplar
  for (std::size_t e = 0; e < exemplars.size(); ++e)
  {
    const Heightfield& ex = *exemplars[e];
    if (ex.width < P || ex.height < P)
    {
      throw Error("Exemplar " + std::to_string(e) + " is " + std::to_string(ex.width) + " x " +
        std::to_string(ex.height) + " cells, smaller than one patch (" + std::to_string(P) + ").");
    }
    for (std::size_t k = 0; k < ex.size(); ++k)
    {
      if (ex.isValid(k))
      {
        sum += ex.z[k];
        square += static_cast<double>(ex.z[k]) * ex.z[k];
        count += 1.0;
      }
    }
    exemplarSize_.push_back({ ex.width, ex.height });
    for (int v = 0; v < kVariantCount; ++v)
    {
      if (o.variants[static_cast<std::size_t>(v)])
      {
        wanted.push_back({ static_cast<int>(e), v });
      }
    }
  }
  // Each exemplar's tables, then each oriented exemplar, on every core: each
  // is computed alone from its inputs, so the thread count changes nothing.
  noise_.resize(exemplars.size());
  std::vector<Heightfield> smooth(exemplars.size());
  const long exemplarCount = static_cast<long>(exemplars.size());
  // (One exemplar keeps the cores for its smoothing's own loops.)
#pragma omp parallel for schedule(dynamic) if (exemplarCount > 1)
  for (long e = 0; e < exemplarCount; ++e)
  {
    const std::size_t i = static_cast<std::size_t>(e);
    noise_[i] = NoiseVariance(*exemplars[i]);
    smooth[i] = landformImage(*exemplars[i], P);
  }
  oriented_.resize(wanted.size());
  const long orientedCount = static_cast<long>(wanted.size());
#pragma omp parallel for schedule(dynamic)
  for (long n = 0; n < orientedCount; ++n)
  {
    const auto [e, v] = wanted[static_cast<std::size_t>(n)];
    oriented_[static_cast<std::size_t>(n)] =
      orient(*exemplars[static_cast<std::size_t>(e)], smooth[static_cast<std::size_t>(e)], e, v);
  }
  stackLandform();
  const double mean = count > 0 ? sum / count : 0.0;
  heightScale_ =
    std::max(1e-6, std::sqrt(std::max(0.0, square / std::max(1.0, count) - mean * mean)));
}

DenseMatcher::Oriented DenseMatcher::orient(const Heightfield& ex,
  const Heightfield& smooth,
  int e,
  int v) const
{
  const int P = options_.patchSize;
  const int f = std::max(1, options_.coarseFactor);
  Oriented r;
  r.exemplar = e;
  r.variant = v;
  r.full = padRight(orientExemplar(ex, variant(v), &r.centreX, &r.centreY), kRowLanes);
  std::vector<std::uint8_t> cellValid(r.full.size());
  for (std::size_t k = 0; k < cellValid.size(); ++k)
  {
    cellValid[k] = r.full.isValid(k) ? 1 : 0;
  }
  r.fullValid = windowValidity(r.full.width, r.full.height, P, cellValid);
  r.coarseWidth = r.full.width / f;
  r.coarseHeight = r.full.height / f;
  r.coarseStride = r.coarseWidth + 16;
  std::vector<std::uint8_t> blockValid;
  r.coarse = blockMeans(r.full, f, r.coarseWidth, r.coarseHeight, r.coarseStride, &blockValid);
  r.landform = padRight(orientExemplar(smooth, variant(v)), kRowLanes);
  r.landformBlocks =
    blockMeans(r.landform, f, r.coarseWidth, r.coarseHeight, r.coarseStride, nullptr);
  // Its mask was read by the block means only: the landform samples are read
  // inside windows that fullValid already says are valid. (28 MB for five
  // 648^2 exemplars in ten variants.)
  std::vector<std::uint8_t>().swap(r.landform.valid);
  r.pairs.assign(r.coarse.size(), 0.0f);
  for (int b = 0; b + 1 < r.coarseHeight; ++b)
  {
    for (int a = 0; a + 1 < r.coarseWidth; ++a)
    {
      const std::size_t k = rowMajor(a, b, r.coarseStride);
      const std::size_t up = rowMajor(a, b + 1, r.coarseStride);
      r.pairs[k] = 0.25f * (r.coarse[k] + r.coarse[k + 1] + r.coarse[up] + r.coarse[up + 1]);
    }
  }
  r.quads.assign(r.coarse.size(), 0.0f);
  for (int b = 0; b + 3 < r.coarseHeight; ++b)
  {
    for (int a = 0; a + 3 < r.coarseWidth; ++a)
    {
      const std::size_t k = rowMajor(a, b, r.coarseStride);
      const std::size_t down = rowMajor(a, b + 2, r.coarseStride);
      r.quads[k] = 0.25f * (r.pairs[k] + r.pairs[k + 2] + r.pairs[down] + r.pairs[down + 2]);
    }
  }
  r.coarseValid = windowValidity(r.coarseWidth, r.coarseHeight, P / f, blockValid);
  r.offsetsX = std::max(0, r.coarseWidth - P / f + 1);
  r.offsetsY = std::max(0, r.coarseHeight - P / f + 1);
  const int groups = (r.offsetsX + 15) / 16;
  r.groupValid.assign(cellCount(groups, r.offsetsY), 0);
  for (int y = 0; y < r.offsetsY; ++y)
  {
    for (int x = 0; x < r.offsetsX; ++x)
    {
      if (r.coarseValid[rowMajor(x, y, r.offsetsX)] != 0)
      {
        r.groupValid[rowMajor(x / 16, y, groups)] = 1;
      }
    }
  }
  return r;
}

void DenseMatcher::stackLandform()
{
  // The landform's block means go below the blocks (and the pairs and quads) of
  // each oriented exemplar, from a row shared by all, so landform terms are
  // ordinary terms kLandformRow rows down: one pass sums both, the pruning
  // bound included, with no pass of its own.
  landformRow_ = 0;
  for (const Oriented& r : oriented_)
  {
    landformRow_ = std::max(landformRow_, r.coarseHeight);
  }
  for (Oriented& r : oriented_)
  {
    const std::size_t below = cellCount(landformRow_, r.coarseStride);
    for (std::vector<float>* image : { &r.coarse, &r.pairs, &r.quads })
    {
      image->resize(below, 0.0f);
      image->insert(image->end(), r.landformBlocks.begin(), r.landformBlocks.end());
    }
  }
}

void CoarseTerms::add(int r, int c, float h, float w)
{
  row.push_back(r);
  column.push_back(c);
  heights.push_back(h);
  weights.push_back(w);
}

CoarseQuery DenseMatcher::coarseQuery(const DenseQuery& q) const
{
  const int P = options_.patchSize;
  const int f = std::max(1, options_.coarseFactor);
  CoarseQuery c;
  c.side = P / f;
  c.heights.assign(cellCount(c.side, c.side), 0.0f);
  c.weights.assign(cellCount(c.side, c.side), 0.0f);
  for (int b = 0; b < c.side; ++b)
  {
    for (int a = 0; a < c.side; ++a)
    {
      double s = 0.0;
      double n = 0.0;
      for (int j = b * f; j < (b + 1) * f; ++j)
      {
        for (int i = a * f; i < (a + 1) * f; ++i)
        {
          const std::size_t k = rowMajor(i, j, P);
          if (q.known[k] != 0)
          {
            s += q.heights[k];
            n += 1.0;
          }
        }
      }
      const std::size_t k = rowMajor(a, b, c.side);
      c.heights[k] = n > 0 ? static_cast<float>(s / n) : 0.0f;
      c.weights[k] = static_cast<float>(n / (f * f));
      if (n > 0)
      {
        c.terms.add(b, a, c.heights[k], c.weights[k]);
      }
    }
  }
  for (int b = 0; b + 1 < c.side; b += 2)
  {
    for (int a = 0; a + 1 < c.side; a += 2)
    {
      const std::size_t k = rowMajor(a, b, c.side);
      const std::size_t up = rowMajor(a, b + 1, c.side);
      const std::size_t group[4] = { k, k + 1, up, up + 1 };
      const float w = c.weights[k];
      if (w > 0.0f &&
        std::all_of(group, group + 4, [&](std::size_t g) { return c.weights[g] == w; }))
      {
        const float mean = 0.25f *
          (c.heights[group[0]] + c.heights[group[1]] + c.heights[group[2]] + c.heights[group[3]]);
        c.bound.add(b, a, mean, 4.0f * w);
      }
    }
  }
  for (int b = 0; b + 3 < c.side; b += 4)
  {
    for (int a = 0; a + 3 < c.side; a += 4)
    {
      const float w = c.weights[rowMajor(a, b, c.side)];
      double sum = 0.0;
      bool equal = w > 0.0f;
      for (int j = b; j < b + 4; ++j)
      {
        for (int i = a; i < a + 4; ++i)
        {
          const std::size_t k = rowMajor(i, j, c.side);
          equal = equal && c.weights[k] == w;
          sum += c.heights[k];
        }
      }
      if (equal)
      {
        c.quadBound.add(b, a, static_cast<float>(sum / 16.0), 16.0f * w);
      }
    }
  }
  // Landform terms weighted so that, as in refine(), they count against the
  // overlap as landformWeight against overlapWeight (the overlap's block sums
  // approximate known / f^2 times its mean; with nothing known any scale will do).
  const double known =
    static_cast<double>(std::count(q.known.begin(), q.known.end(), std::uint8_t{ 1 }));
  // The coarse pass reads every other sample (3 x 3 of the 5 x 5, each
  // standing for its share of all 25): the low-passed terrain changes little
  // between neighbouring samples, refine() reads them all, and the coarse pass
  // reads these at every offset of every exemplar.
  const double scale = options_.landformWeight / options_.overlapWeight *
    (known > 0.0 ? known : static_cast<double>(P) * P) /
    (static_cast<double>(f) * f * kCoarseLandformSamples);
  for (int b = 0; b < kLandformSide; b += kCoarseLandformStep)
  {
    for (int a = 0; a < kLandformSide; a += kCoarseLandformStep)
    {
      const std::size_t k = rowMajor(a, b, kLandformSide);
      const float w = q.landform.weights[k];
      if (w > 0.0f)
      {
        const int row = landformRow_ + landformCell(b, P, f) / f;
        const int column = landformCell(a, P, f) / f;
        c.terms.add(row, column, q.landform.heights[k], static_cast<float>(w * scale));
        c.landform.add(row, column, q.landform.heights[k], static_cast<float>(w * scale));
      }
    }
  }
  // The bound reads the same landform terms (from below the pairs): it stays a
  // lower bound of the full sum. Only with overlap terms to prune by.
  for (CoarseTerms* bound : { &c.bound, &c.quadBound })
  {
    const bool overlap = !bound->empty();
    for (std::size_t e = 0; e < c.landform.size() && overlap; ++e)
    {
      bound->add(
        c.landform.row[e], c.landform.column[e], c.landform.heights[e], c.landform.weights[e]);
    }
  }
  return c;
}

std::vector<std::vector<float>> DenseMatcher::coarseSsd(const CoarseTerms& q,
  CoarseImage image,
  const std::vector<std::vector<std::uint8_t>>* runs) const
{
  std::vector<std::vector<float>> out(oriented_.size());
  // One task per row of offsets of every oriented exemplar, in a single parallel
  // region (a region per variant stalls when a core is busy elsewhere).
  std::vector<std::pair<std::size_t, int>> tasks;
  for (std::size_t o = 0; o < oriented_.size(); ++o)
  {
    const Oriented& r = oriented_[o];
    if (runs != nullptr &&
      std::none_of((*runs)[o].begin(), (*runs)[o].end(), [](std::uint8_t m) { return m != 0; }))
    {
      continue; // nothing asked of it: no costs at all
    }
    out[o].assign(cellCount(r.offsetsX, r.offsetsY), kInf);
    for (int y = 0; y < r.offsetsY; ++y)
    {
      tasks.push_back({ o, y });
    }
  }
  const long taskCount = static_cast<long>(tasks.size());
#pragma omp parallel for schedule(dynamic, 16)
  for (long t = 0; t < taskCount; ++t)
  {
    const auto [o, y] = tasks[static_cast<std::size_t>(t)];
    const Oriented& r = oriented_[o];
    const std::vector<float>& pixels =
      image == CoarseImage::Blocks ? r.coarse : (image == CoarseImage::Pairs ? r.pairs : r.quads);
    std::vector<float>& costs = out[o];
    // Sixteen neighbouring offsets at a time, like the OpenCL kernel (DenseSsd.cl),
    // skipping runs of offsets that are all invalid or not asked for.
    const int groups = (r.offsetsX + 15) / 16;
    std::vector<int> x0s;
    for (int g = 0; g < groups; ++g)
    {
      const std::size_t run = rowMajor(g, y, groups);
      if (r.groupValid[run] != 0 && (runs == nullptr || (*runs)[o][run] != 0))
      {
        x0s.push_back(16 * g);
      }
    }
    std::vector<float> acc(x0s.size() * 16);
    ssdOfRuns(q, pixels, r.coarseStride, x0s, y, acc.data());
    for (std::size_t n = 0; n < x0s.size(); ++n)
    {
      const int x0 = x0s[n];
      for (int l = 0; l < 16 && x0 + l < r.offsetsX; ++l)
      {
        const std::size_t k = rowMajor(x0 + l, y, r.offsetsX);
        costs[k] = r.coarseValid[k] != 0 ? acc[rowMajor(l, n, 16)] : kInf;
      }
    }
  }
  return out;
}

std::vector<std::vector<float>> DenseMatcher::coarseCosts(const CoarseQuery& q) const
{
  return coarseSsd(q.terms, CoarseImage::Blocks);
}

std::size_t DenseMatcher::headSize() const
{
  return static_cast<std::size_t>(16 * std::max(1, options_.refinePerVariant));
}

namespace
{

// bestCoarseOffsets drops an offset within one block of a better chosen one.
// Offsets this far apart (or more) can never be dropped for the same chosen
// offset, so each of them stands for a seed of its own.
constexpr int kSeparateSeedBlocks = 3;

// The least cost T at which refine() is sure to have `needed` seeds costing at
// most T, from offsets whose full costs are known (+inf if they do not show
// it). Per oriented exemplar, refine() picks its seeds greedily from the head
// of its costs. Every offset of cost <= T in that head is a seed or lies next
// to a better seed, so the seeds <= T number at least as many as there are
// known offsets <= T kSeparateSeedBlocks apart, up to refinePerVariant. (If
// more than the head cost <= T, the head alone holds head / 9 >= that many.)
float leastSureThreshold(std::vector<DenseMatcher::ScoredOffset> known,
  std::size_t orientedCount,
  std::size_t perOriented,
  std::size_t needed)
{
  std::sort(known.begin(),
    known.end(),
    [](const DenseMatcher::ScoredOffset& a, const DenseMatcher::ScoredOffset& b) {
      return std::tie(a.cost, a.oriented, a.cy, a.cx) < std::tie(b.cost, b.oriented, b.cy, b.cx);
    });
  std::vector<std::vector<DenseMatcher::ScoredOffset>> apart(orientedCount);
  std::size_t seeds = 0;
  for (const DenseMatcher::ScoredOffset& s : known)
  {
    std::vector<DenseMatcher::ScoredOffset>& mine = apart[s.oriented];
    const bool separate = std::none_of(mine.begin(),
      mine.end(),
      [&](const DenseMatcher::ScoredOffset& m)
      { return std::max(std::abs(m.cx - s.cx), std::abs(m.cy - s.cy)) < kSeparateSeedBlocks; });
    if (std::isfinite(s.cost) && mine.size() < perOriented && separate)
    {
      mine.push_back(s);
      if (++seeds >= needed)
      {
        return s.cost;
      }
    }
  }
  return kInf;
}

// `runs` less those of 16 offsets whose bounds are all above `threshold`.
std::vector<std::uint8_t> runsUnder(const std::vector<float>& bound,
  std::vector<std::uint8_t> runs,
  const DenseMatcher::Oriented& r,
  float threshold)
{
  const std::size_t nx = static_cast<std::size_t>(r.offsetsX);
  const std::size_t groups = (nx + 15) / 16;
  for (std::size_t y = 0; y < static_cast<std::size_t>(r.offsetsY); ++y)
  {
    for (std::size_t g = 0; g < groups; ++g)
    {
      const float* b = bound.data() + y * nx + 16 * g;
      const std::size_t lanes = std::min<std::size_t>(16, nx - 16 * g);
      bool any = false;
      for (std::size_t l = 0; l < lanes; ++l)
      {
        any |= b[l] <= threshold;
      }
      runs[y * groups + g] &= any ? 1 : 0;
    }
  }
  return runs;
}

// The quad bound's best offsets scored in full per oriented exemplar, as a
// share of headSize(): enough for refinePerVariant seeds kSeparateSeedBlocks
// apart where the land matches, few enough to cost little beside the pass.
constexpr std::size_t kQuadHeadShare = 4;

// How many times the seeds refine() takes the oriented exemplars asked must be
// able to give before the quad pass runs (prunedCoarseCosts).
constexpr std::size_t kQuadPassSurplus = 2;

// Bounds and full costs differ by float round-off: a threshold on full costs
// is widened by this share before it is compared with bounds.
constexpr float kBoundRoundOff = 1e-3f;

float widened(float threshold)
{
  return threshold * (1.0f + kBoundRoundOff) + 1e-30f;
}

} // namespace

std::size_t DenseMatcher::seedCount(std::size_t k) const
{
  return std::max(k, static_cast<std::size_t>(options_.refineTotal));
}

std::vector<std::vector<float>> DenseMatcher::prunedCoarseCosts(const CoarseQuery& q,
  const CoarseSsdFunction& ssd,
  const RefineRequest* request) const
{
  // Landform terms are among q.terms and q.bound (stackLandform).
  const std::size_t overlapTerms = q.terms.size() - q.landform.size();
  if (q.bound.empty() || overlapTerms == 0)
  {
    return ssd(q.terms, CoarseImage::Blocks, nullptr);
  }
  // Oriented exemplars refine() will not look at are not scored at all.
  const std::vector<int>* only = request != nullptr ? request->exemplars : nullptr;
  std::vector<std::vector<std::uint8_t>> runs(oriented_.size());
  for (std::size_t o = 0; o < oriented_.size(); ++o)
  {
    const bool asked = only == nullptr ||
      std::find(only->begin(), only->end(), oriented_[o].exemplar) != only->end();
    runs[o] = asked ? oriented_[o].groupValid
                    : std::vector<std::uint8_t>(oriented_[o].groupValid.size(), 0);
  }
  // Across exemplars, the looser and cheaper quad bound first: the full cost
  // of a few of its best offsets per oriented exemplar is enough to find a
  // threshold for all (seedThreshold). Then the pair bound where that leaves
  // room, with the full cost of its head: a threshold per oriented exemplar
  // too, and a lower one across. Then the full sum where both leave room.
  std::vector<float> local(oriented_.size(), kInf);
  std::vector<std::vector<ScoredOffset>> known(oriented_.size());
  struct Level
  {
    const CoarseTerms* terms;
    CoarseImage image;
    std::size_t scored; // offsets per oriented exemplar that get their full cost
  };
  std::vector<Level> levels;
  // Only worth it where most oriented exemplars can be left out: where they
  // could give kQuadPassSurplus times the seeds refine() takes (each gives at
  // most refinePerVariant). With fewer, most of them keep seeds, the threshold
  // across is near the worst of theirs, and the quad pass is extra work: one
  // exemplar in 10 variants took 7% longer to fill with it.
  const std::size_t asked = static_cast<std::size_t>(std::count_if(runs.begin(),
    runs.end(),
    [](const std::vector<std::uint8_t>& r)
    { return std::any_of(r.begin(), r.end(), [](std::uint8_t m) { return m != 0; }); }));
  const std::size_t perOriented = static_cast<std::size_t>(std::max(1, options_.refinePerVariant));
  if (request != nullptr && asked * perOriented >= kQuadPassSurplus * seedCount(request->k))
  {
    levels.push_back({ &q.quadBound, CoarseImage::Quads, headSize() / kQuadHeadShare });
  }
  levels.push_back({ &q.bound, CoarseImage::Pairs, headSize() });
  for (const Level& level : levels)
  {
    if (level.terms->size() > q.landform.size())
    {
      const std::vector<std::vector<float>> bound = ssd(*level.terms, level.image, &runs);
      scoreHeads(q.terms, bound, level.scored, local, known);
      const float across = request != nullptr ? seedThreshold(known, seedCount(request->k)) : kInf;
      const long orientedCount = static_cast<long>(oriented_.size());
#pragma omp parallel for schedule(dynamic)
      for (long n = 0; n < orientedCount; ++n)
      {
        const std::size_t o = static_cast<std::size_t>(n);
        const float threshold = std::min(local[o], across);
        if (!bound[o].empty() && threshold < kInf)
        {
          runs[o] = runsUnder(bound[o], runs[o], oriented_[o], widened(threshold));
        }
      }
    }
  }
  return ssd(q.terms, CoarseImage::Blocks, &runs);
}

void DenseMatcher::scoreHeads(const CoarseTerms& terms,
  const std::vector<std::vector<float>>& bound,
  std::size_t head,
  std::vector<float>& local,
  std::vector<std::vector<ScoredOffset>>& known) const
{
  const long orientedCount = static_cast<long>(oriented_.size());
#pragma omp parallel for schedule(dynamic)
  for (long n = 0; n < orientedCount; ++n)
  {
    const std::size_t o = static_cast<std::size_t>(n);
    const Oriented& r = oriented_[o];
    const std::size_t nx = static_cast<std::size_t>(r.offsetsX);
    const std::vector<std::size_t> best = smallestOffsets(bound[o], head);
    const std::size_t before = known[o].size();
    float worst = 0.0f;
    for (std::size_t idx : best)
    {
      const int x = static_cast<int>(idx % nx);
      const int y = static_cast<int>(idx / nx);
      // An offset a looser bound already had scored keeps its cost.
      const auto end = known[o].begin() + static_cast<std::ptrdiff_t>(before);
      const auto seen = std::find_if(
        known[o].begin(), end, [&](const ScoredOffset& s) { return s.cx == x && s.cy == y; });
      const float cost =
        seen != end ? seen->cost : offsetSsd(terms, r.coarse, r.coarseStride, x, y);
      if (seen == end)
      {
        known[o].push_back({ cost, o, x, y });
      }
      worst = std::max(worst, cost);
    }
    // At least `head` offsets cost at most the worst of them, so the `head`
    // best all do, and their bounds are below it.
    if (head == headSize() && best.size() == head)
    {
      local[o] = std::min(local[o], worst);
    }
  }
}

float DenseMatcher::seedThreshold(const std::vector<std::vector<ScoredOffset>>& known,
  std::size_t needed) const
{
  std::vector<ScoredOffset> all;
  for (const std::vector<ScoredOffset>& k : known)
  {
    all.insert(all.end(), k.begin(), k.end());
  }
  return leastSureThreshold(std::move(all),
    oriented_.size(),
    static_cast<std::size_t>(std::max(1, options_.refinePerVariant)),
    needed);
}

namespace
{

// Rows the refinement's squared differences are summed for at once.
constexpr int kRowsAtOnce = 4;
// kRowLanes floats as one value of GCC's vector extension.
using LanesOfRow = float __attribute__((vector_size(kRowLanes * sizeof(float))));

// Sums of squared differences of the known cells (offsets `cells` from `base`,
// heights `heights`) at kRowLanes neighbouring offsets on each of Rows rows
// `stride` apart. Each lane sums its cells in order, as for one offset alone;
// the rows' sums are independent, so their additions overlap in the pipeline
// instead of waiting on one another (one row at a time, each addition waited
// for the last).
template<int Rows>
inline __attribute__((always_inline)) void squaredDifferenceRows(const float* base,
  std::ptrdiff_t stride,
  const std::vector<int>& cells,
  const std::vector<float>& heights,
  float* sums)
{
  LanesOfRow s[Rows] = {};
  for (std::size_t e = 0; e < cells.size(); ++e)
  {
    const float h = heights[e];
    for (int r = 0; r < Rows; ++r)
    {
      LanesOfRow cell;
      std::memcpy(&cell, base + r * stride + cells[e], sizeof cell);
      const LanesOfRow d = h - cell;
      s[r] += d * d;
    }
  }
  std::memcpy(sums, s, sizeof s);
}

TSYNTH_VECTOR_CLONES void squaredDifferenceRows4(const float* base,
  std::ptrdiff_t stride,
  const std::vector<int>& cells,
  const std::vector<float>& heights,
  float* sums)
{
  squaredDifferenceRows<kRowsAtOnce>(base, stride, cells, heights, sums);
}

TSYNTH_VECTOR_CLONES void squaredDifferenceRows2(const float* base,
  std::ptrdiff_t stride,
  const std::vector<int>& cells,
  const std::vector<float>& heights,
  float* sums)
{
  squaredDifferenceRows<2>(base, stride, cells, heights, sums);
}

TSYNTH_VECTOR_CLONES void squaredDifferenceRows1(const float* base,
  std::ptrdiff_t stride,
  const std::vector<int>& cells,
  const std::vector<float>& heights,
  float* sums)
{
  squaredDifferenceRows<1>(base, stride, cells, heights, sums);
}

} // namespace

void DenseMatcher::overlapRows(const std::vector<int>& cells,
  const std::vector<float>& heights,
  std::size_t o,
  int x,
  int y,
  int rows,
  float* out) const
{
  const Oriented& r = oriented_[o];
  const std::ptrdiff_t stride = r.full.width;
  for (int done = 0; done < rows;)
  {
    const float* base = r.full.z.data() + r.full.index(x, y + done);
    float* sums = out + static_cast<std::size_t>(done) * kRowLanes;
    const int left = rows - done;
    const int step = left >= kRowsAtOnce ? kRowsAtOnce : left >= 2 ? 2 : 1;
    if (step == kRowsAtOnce)
    {
      squaredDifferenceRows4(base, stride, cells, heights, sums);
    }
    else if (step == 2)
    {
      squaredDifferenceRows2(base, stride, cells, heights, sums);
    }
    else
    {
      squaredDifferenceRows1(base, stride, cells, heights, sums);
    }
    done += step;
  }
  for (int k = 0; k < rows * kRowLanes; ++k)
  {
    out[k] = cells.empty()
      ? 0.0f
      : static_cast<float>(out[k] / cells.size() / (heightScale_ * heightScale_));
  }
}

DenseMatcher::LandformCells DenseMatcher::landformCells(const DenseQuery& q, int stride) const
{
  const int P = options_.patchSize;
  const int f = std::max(1, options_.coarseFactor);
  LandformCells cells;
  for (int b = 0; b < kLandformSide; ++b)
  {
    for (int a = 0; a < kLandformSide; ++a)
    {
      const std::size_t k = rowMajor(a, b, kLandformSide);
      if (q.landform.weights[k] > 0.0f)
      {
        cells.offset.push_back(landformCell(b, P, f) * stride + landformCell(a, P, f));
        cells.height.push_back(q.landform.heights[k]);
        cells.weight.push_back(q.landform.weights[k]);
      }
    }
  }
  return cells;
}

double DenseMatcher::landformMisfit(const LandformCells& cells, std::size_t o, int x, int y) const
{
  const Oriented& r = oriented_[o];
  const float* base = r.landform.z.data() + r.landform.index(x, y);
  double sum = 0.0;
  for (std::size_t k = 0; k < cells.offset.size(); ++k)
  {
    const double e = cells.height[k] - base[cells.offset[k]];
    sum += cells.weight[k] * e * e;
  }
  return sum;
}

float DenseMatcher::combined(float overlap, double landformSquares) const
{
  return static_cast<float>(options_.overlapWeight * overlap +
    options_.landformWeight * landformSquares / (kLandformSamples * heightScale_ * heightScale_));
}

DenseMatch DenseMatcher::describe(const DenseQuery& q,
  std::size_t o,
  int x,
  int y,
  float overlap,
  double landformSquares,
  double landformWeight) const
{
  const Oriented& r = oriented_[o];
  const int P = options_.patchSize;
  DenseMatch match;
  match.exemplar = r.exemplar;
  match.variant = r.variant;
  match.x = x;
  match.y = y;
  // Window centre, back in the exemplar's own cells.
  const Variant v = variant(r.variant);
  double su = 0.0;
  double sv = 0.0;
  v.toSource(x + 0.5 * (P - 1) - r.centreX, y + 0.5 * (P - 1) - r.centreY, su, sv);
  const auto& size = exemplarSize_[static_cast<std::size_t>(r.exemplar)];
  match.centreX = 0.5 * (size[0] - 1) + su;
  match.centreY = 0.5 * (size[1] - 1) + sv;
  const double scale2 = heightScale_ * heightScale_;
  match.overlap = overlap;
  match.landform = static_cast<float>(landformSquares / (kLandformSamples * scale2));
  match.landformRms =
    landformWeight > 0.0 ? static_cast<float>(std::sqrt(landformSquares / landformWeight)) : 0.0f;
  const auto nv =
    noise_[static_cast<std::size_t>(r.exemplar)].window(match.centreX, match.centreY, P);
  match.roughness = static_cast<float>(roughnessMisfit(q.noise, nv));
  match.cost =
    static_cast<float>(combined(overlap, landformSquares) + options_.noiseWeight * match.roughness);
  return match;
}

namespace
{

// Known cells of a query as offsets into an image of the given row length.
void knownCells(const DenseQuery& q,
  int patch,
  int stride,
  std::vector<int>& cells,
  std::vector<float>& heights)
{
  cells.clear();
  heights.clear();
  for (int j = 0; j < patch; ++j)
  {
    for (int i = 0; i < patch; ++i)
    {
      const std::size_t k = rowMajor(i, j, patch);
      if (q.known[k] != 0)
      {
        cells.push_back(j * stride + i);
        heights.push_back(q.heights[k]);
      }
    }
  }
}

} // namespace

namespace
{

// A coarse offset chosen for refinement.
struct Seed
{
  float cost;
  std::size_t oriented;
  int cx, cy;
};

bool seedBefore(const Seed& a, const Seed& b)
{
  if (a.cost != b.cost)
  {
    return a.cost < b.cost;
  }
  if (a.oriented != b.oriented)
  {
    return a.oriented < b.oriented;
  }
  return a.cy != b.cy ? a.cy < b.cy : a.cx < b.cx;
}

// The best `count` coarse offsets of one oriented exemplar, at least two blocks
// apart, picked from its headSize() best.
std::vector<Seed> bestCoarseOffsets(const std::vector<float>& costs,
  std::size_t oriented,
  int offsetsX,
  int count,
  std::size_t head)
{
  std::vector<Seed> chosen;
  for (std::size_t idx : smallestOffsets(costs, head))
  {
    if (static_cast<int>(chosen.size()) >= count)
    {
      break;
    }
    const GridCell at = cellOf(idx, offsetsX);
    const int cx = at.i;
    const int cy = at.j;
    const bool near = std::any_of(chosen.begin(),
      chosen.end(),
      [&](const Seed& c) { return std::abs(c.cx - cx) <= 1 && std::abs(c.cy - cy) <= 1; });
    if (!near)
    {
      chosen.push_back({ costs[idx], oriented, cx, cy });
    }
  }
  return chosen;
}

} // namespace

std::vector<DenseMatch> DenseMatcher::refine(const DenseQuery& q,
  const std::vector<std::vector<float>>& coarse,
  std::size_t k,
  const std::vector<int>* exemplars) const
{
  const int f = std::max(1, options_.coarseFactor);
  const int P = options_.patchSize;
  // The best coarse offsets of each oriented exemplar, then the best of those
  // overall: coarse costs of all exemplars and variants compare directly, so
  // the refinement budget goes where the good matches are.
  std::vector<std::vector<Seed>> perOriented(oriented_.size());
  const long orientedCount = static_cast<long>(oriented_.size());
#pragma omp parallel for schedule(dynamic)
  for (long o = 0; o < orientedCount; ++o)
  {
    const Oriented& r = oriented_[static_cast<std::size_t>(o)];
    if (exemplars == nullptr ||
      std::find(exemplars->begin(), exemplars->end(), r.exemplar) != exemplars->end())
    {
      perOriented[static_cast<std::size_t>(o)] =
        bestCoarseOffsets(coarse[static_cast<std::size_t>(o)],
          static_cast<std::size_t>(o),
          r.offsetsX,
          options_.refinePerVariant,
          headSize());
    }
  }
  std::vector<Seed> seeds;
  for (const std::vector<Seed>& s : perOriented)
  {
    seeds.insert(seeds.end(), s.begin(), s.end());
  }
  std::sort(seeds.begin(), seeds.end(), seedBefore);
  seeds.resize(std::min(seeds.size(), seedCount(k)));

  // Each seed at full resolution: the optimum lies within half a block of it.
  const int reach = f / 2 + 1;
  std::vector<DenseMatch> found(seeds.size());
  const long seedCount = static_cast<long>(seeds.size());
#pragma omp parallel for schedule(dynamic)
  for (long n = 0; n < seedCount; ++n)
  {
    const Seed& seed = seeds[static_cast<std::size_t>(n)];
    const Oriented& r = oriented_[seed.oriented];
    const int nx = r.full.width - P + 1;
    const int ny = r.full.height - P + 1;
    std::vector<int> cells;
    std::vector<float> heights;
    knownCells(q, P, r.full.width, cells, heights);
    // Runs of kRowLanes offsets must stay inside the (padded) image.
    const int xa = std::max(0, seed.cx * f - reach);
    const int xb = std::min(nx - kRowLanes, seed.cx * f + reach);
    const LandformCells samples = landformCells(q, r.landform.width);
    const double sampleWeight = std::accumulate(samples.weight.begin(), samples.weight.end(), 0.0);
    float best = kInf;
    float bestOverlap = 0.0f;
    double bestLandform = 0.0;
    int bx = -1;
    int by = -1;
    // Every row of the neighbourhood at once (overlapRows), one run of
    // kRowLanes offsets after another; then the offsets in the same order as
    // ever, so ties go the same way.
    const int ya = std::max(0, seed.cy * f - reach);
    const int rows = std::min(ny - 1, seed.cy * f + reach) - ya + 1;
    const int runs = xb >= xa ? (xb - xa) / kRowLanes + 1 : 0;
    std::vector<float> v(static_cast<std::size_t>(std::max(0, rows) * runs * kRowLanes));
    for (int run = 0; run < runs && rows > 0; ++run)
    {
      overlapRows(cells,
        heights,
        seed.oriented,
        xa + run * kRowLanes,
        ya,
        rows,
        &v[static_cast<std::size_t>(run * rows * kRowLanes)]);
    }
    for (int row = 0; row < rows; ++row)
    {
      const int y = ya + row;
      for (int run = 0; run < runs; ++run)
      {
        const int xs = xa + run * kRowLanes;
        const float* lanes = &v[static_cast<std::size_t>((run * rows + row) * kRowLanes)];
        for (int x = xs; x < std::min(xs + kRowLanes, xb + 1); ++x)
        {
          if (r.fullValid[rowMajor(x, y, nx)] == 0)
          {
            continue;
          }
          const double l = landformMisfit(samples, seed.oriented, x, y);
          const float c = combined(lanes[x - xs], l);
          if (c < best)
          {
            best = c;
            bestOverlap = lanes[x - xs];
            bestLandform = l;
            bx = x;
            by = y;
          }
        }
      }
    }
    found[static_cast<std::size_t>(n)] = bx >= 0
      ? describe(q, seed.oriented, bx, by, bestOverlap, bestLandform, sampleWeight)
      : DenseMatch{ 0, 0, 0, 0, 0.0, 0.0, kInf, kInf, kInf, kInf };
  }
  std::vector<DenseMatch> all;
  for (const DenseMatch& m : found)
  {
    if (m.cost < kInf)
    {
      all.push_back(m);
    }
  }
  std::sort(all.begin(), all.end(), better);
  all.erase(
    std::unique(all.begin(),
      all.end(),
      [](const DenseMatch& a, const DenseMatch& b)
      { return a.exemplar == b.exemplar && a.variant == b.variant && a.x == b.x && a.y == b.y; }),
    all.end());
  if (all.size() > k)
  {
    all.resize(k);
  }
  return all;
}

std::vector<DenseMatch> DenseMatcher::search(const DenseQuery& q, std::size_t k) const
{
  const RefineRequest request{ k, nullptr };
  return refine(q,
    prunedCoarseCosts(
      coarseQuery(q),
      [this](const CoarseTerms& t, CoarseImage i, const std::vector<std::vector<std::uint8_t>>* r)
      { return coarseSsd(t, i, r); },
      &request),
    k);
}

std::vector<DenseMatch> DenseMatcher::bruteForce(const DenseQuery& q, std::size_t k) const
{
  const int P = options_.patchSize;
  std::vector<DenseMatch> all;
  for (std::size_t o = 0; o < oriented_.size(); ++o)
  {
    const Oriented& r = oriented_[o];
    const int nx = r.full.width - P + 1;
    const int ny = r.full.height - P + 1;
    std::vector<DenseMatch> rows(static_cast<std::size_t>(std::max(0, ny)));
    std::vector<char> found(rows.size(), 0);
    std::vector<int> cells;
    std::vector<float> heights;
    knownCells(q, P, r.full.width, cells, heights);
    const LandformCells samples = landformCells(q, r.landform.width);
    const double sampleWeight = std::accumulate(samples.weight.begin(), samples.weight.end(), 0.0);
#pragma omp parallel for schedule(dynamic)
    for (int y = 0; y < ny; ++y)
    {
      DenseMatch best;
      best.cost = kInf;
      // The last kRowLanes - 1 offsets of a row lie in the padding: never valid.
      for (int xs = 0; xs + kRowLanes <= nx; xs += kRowLanes)
      {
        float v[kRowLanes];
        overlapRows(cells, heights, o, xs, y, 1, v);
        for (int x = xs; x < xs + kRowLanes; ++x)
        {
          if (r.fullValid[rowMajor(x, y, nx)] == 0)
          {
            continue;
          }
          const DenseMatch m =
            describe(q, o, x, y, v[x - xs], landformMisfit(samples, o, x, y), sampleWeight);
          if (better(m, best))
          {
            best = m;
          }
        }
      }
      rows[static_cast<std::size_t>(y)] = best;
      found[static_cast<std::size_t>(y)] = best.cost < kInf ? 1 : 0;
    }
    for (std::size_t y = 0; y < rows.size(); ++y)
    {
      if (found[y] != 0)
      {
        all.push_back(rows[y]);
      }
    }
  }
  std::sort(all.begin(), all.end(), better);
  if (all.size() > k)
  {
    all.resize(k);
  }
  return all;
}

std::array<float, kNoiseLevels> DenseMatcher::typicalNoise() const
{
  const int P = options_.patchSize;
  std::array<std::vector<float>, kNoiseLevels> samples;
  for (std::size_t e = 0; e < noise_.size(); ++e)
  {
    const auto& size = exemplarSize_[e];
    for (int y = P / 2; y + P / 2 <= size[1]; y += P / 2)
    {
      for (int x = P / 2; x + P / 2 <= size[0]; x += P / 2)
      {
        const auto v = noise_[e].window(x, y, P);
        for (std::size_t l = 0; l < samples.size(); ++l)
        {
          samples[l].push_back(v[l]);
        }
      }
    }
  }
  std::array<float, kNoiseLevels> typical{};
  for (std::size_t l = 0; l < samples.size(); ++l)
  {
    auto& v = samples[l];
    if (!v.empty())
    {
      std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
      typical[l] = v[v.size() / 2];
    }
  }
  return typical;
}

double roughnessMisfit(const std::array<float, kNoiseLevels>& asked,
  const std::array<float, kNoiseLevels>& found)
{
  double misfit = 0.0;
  for (std::size_t l = 0; l < asked.size(); ++l)
  {
    const double a = asked[l];
    const double f = found[l];
    if (a > 0.0 && a + f > 0.0)
    {
      const double d = (a - f) / (a + f);
      misfit += d * d;
    }
  }
  return misfit;
}

} // namespace tsynth
