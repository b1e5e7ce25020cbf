#include "Ppa.h"

#include "../Core/Cancellation.h"
#include "../Core/Error.h"
#include "../Core/Grid.h"

#include <boost/pending/disjoint_sets.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>

namespace tsynth
{
namespace
{

using Clock = std::chrono::steady_clock;

// The four profile axes (E-W, N-S and the two diagonals), one direction each.
constexpr int kAxes[4][2] = { { 1, 0 }, { 0, 1 }, { 1, 1 }, { 1, -1 } };

// Percentiles that bound the robust relief: up to 1% of the cells at either end
// (spikes, pits, a sliver of sea or of a higher massif) do not set the scale.
constexpr double kReliefLowQuantile = 0.01;
constexpr double kReliefHighQuantile = 0.99;
// Cells the relief is estimated from (all of them up to 512 x 512): percentiles
// of 2^18 samples are within a few parts in ten thousand of the exact ones.
constexpr std::size_t kReliefSamples = std::size_t{ 1 } << 18;

// The residual of the least-squares quadric at the centre of a 3 x 3 block, times
// 9: the mixed fourth difference (1 -2 1) x (1 -2 1).
constexpr double kQuadricResidual[3][3] = { { 1, -2, 1 }, { -2, 4, -2 }, { 1, -2, 1 } };
// Its standard deviation for white noise of sigma 1: sqrt(36) / 9.
constexpr double kQuadricResidualPerSigma = 2.0 / 3.0;
// Median absolute value of a standard normal variable.
constexpr double kMedianAbsPerSigma = 0.6744897501960817;

double secondsSince(Clock::time_point t0)
{
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Ascending order of the key is descending order of the weight.
std::uint32_t descendingKey(float w)
{
  std::uint32_t bits = 0;
  std::memcpy(&bits, &w, sizeof bits);
  const std::uint32_t ascending = (bits & 0x80000000U) != 0 ? ~bits : (bits | 0x80000000U);
  return ~ascending;
}

// Keys a radix pass handles between cancellation checks: a pass's scatter over
// the 10^8 keys of a large DEM's edges takes up to a second on a loaded machine
// (Ctrl-C waited 1.3 s in it), a block of 2^22 about 40 ms.
constexpr std::size_t kKeysPerCancellationCheck = std::size_t{ 1 } << 22;

// body(k) for every key, in order, checking for cancellation every block of keys.
template<class Body>
void forKeyBlocks(const std::vector<std::uint64_t>& keys, const Body& body)
{
  for (std::size_t first = 0; first < keys.size(); first += kKeysPerCancellationCheck)
  {
    const std::size_t last = std::min(keys.size(), first + kKeysPerCancellationCheck);
    for (std::size_t e = first; e < last; ++e)
    {
      body(keys[e]);
    }
    checkCancellation();
  }
}

// LSD radix sort of 64-bit keys, 16 bits a pass.
void radixSort(std::vector<std::uint64_t>& keys)
{
  std::vector<std::uint64_t> tmp(keys.size());
  std::vector<std::size_t> count(65537);
  for (int shift = 0; shift < 64; shift += 16)
  {
    std::fill(count.begin(), count.end(), 0);
    forKeyBlocks(keys, [&](std::uint64_t k) { ++count[((k >> shift) & 0xffffU) + 1]; });
    if (count[1] == keys.size() && shift > 0)
    {
      continue; // every key has a zero digit here: nothing to reorder
    }
    std::partial_sum(count.begin(), count.end(), count.begin());
    forKeyBlocks(keys, [&](std::uint64_t k) { tmp[count[(k >> shift) & 0xffffU]++] = k; });
    keys.swap(tmp);
  }
}

} // namespace

Heightfield gaussianSmooth(const Heightfield& hf, double sigma)
{
  if (!(sigma > 0.0))
  {
    return hf;
  }
  const int r = std::max(1, static_cast<int>(std::ceil(3.0 * sigma)));
  std::vector<double> kernel(static_cast<std::size_t>(2 * r + 1));
  double* const tap = kernel.data() + r; // tap[t]: the weight at offset t, -r..r
  for (int t = -r; t <= r; ++t)
  {
    tap[t] = std::exp(-0.5 * t * t / (sigma * sigma));
  }
  const int w = hf.width;
  const int h = hf.height;
  std::vector<float> pass(hf.size());
  std::vector<float> weight(hf.size());
  // Horizontal pass: weighted sums and weights of valid cells.
  forRowBands(h,
    [&](int j)
    {
      for (int i = 0; i < w; ++i)
      {
        double s = 0.0;
        double ws = 0.0;
        for (int t = std::max(-r, -i); t <= std::min(r, w - 1 - i); ++t)
        {
          if (hf.isValid(i + t, j))
          {
            const double k = tap[t];
            s += k * hf.at(i + t, j);
            ws += k;
          }
        }
        pass[hf.index(i, j)] = static_cast<float>(s);
        weight[hf.index(i, j)] = static_cast<float>(ws);
      }
    });
  Heightfield out = hf;
  forRowBands(h,
    [&](int j)
    {
      for (int i = 0; i < w; ++i)
      {
        if (!hf.isValid(i, j))
        {
          continue;
        }
        double s = 0.0;
        double ws = 0.0;
        for (int t = std::max(-r, -j); t <= std::min(r, h - 1 - j); ++t)
        {
          const double k = tap[t];
          s += k * pass[hf.index(i, j + t)];
          ws += k * weight[hf.index(i, j + t)];
        }
        out.at(i, j) = static_cast<float>(s / ws);
      }
    });
  return out;
}

std::vector<std::uint8_t> profileTargets(const Heightfield& hf,
  int halfProfileLength,
  double minDip,
  double relativeDip)
{
  const int w = hf.width;
  const int h = hf.height;
  const int len = std::max(1, halfProfileLength);
  std::vector<std::uint8_t> targets(hf.size(), 0);
  forRowBands(h,
    [&](int j)
    {
      for (int i = 0; i < w; ++i)
      {
        if (!hf.isValid(i, j))
        {
          continue;
        }
        const float centre = hf.at(i, j);
        // Deepest dip (centre minus lowest valid height) within len cells one way,
        // and the largest height difference seen, for the relative threshold.
        float relief = 0.0f;
        auto dipAlong = [&](int dx, int dy)
        {
          float dip = 0.0f;
          for (int t = 1; t <= len; ++t)
          {
            const int ii = i + t * dx;
            const int jj = j + t * dy;
            if (ii < 0 || jj < 0 || ii >= w || jj >= h)
            {
              break;
            }
            if (hf.isValid(ii, jj))
            {
              const float d = centre - hf.at(ii, jj);
              dip = std::max(dip, d);
              relief = std::max(relief, std::abs(d));
            }
          }
          return dip;
        };
        float best = 0.0f;
        for (const auto& a : kAxes)
        {
          best = std::max(best, std::min(dipAlong(a[0], a[1]), dipAlong(-a[0], -a[1])));
        }
        if (best > 0.0f && best > minDip && best >= relativeDip * relief)
        {
          targets[hf.index(i, j)] = 1;
        }
      }
    });
  return targets;
}

double robustRelief(const Heightfield& hf)
{
  // Every stride-th cell: evenly spread over the grid, enough for percentiles
  // of a few parts in ten thousand, and quick to select among.
  const std::size_t stride =
    std::max<std::size_t>(1, (hf.size() + kReliefSamples - 1) / kReliefSamples);
  std::vector<float> heights;
  heights.reserve(hf.size() / stride + 1);
  for (std::size_t k = 0; k < hf.size(); k += stride)
  {
    if (hf.isValid(k) && std::isfinite(hf.z[k]))
    {
      heights.push_back(hf.z[k]);
    }
  }
  if (heights.empty())
  {
    return 0.0;
  }
  const double last = static_cast<double>(heights.size() - 1);
  const auto rank = [&](double q)
  { return heights.begin() + static_cast<std::ptrdiff_t>(std::floor(q * last)); };
  const auto low = rank(kReliefLowQuantile);
  const auto high = rank(kReliefHighQuantile);
  std::nth_element(heights.begin(), low, heights.end());
  const double lowHeight = *low;              // read now: the next step reorders from `low` on
  std::nth_element(low, high, heights.end()); // everything from `low` on is >= lowHeight
  const double relief = static_cast<double>(*high) - lowHeight;
  if (relief > 0.0)
  {
    return relief;
  }
  const auto [lo, hi] = std::minmax_element(heights.begin(), heights.end());
  return static_cast<double>(*hi) - static_cast<double>(*lo);
}

double cellNoise(const Heightfield& hf)
{
  const int w = hf.width;
  const int h = hf.height;
  if (w < 3 || h < 3)
  {
    return 0.0;
  }
  const std::size_t interior = cellCount(w - 2, h - 2);
  const std::size_t stride =
    std::max<std::size_t>(1, (interior + kReliefSamples - 1) / kReliefSamples);
  auto block = [&](int i, int j, double& residual)
  {
    double sum = 0.0;
    for (int dj = -1; dj <= 1; ++dj)
    {
      for (int di = -1; di <= 1; ++di)
      {
        const std::size_t k = hf.index(i + di, j + dj);
        if (!hf.isValid(k) || !std::isfinite(hf.z[k]))
        {
          return false;
        }
        sum += kQuadricResidual[dj + 1][di + 1] * static_cast<double>(hf.z[k]);
      }
    }
    residual = std::abs(sum) / 9.0;
    return true;
  };
  std::vector<float> residuals;
  residuals.reserve(interior / stride + 1);
  for (std::size_t n = 0; n < interior; n += stride)
  {
    const GridCell c = cellOf(n, w - 2); // of the interior, one cell in from each edge
    double r = 0.0;
    if (block(1 + c.i, 1 + c.j, r))
    {
      residuals.push_back(static_cast<float>(r));
    }
  }
  if (residuals.empty())
  {
    return 0.0;
  }
  const auto median = residuals.begin() + static_cast<std::ptrdiff_t>(residuals.size() / 2);
  std::nth_element(residuals.begin(), median, residuals.end());
  return *median / (kMedianAbsPerSigma * kQuadricResidualPerSigma);
}

namespace
{

// True if the walk of at most `steps` cells from cell idx, `stride` cells a
// step, falls `drop` below the cell's height before it rises `drop` above it.
// Masked: invalid cells are stepped over.
template<bool Masked>
bool descendsFirst(const Heightfield& hf,
  std::size_t idx,
  std::ptrdiff_t stride,
  int steps,
  float drop)
{
  const float centre = hf.z[idx];
  std::size_t cell = idx;
  for (int t = 0; t < steps; ++t)
  {
    cell = offsetCell(cell, stride);
    if (Masked && hf.valid[cell] == 0)
    {
      continue;
    }
    const float dip = centre - hf.z[cell];
    if (dip >= drop)
    {
      return true;
    }
    if (dip <= -drop)
    {
      return false;
    }
  }
  return false;
}

// Cells from (i, j) to the grid edge in direction (dx, dy), at most len.
int stepsToEdge(const Heightfield& hf, int i, int j, int dx, int dy, int len)
{
  int n = len;
  n = dx > 0 ? std::min(n, hf.width - 1 - i) : dx < 0 ? std::min(n, i) : n;
  n = dy > 0 ? std::min(n, hf.height - 1 - j) : dy < 0 ? std::min(n, j) : n;
  return n;
}

template<bool Masked>
bool isSignificant(const Heightfield& hf, int i, int j, int len, float drop)
{
  const std::size_t idx = hf.index(i, j);
  const auto width = static_cast<std::ptrdiff_t>(hf.width);
  for (const auto& a : kAxes)
  {
    const std::ptrdiff_t stride = a[1] * width + a[0];
    if (descendsFirst<Masked>(hf, idx, stride, stepsToEdge(hf, i, j, a[0], a[1], len), drop) &&
      descendsFirst<Masked>(hf, idx, -stride, stepsToEdge(hf, i, j, -a[0], -a[1], len), drop))
    {
      return true;
    }
  }
  return false;
}

template<bool Masked>
std::size_t clearInsignificant(const Heightfield& hf,
  std::vector<std::uint8_t>& targets,
  int len,
  float drop)
{
  std::size_t removed = 0;
  // Each cell reads heights only and writes its own target flag: rows are independent. Rows
  // cost very different amounts (targets are sparse), hence the dynamic schedule per band.
  for (int first = 0; first < hf.height; first += kCancellationBandRows)
  {
    const int last = std::min(hf.height, first + kCancellationBandRows);
#pragma omp parallel for schedule(dynamic, 16) reduction(+ : removed)
    for (int j = first; j < last; ++j)
    {
      for (int i = 0; i < hf.width; ++i)
      {
        std::uint8_t& target = targets[hf.index(i, j)];
        if (target != 0 && !isSignificant<Masked>(hf, i, j, len, drop))
        {
          target = 0;
          ++removed;
        }
      }
    }
    checkCancellation();
  }
  return removed;
}

} // namespace

std::size_t removeInsignificantTargets(const Heightfield& hf,
  std::vector<std::uint8_t>& targets,
  int radius,
  double minDrop)
{
  const int len = std::max(1, radius);
  const auto drop = static_cast<float>(minDrop);
  return hf.hasMask() ? clearInsignificant<true>(hf, targets, len, drop)
                      : clearInsignificant<false>(hf, targets, len, drop);
}

std::vector<CellEdge> connectTargets(const Heightfield& hf,
  const std::vector<std::uint8_t>& targets)
{
  const int w = hf.width;
  const int h = hf.height;
  auto isTarget = [&](int i, int j)
  { return i >= 0 && j >= 0 && i < w && j < h && targets[hf.index(i, j)] != 0; };
  auto weight = [&](std::size_t a, std::size_t b) { return hf.z[a] + hf.z[b]; };
  std::vector<std::vector<CellEdge>> perRow(static_cast<std::size_t>(h));
  forRowBands(h,
    [&](int j)
    {
      auto& row = perRow[static_cast<std::size_t>(j)];
      for (int i = 0; i < w; ++i)
      {
        const std::size_t a = hf.index(i, j);
        const bool ta = targets[a] != 0;
        if (ta && isTarget(i + 1, j))
        {
          const std::size_t b = hf.index(i + 1, j);
          row.push_back(
            { static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(b), weight(a, b) });
        }
        if (ta && isTarget(i, j + 1))
        {
          const std::size_t b = hf.index(i, j + 1);
          row.push_back(
            { static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(b), weight(a, b) });
        }
        // The 2x2 block with lower-left (i, j): its two diagonals cross.
        const bool ne = ta && isTarget(i + 1, j + 1);
        const bool nw = isTarget(i + 1, j) && isTarget(i, j + 1);
        if (!ne && !nw)
        {
          continue;
        }
        const std::size_t neB = ne ? hf.index(i + 1, j + 1) : 0;
        const std::size_t nwA = nw ? hf.index(i + 1, j) : 0;
        const std::size_t nwB = nw ? hf.index(i, j + 1) : 0;
        const float wne = ne ? weight(a, neB) : -std::numeric_limits<float>::infinity();
        const float wnw = nw ? weight(nwA, nwB) : -std::numeric_limits<float>::infinity();
        if (ne && wne >= wnw)
        {
          row.push_back({ static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(neB), wne });
        }
        else if (nw)
        {
          row.push_back({ static_cast<std::uint32_t>(nwA), static_cast<std::uint32_t>(nwB), wnw });
        }
      }
    });
  std::size_t total = 0;
  for (const auto& row : perRow)
  {
    total += row.size();
  }
  std::vector<CellEdge> edges;
  edges.reserve(total);
  for (const auto& row : perRow)
  {
    edges.insert(edges.end(), row.begin(), row.end());
  }
  return edges;
}

PixelGraph maximumSpanningForest(int width, int height, const std::vector<CellEdge>& edges)
{
  std::vector<std::uint64_t> keys(edges.size());
  for (std::size_t e = 0; e < edges.size(); ++e)
  {
    keys[e] = (static_cast<std::uint64_t>(descendingKey(edges[e].weight)) << 32) |
      static_cast<std::uint64_t>(e);
  }
  radixSort(keys);

  PixelGraph forest(width, height);
  const std::size_t n = forest.size();
  std::vector<int> rank(n, 0);
  std::vector<std::uint32_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0U);
  boost::disjoint_sets<int*, std::uint32_t*> sets(rank.data(), parent.data());
  for (std::uint64_t key : keys)
  {
    pollCancellation();
    const CellEdge& e = edges[static_cast<std::size_t>(key & 0xffffffffU)];
    const std::uint32_t ra = sets.find_set(e.a);
    const std::uint32_t rb = sets.find_set(e.b);
    if (ra == rb)
    {
      continue;
    }
    sets.link(ra, rb);
    const int dx = forest.column(e.b) - forest.column(e.a);
    const int dy = forest.row(e.b) - forest.row(e.a);
    for (int k = 0; k < 8; ++k)
    {
      if (PixelGraph::kDx[k] == dx && PixelGraph::kDy[k] == dy)
      {
        forest.link(e.a, k);
        break;
      }
    }
  }
  return forest;
}

FeatureExtraction extractFeatures(const Heightfield& hf, FeatureType type, const PpaOptions& o)
{
  if (!(o.significance >= 0.0 && o.significance <= 1.0))
  {
    throw Error("The PPA significance must be a fraction of the relief from 0 to 1.");
  }
  if (o.significance > 0.0 && o.significanceRadius < 1)
  {
    throw Error("The PPA significance radius must be at least one cell.");
  }
  if (!(o.significanceNoise >= 0.0))
  {
    throw Error("The PPA significance noise factor must not be negative.");
  }
  checkCancellation();
  FeatureExtraction result;
  const auto t0 = Clock::now();
  // Valleys are the ridges of the negated field.
  Heightfield work = hf;
  if (type == FeatureType::Valley)
  {
    for (float& v : work.z)
    {
      v = -v;
    }
  }
  work = gaussianSmooth(work, o.presmoothSigma);
  result.timings.presmooth = secondsSince(t0);

  checkCancellation();
  auto t = Clock::now();
  std::vector<std::uint8_t> targets =
    profileTargets(work, o.halfProfileLength, o.minDip, o.relativeDip);
  result.timings.profile = secondsSince(t);

  checkCancellation();
  t = Clock::now();
  if (o.significance > 0.0)
  {
    result.statistics.relief = robustRelief(work);
    result.statistics.noise = o.significanceNoise > 0.0 ? cellNoise(work) : 0.0;
    result.statistics.significantDrop = std::max(
      o.significance * result.statistics.relief, o.significanceNoise * result.statistics.noise);
    if (result.statistics.significantDrop > 0.0)
    {
      result.statistics.insignificant = removeInsignificantTargets(
        work, targets, o.significanceRadius, result.statistics.significantDrop);
    }
  }
  result.timings.significance = secondsSince(t);
  result.statistics.targets =
    static_cast<std::size_t>(std::count(targets.begin(), targets.end(), std::uint8_t{ 1 }));

  checkCancellation();
  t = Clock::now();
  const std::vector<CellEdge> edges = connectTargets(work, targets);
  result.timings.connect = secondsSince(t);
  result.statistics.candidateEdges = edges.size();

  checkCancellation();
  t = Clock::now();
  result.pixels = maximumSpanningForest(hf.width, hf.height, edges);
  result.timings.spanningForest = secondsSince(t);
  result.statistics.forestEdges = result.pixels.edgeCount();

  checkCancellation();
  t = Clock::now();
  // Each step is a few tenths of a second on a large DEM: a stop is seen between them.
  result.pixels.removeEndSegments(o.endReductions);
  checkCancellation();
  result.pixels.pruneShortBranches(o.minBranchLength);
  checkCancellation();
  result.pixels.removeSmallComponents(o.minTreeSize);
  result.timings.pruning = secondsSince(t);
  result.statistics.prunedCells = result.pixels.nodeCount();

  checkCancellation();
  t = Clock::now();
  result.graph = buildFeatureGraph(result.pixels, type, &hf, hf.cellX, hf.cellY);
  checkCancellation();
  smoothChains(result.graph, o.smoothingPasses);
  checkCancellation();
  computeControlPoints(result.graph, o.controlRadius);
  result.timings.graph = secondsSince(t);

  if (result.graph.empty())
  {
    const HeightRange range = computeHeightRange(hf);
    const char* what = type == FeatureType::Ridge ? "ridges" : "valleys";
    result.warnings.push_back(range.max > range.min
        ? std::string("No ") + what +
          " were found with these settings; try a longer profile, a lower significance or "
          "smaller pruning lengths."
        : std::string("No ") + what + ": the heightfield is flat.");
  }
  return result;
}

FeatureGraph ridgesAndValleys(const Heightfield& hf, const PpaOptions& options)
{
  FeatureGraph g = extractFeatures(hf, FeatureType::Ridge, options).graph;
  appendGraph(g, extractFeatures(hf, FeatureType::Valley, options).graph);
  return g;
}

bool keeps(FeatureSelection selection, FeatureType type)
{
  return selection == FeatureSelection::Both ||
    (selection == FeatureSelection::Valleys) == (type == FeatureType::Valley);
}

FeatureExtraction extractSelectedFeatures(const Heightfield& hf,
  FeatureSelection selection,
  const PpaOptions& options,
  const ProgressReport& progress)
{
  FeatureExtraction out;
  out.graph.width = hf.width;
  out.graph.height = hf.height;
  out.graph.cellX = hf.cellX;
  out.graph.cellY = hf.cellY;
  for (const FeatureType type : { FeatureType::Ridge, FeatureType::Valley })
  {
    const bool valleys = type == FeatureType::Valley;
    if (keeps(selection, type))
    {
      reportProgress(progress, valleys ? 0.5 : 0.0, valleys ? "valleys" : "ridges");
      FeatureExtraction e = extractFeatures(hf, type, options);
      out.statistics = e.statistics;
      appendGraph(out.graph, e.graph);
      out.warnings.insert(out.warnings.end(), e.warnings.begin(), e.warnings.end());
    }
  }
  return out;
}

const std::vector<OptionRow>& ppaOptionRows()
{
  static const std::vector<OptionRow> rows = []
  {
    const PpaOptions d;
    using T = OptionType;
    return std::vector<OptionRow>{
      // Both by default: a terrain's whole feature tree, as the synthesis reads exemplars.
      choiceRow("Features",
        "--features",
        static_cast<int>(FeatureSelection::Both),
        choicesOf(kFeatureSelectionWords),
        { "Ridges", "Valleys", "Ridges and valleys" }),
      numberRow("HalfProfileLength",
        "--profile-length",
        T::Integer,
        d.halfProfileLength,
        1,
        kMaxHalfProfileLength),
      numberRow("MinimumDip", "--min-dip", T::Real, d.minDip, 0.0, kMaxMinimumDip),
      numberRow("RelativeDip", "--relative-dip", T::Real, d.relativeDip, 0.0, 1.0),
      numberRow("Significance", "--significance", T::Real, d.significance, 0.0, 1.0),
      numberRow("SignificanceNoise",
        "--significance-noise",
        T::Real,
        d.significanceNoise,
        0.0,
        kMaxSignificanceNoise),
      numberRow("SignificanceRadius",
        "--significance-radius",
        T::Integer,
        d.significanceRadius,
        1,
        kMaxSignificanceRadius),
      numberRow("PresmoothSigma", "--smooth", T::Real, d.presmoothSigma, 0.0, kMaxPresmoothSigma),
      numberRow(
        "EndReductions", "--end-reductions", T::Integer, d.endReductions, 0, kMaxEndReductions),
      numberRow(
        "MinimumBranchLength", "--min-branch", T::Integer, d.minBranchLength, 0, kMaxBranchLength),
      numberRow("MinimumTreeSize", "--min-tree", T::Integer, d.minTreeSize, 0, kMaxTreeSize),
      numberRow("SmoothingPasses", "", T::Integer, d.smoothingPasses, 0, kMaxSmoothingPasses),
      numberRow("ControlRadius", "", T::Real, d.controlRadius, 1.0, kMaxControlRadius),
    };
  }();
  return rows;
}

} // namespace tsynth
