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
    }
  }
  return c;
}

std::vector<std::vector<float>> DenseMatcher::coarseCosts(const CoarseQuery& q) const
{
  std::vector<std::vector<float>> out(oriented_.size());
  const int side = q.side;
  for (std::size_t o = 0; o < oriented_.size(); ++o)
  {
    const Oriented& r = oriented_[o];
    std::vector<float>& costs = out[o];
    costs.assign(static_cast<std::size_t>(r.offsetsX) * static_cast<std::size_t>(r.offsetsY), kInf);
    // Sixteen neighbouring offsets at a time, like the OpenCL kernel (DenseSsd.cl).
#pragma omp parallel for schedule(static)
    for (int y = 0; y < r.offsetsY; ++y)
    {
      for (int x0 = 0; x0 < r.offsetsX; x0 += 16)
      {
        float acc[16] = {};
        for (int v = 0; v < side; ++v)
        {
          const float* row = r.coarse.data() +
            static_cast<std::size_t>(y + v) * static_cast<std::size_t>(r.coarseStride) +
            static_cast<std::size_t>(x0);
          for (int u = 0; u < side; ++u)
          {
            const float t = q.heights[static_cast<std::size_t>(v * side + u)];
            const float m = q.weights[static_cast<std::size_t>(v * side + u)];
            for (int l = 0; l < 16; ++l)
            {
              const float d = t - row[u + l];
              acc[l] += m * d * d;
            }
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
  }
  return out;
}

DenseMatch DenseMatcher::evaluate(const DenseQuery& q, std::size_t o, int x, int y) const
{
  const Oriented& r = oriented_[o];
  const int P = options_.patchSize;
  double s = 0.0;
  double n = 0.0;
  for (int j = 0; j < P; ++j)
  {
    const float* row = r.full.z.data() + r.full.index(x, y + j);
    const float* t = q.heights.data() + static_cast<std::size_t>(j * P);
    const std::uint8_t* m = q.known.data() + static_cast<std::size_t>(j * P);
    for (int i = 0; i < P; ++i)
    {
      if (m[i] != 0)
      {
        const double d = static_cast<double>(t[i]) - row[i];
        s += d * d;
        n += 1.0;
      }
    }
  }
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
  const double ecx = 0.5 * (size[0] - 1);
  const double ecy = 0.5 * (size[1] - 1);
  match.centreX = ecx + su;
  match.centreY = ecy + sv;
  const double scale2 = heightScale_ * heightScale_;
  match.overlap = static_cast<float>(n > 0 ? s / n / scale2 : 0.0);
  const auto nv =
    noise_[static_cast<std::size_t>(r.exemplar)].window(match.centreX, match.centreY, P);
  double cn = 0.0;
  for (int l = 0; l < kNoiseLevels; ++l)
  {
    const double d =
      (q.noise[static_cast<std::size_t>(l)] - nv[static_cast<std::size_t>(l)]) / scale2;
    cn += d * d;
  }
  match.cost =
    static_cast<float>(options_.overlapWeight * match.overlap + options_.noiseWeight * cn);
  return match;
}

std::vector<DenseMatch> DenseMatcher::refine(const DenseQuery& q,
  const std::vector<std::vector<float>>& coarse,
  std::size_t k) const
{
  const int f = std::max(1, options_.coarseFactor);
  const int P = options_.patchSize;
  std::vector<DenseMatch> all;
  for (std::size_t o = 0; o < oriented_.size(); ++o)
  {
    const Oriented& r = oriented_[o];
    const std::vector<float>& costs = coarse[o];
    // The best coarse offsets, at least two blocks apart.
    std::vector<std::size_t> order(costs.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(),
      order.end(),
      [&](std::size_t a, std::size_t b)
      { return costs[a] < costs[b] || (costs[a] == costs[b] && a < b); });
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
    for (const auto& [cx, cy] : chosen)
    {
      DenseMatch best;
      best.cost = kInf;
      for (int y = cy * f - f; y <= cy * f + f; ++y)
      {
        for (int x = cx * f - f; x <= cx * f + f; ++x)
        {
          if (x < 0 || y < 0 || x >= nx || y >= ny ||
            r.fullValid[static_cast<std::size_t>(y) * static_cast<std::size_t>(nx) +
              static_cast<std::size_t>(x)] == 0)
          {
            continue;
          }
          const DenseMatch m = evaluate(q, o, x, y);
          if (better(m, best))
          {
            best = m;
          }
        }
      }
      if (best.cost < kInf)
      {
        all.push_back(best);
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
        const DenseMatch m = evaluate(q, o, x, y);
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
