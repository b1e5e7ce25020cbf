#include "Ppa.h"

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

// LSD radix sort of 64-bit keys, 16 bits a pass.
void radixSort(std::vector<std::uint64_t>& keys)
{
  std::vector<std::uint64_t> tmp(keys.size());
  std::vector<std::size_t> count(65537);
  for (int shift = 0; shift < 64; shift += 16)
  {
    std::fill(count.begin(), count.end(), 0);
    for (std::uint64_t k : keys)
    {
      ++count[((k >> shift) & 0xffffU) + 1];
    }
    if (count[1] == keys.size() && shift > 0)
    {
      continue; // every key has a zero digit here: nothing to reorder
    }
    std::partial_sum(count.begin(), count.end(), count.begin());
    for (std::uint64_t k : keys)
    {
      tmp[count[(k >> shift) & 0xffffU]++] = k;
    }
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
  for (int t = -r; t <= r; ++t)
  {
    kernel[static_cast<std::size_t>(t + r)] = std::exp(-0.5 * t * t / (sigma * sigma));
  }
  const int w = hf.width;
  const int h = hf.height;
  std::vector<float> pass(hf.size());
  std::vector<float> weight(hf.size());
  // Horizontal pass: weighted sums and weights of valid cells.
#pragma omp parallel for schedule(static)
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      double s = 0.0;
      double ws = 0.0;
      for (int t = std::max(-r, -i); t <= std::min(r, w - 1 - i); ++t)
      {
        if (hf.isValid(i + t, j))
        {
          const double k = kernel[static_cast<std::size_t>(t + r)];
          s += k * hf.at(i + t, j);
          ws += k;
        }
      }
      pass[hf.index(i, j)] = static_cast<float>(s);
      weight[hf.index(i, j)] = static_cast<float>(ws);
    }
  }
  Heightfield out = hf;
#pragma omp parallel for schedule(static)
  for (int j = 0; j < h; ++j)
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
        const double k = kernel[static_cast<std::size_t>(t + r)];
        s += k * pass[hf.index(i, j + t)];
        ws += k * weight[hf.index(i, j + t)];
      }
      out.at(i, j) = static_cast<float>(s / ws);
    }
  }
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
  static constexpr int axes[4][2] = { { 1, 0 }, { 0, 1 }, { 1, 1 }, { 1, -1 } };
#pragma omp parallel for schedule(static)
  for (int j = 0; j < h; ++j)
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
      for (const auto& a : axes)
      {
        best = std::max(best, std::min(dipAlong(a[0], a[1]), dipAlong(-a[0], -a[1])));
      }
      if (best > 0.0f && best > minDip && best >= relativeDip * relief)
      {
        targets[hf.index(i, j)] = 1;
      }
    }
  }
  return targets;
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
#pragma omp parallel for schedule(static)
  for (int j = 0; j < h; ++j)
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
  }
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

  auto t = Clock::now();
  const std::vector<std::uint8_t> targets =
    profileTargets(work, o.halfProfileLength, o.minDip, o.relativeDip);
  result.timings.profile = secondsSince(t);
  result.statistics.targets =
    static_cast<std::size_t>(std::count(targets.begin(), targets.end(), std::uint8_t{ 1 }));

  t = Clock::now();
  const std::vector<CellEdge> edges = connectTargets(work, targets);
  result.timings.connect = secondsSince(t);
  result.statistics.candidateEdges = edges.size();

  t = Clock::now();
  result.pixels = maximumSpanningForest(hf.width, hf.height, edges);
  result.timings.spanningForest = secondsSince(t);
  result.statistics.forestEdges = result.pixels.edgeCount();

  t = Clock::now();
  result.pixels.removeEndSegments(o.endReductions);
  result.pixels.pruneShortBranches(o.minBranchLength);
  result.pixels.removeSmallComponents(o.minTreeSize);
  result.timings.pruning = secondsSince(t);
  result.statistics.prunedCells = result.pixels.nodeCount();

  t = Clock::now();
  result.graph = buildFeatureGraph(result.pixels, type, &hf, hf.cellX, hf.cellY);
  smoothChains(result.graph, o.smoothingPasses);
  computeControlPoints(result.graph, o.controlRadius);
  result.timings.graph = secondsSince(t);

  if (result.graph.empty())
  {
    const HeightRange range = computeHeightRange(hf);
    const char* what = type == FeatureType::Ridge ? "ridges" : "valleys";
    result.warnings.push_back(range.max > range.min
        ? std::string("No ") + what +
          " were found with these settings; try a longer profile or smaller pruning lengths."
        : std::string("No ") + what + ": the heightfield is flat.");
  }
  return result;
}

} // namespace tsynth
