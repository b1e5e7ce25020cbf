#include "DenseSearch.h"

#include "../Core/Error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace tsynth
{
namespace
{

constexpr float kInf = std::numeric_limits<float>::infinity();

// valid[y * (w - side + 1) + x] = 1 when the side x side window at (x, y) has
// no invalid cell, from a summed-area table of invalid cells.
std::vector<std::uint8_t> windowValidity(int w,
  int h,
  int side,
  const std::vector<std::uint8_t>& cellValid)
{
  std::vector<int> sat(static_cast<std::size_t>(w + 1) * static_cast<std::size_t>(h + 1), 0);
  auto at = [&](int i, int j)
  {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(w + 1) +
      static_cast<std::size_t>(i);
  };
  for (int j = 0; j < h; ++j)
  {
    int row = 0;
    for (int i = 0; i < w; ++i)
    {
      row += cellValid[static_cast<std::size_t>(j) * static_cast<std::size_t>(w) +
               static_cast<std::size_t>(i)] != 0
        ? 0
        : 1;
      sat[at(i + 1, j + 1)] = sat[at(i + 1, j)] + row;
    }
  }
  const int nx = std::max(0, w - side + 1);
  const int ny = std::max(0, h - side + 1);
  std::vector<std::uint8_t> valid(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny), 0);
  for (int y = 0; y < ny; ++y)
  {
    for (int x = 0; x < nx; ++x)
    {
      const int bad =
        sat[at(x + side, y + side)] - sat[at(x, y + side)] - sat[at(x + side, y)] + sat[at(x, y)];
      valid[static_cast<std::size_t>(y) * static_cast<std::size_t>(nx) +
        static_cast<std::size_t>(x)] = bad == 0 ? 1 : 0;
    }
  }
  return valid;
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
    noise_.emplace_back(ex);
    exemplarSize_.push_back({ ex.width, ex.height });
    for (int v = 0; v < kVariantCount; ++v)
    {
      if (!o.variants[static_cast<std::size_t>(v)])
      {
        continue;
      }
      Oriented r;
      r.exemplar = static_cast<int>(e);
      r.variant = v;
      r.full = orientExemplar(ex, variant(v), &r.centreX, &r.centreY);
      std::vector<std::uint8_t> cellValid(r.full.size());
      for (std::size_t k = 0; k < cellValid.size(); ++k)
      {
        cellValid[k] = r.full.isValid(k) ? 1 : 0;
      }
      r.fullValid = windowValidity(r.full.width, r.full.height, P, cellValid);
      r.coarseWidth = r.full.width / f;
      r.coarseHeight = r.full.height / f;
      r.coarseStride = r.coarseWidth + 16;
      r.coarse.assign(
        static_cast<std::size_t>(r.coarseStride) * static_cast<std::size_t>(r.coarseHeight), 0.0f);
      std::vector<std::uint8_t> blockValid(
        static_cast<std::size_t>(r.coarseWidth) * static_cast<std::size_t>(r.coarseHeight), 0);
      for (int b = 0; b < r.coarseHeight; ++b)
      {
        for (int a = 0; a < r.coarseWidth; ++a)
        {
          double s = 0.0;
          bool ok = true;
          for (int j = b * f; j < (b + 1) * f && ok; ++j)
          {
            for (int i = a * f; i < (a + 1) * f; ++i)
            {
              if (!r.full.isValid(i, j))
              {
                ok = false;
                break;
              }
              s += r.full.at(i, j);
            }
          }
          if (ok)
          {
            r.coarse[static_cast<std::size_t>(b) * static_cast<std::size_t>(r.coarseStride) +
              static_cast<std::size_t>(a)] = static_cast<float>(s / (f * f));
            blockValid[static_cast<std::size_t>(b) * static_cast<std::size_t>(r.coarseWidth) +
              static_cast<std::size_t>(a)] = 1;
          }
        }
      }
      r.coarseValid = windowValidity(r.coarseWidth, r.coarseHeight, P / f, blockValid);
      r.offsetsX = std::max(0, r.coarseWidth - P / f + 1);
      r.offsetsY = std::max(0, r.coarseHeight - P / f + 1);
      const int groups = (r.offsetsX + 15) / 16;
      r.groupValid.assign(
        static_cast<std::size_t>(groups) * static_cast<std::size_t>(r.offsetsY), 0);
      for (int y = 0; y < r.offsetsY; ++y)
      {
        for (int x = 0; x < r.offsetsX; ++x)
        {
          if (r.coarseValid[static_cast<std::size_t>(y) * static_cast<std::size_t>(r.offsetsX) +
                static_cast<std::size_t>(x)] != 0)
          {
            r.groupValid[static_cast<std::size_t>(y) * static_cast<std::size_t>(groups) +
              static_cast<std::size_t>(x / 16)] = 1;
          }
        }
      }
      oriented_.push_back(std::move(r));
    }
  }
  const double mean = count > 0 ? sum / count : 0.0;
  heightScale_ =
    std::max(1e-6, std::sqrt(std::max(0.0, square / std::max(1.0, count) - mean * mean)));
}

CoarseQuery DenseMatcher::coarseQuery(const DenseQuery& q) const
{
  const int P = options_.patchSize;
  const int f = std::max(1, options_.coarseFactor);
  CoarseQuery c;
  c.side = P / f;
  c.heights.assign(static_cast<std::size_t>(c.side * c.side), 0.0f);
  c.weights.assign(static_cast<std::size_t>(c.side * c.side), 0.0f);
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
          const std::size_t k = static_cast<std::size_t>(j * P + i);
          if (q.known[k] != 0)
          {
            s += q.heights[k];
            n += 1.0;
          }
        }
      }
      const std::size_t k = static_cast<std::size_t>(b * c.side + a);
      c.heights[k] = n > 0 ? static_cast<float>(s / n) : 0.0f;
      c.weights[k] = static_cast<float>(n / (f * f));
      if (n > 0)
      {
        c.row.push_back(b);
        c.column.push_back(a);
        c.listHeights.push_back(c.heights[k]);
        c.listWeights.push_back(c.weights[k]);
      }
    }
  }
  return c;
}

std::vector<std::vector<float>> DenseMatcher::coarseCosts(const CoarseQuery& q) const
{
  std::vector<std::vector<float>> out(oriented_.size());
  // One task per row of offsets of every oriented exemplar, in a single parallel
  // region (a region per variant stalls when a core is busy elsewhere).
  std::vector<std::pair<std::size_t, int>> tasks;
  for (std::size_t o = 0; o < oriented_.size(); ++o)
  {
    const Oriented& r = oriented_[o];
    out[o].assign(
      static_cast<std::size_t>(r.offsetsX) * static_cast<std::size_t>(r.offsetsY), kInf);
    for (int y = 0; y < r.offsetsY; ++y)
    {
      tasks.push_back({ o, y });
    }
  }
  const std::size_t terms = q.row.size();
  const long taskCount = static_cast<long>(tasks.size());
#pragma omp parallel for schedule(dynamic, 16)
  for (long t = 0; t < taskCount; ++t)
  {
    const auto [o, y] = tasks[static_cast<std::size_t>(t)];
    const Oriented& r = oriented_[o];
    std::vector<float>& costs = out[o];
    // Sixteen neighbouring offsets at a time, like the OpenCL kernel (DenseSsd.cl),
    // over the known blocks only, skipping runs of offsets that are all invalid.
    const int groups = (r.offsetsX + 15) / 16;
    for (int g = 0; g < groups; ++g)
    {
      if (r.groupValid[static_cast<std::size_t>(y) * static_cast<std::size_t>(groups) +
            static_cast<std::size_t>(g)] == 0)
      {
        continue;
      }
      const int x0 = 16 * g;
      float acc[16] = {};
      for (std::size_t e = 0; e < terms; ++e)
      {
        const float* cells = r.coarse.data() +
          static_cast<std::size_t>(y + q.row[e]) * static_cast<std::size_t>(r.coarseStride) +
          static_cast<std::size_t>(x0 + q.column[e]);
        const float h = q.listHeights[e];
        const float m = q.listWeights[e];
        for (int l = 0; l < 16; ++l)
        {
          const float d = h - cells[l];
          acc[l] += m * d * d;
        }
      }
      for (int l = 0; l < 16 && x0 + l < r.offsetsX; ++l)
      {
        const std::size_t k = static_cast<std::size_t>(y) * static_cast<std::size_t>(r.offsetsX) +
          static_cast<std::size_t>(x0 + l);
        costs[k] = r.coarseValid[k] != 0 ? acc[l] : kInf;
      }
    }
  }
  return out;
}

float DenseMatcher::overlapAt(const std::vector<int>& cells,
  const std::vector<float>& heights,
  std::size_t o,
  int x,
  int y) const
{
  const Oriented& r = oriented_[o];
  const float* base = r.full.z.data() + r.full.index(x, y);
  float s = 0.0f;
  for (std::size_t e = 0; e < cells.size(); ++e)
  {
    const float d = heights[e] - base[cells[e]];
    s += d * d;
  }
  return cells.empty() ? 0.0f
                       : static_cast<float>(s / cells.size() / (heightScale_ * heightScale_));
}

DenseMatch DenseMatcher::describe(const DenseQuery& q,
  std::size_t o,
  int x,
  int y,
  float overlap) const
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
  match.overlap = overlap;
  const double scale2 = heightScale_ * heightScale_;
  const auto nv =
    noise_[static_cast<std::size_t>(r.exemplar)].window(match.centreX, match.centreY, P);
  double cn = 0.0;
  for (int l = 0; l < kNoiseLevels; ++l)
  {
    const double d =
      (q.noise[static_cast<std::size_t>(l)] - nv[static_cast<std::size_t>(l)]) / scale2;
    cn += d * d;
  }
  match.cost = static_cast<float>(options_.overlapWeight * overlap + options_.noiseWeight * cn);
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
      const std::size_t k = static_cast<std::size_t>(j * patch + i);
      if (q.known[k] != 0)
      {
        cells.push_back(j * stride + i);
        heights.push_back(q.heights[k]);
      }
    }
  }
}

} // namespace

std::vector<DenseMatch> DenseMatcher::refine(const DenseQuery& q,
  const std::vector<std::vector<float>>& coarse,
  std::size_t k,
  const std::vector<int>* exemplars) const
{
  const int f = std::max(1, options_.coarseFactor);
  const int P = options_.patchSize;
  std::vector<DenseMatch> all;
  for (std::size_t o = 0; o < oriented_.size(); ++o)
  {
    const Oriented& r = oriented_[o];
    if (exemplars != nullptr &&
      std::find(exemplars->begin(), exemplars->end(), r.exemplar) == exemplars->end())
    {
      continue;
    }
    const std::vector<float>& costs = coarse[o];
    // The best coarse offsets, at least two blocks apart.
    std::vector<std::size_t> order(costs.size());
    std::iota(order.begin(), order.end(), 0);
    // Only the head of the ranking is needed: a partial sort of a few times
    // more offsets than will be refined (neighbours get suppressed).
    const std::size_t head =
      std::min(order.size(), static_cast<std::size_t>(16 * std::max(1, options_.refinePerVariant)));
    std::partial_sort(order.begin(),
      order.begin() + static_cast<long>(head),
      order.end(),
      [&](std::size_t a, std::size_t b)
      { return costs[a] < costs[b] || (costs[a] == costs[b] && a < b); });
    order.resize(head);
    std::vector<std::pair<int, int>> chosen;
    for (std::size_t idx : order)
    {
      if (!(costs[idx] < kInf) || static_cast<int>(chosen.size()) >= options_.refinePerVariant)
      {
        break;
      }
      const int cx = static_cast<int>(idx % static_cast<std::size_t>(r.offsetsX));
      const int cy = static_cast<int>(idx / static_cast<std::size_t>(r.offsetsX));
      const bool near = std::any_of(chosen.begin(),
        chosen.end(),
        [&](const auto& c) { return std::abs(c.first - cx) <= 1 && std::abs(c.second - cy) <= 1; });
      if (!near)
      {
        chosen.push_back({ cx, cy });
      }
    }
    const int nx = r.full.width - P + 1;
    const int ny = r.full.height - P + 1;
    std::vector<int> cells;
    std::vector<float> heights;
    knownCells(q, P, r.full.width, cells, heights);
    // The full-resolution optimum lies within half a block of a coarse offset.
    const int reach = f / 2 + 1;
    // A few milliseconds in all: serial, no thread start-up per variant.
    std::vector<DenseMatch> found(chosen.size());
    for (std::size_t c = 0; c < chosen.size(); ++c)
    {
      const auto [cx, cy] = chosen[c];
      float best = kInf;
      int bx = -1;
      int by = -1;
      for (int y = cy * f - reach; y <= cy * f + reach; ++y)
      {
        for (int x = cx * f - reach; x <= cx * f + reach; ++x)
        {
          if (x < 0 || y < 0 || x >= nx || y >= ny ||
            r.fullValid[static_cast<std::size_t>(y) * static_cast<std::size_t>(nx) +
              static_cast<std::size_t>(x)] == 0)
          {
            continue;
          }
          const float v = overlapAt(cells, heights, o, x, y);
          if (v < best)
          {
            best = v;
            bx = x;
            by = y;
          }
        }
      }
      found[c] =
        bx >= 0 ? describe(q, o, bx, by, best) : DenseMatch{ 0, 0, 0, 0, 0.0, 0.0, kInf, kInf };
    }
    for (const DenseMatch& m : found)
    {
      if (m.cost < kInf)
      {
        all.push_back(m);
      }
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
  return refine(q, coarseCosts(coarseQuery(q)), k);
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
#pragma omp parallel for schedule(dynamic)
    for (int y = 0; y < ny; ++y)
    {
      DenseMatch best;
      best.cost = kInf;
      for (int x = 0; x < nx; ++x)
      {
        if (r.fullValid[static_cast<std::size_t>(y) * static_cast<std::size_t>(nx) +
              static_cast<std::size_t>(x)] == 0)
        {
          continue;
        }
        const DenseMatch m = describe(q, o, x, y, overlapAt(cells, heights, o, x, y));
        if (better(m, best))
        {
          best = m;
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

} // namespace tsynth
