#include "TerrainMetrics.h"

#include "../Features/Profiles.h"

#include <algorithm>
#include <cmath>
#include <random>

namespace tsynth
{

double featureFidelity(const Heightfield& t, const FeatureGraph& g, FeatureType type)
{
  std::size_t samples = 0;
  std::size_t good = 0;
  const double sign = type == FeatureType::Ridge ? 1.0 : -1.0;
  for (const FeatureChain& c : g.chains)
  {
    if (c.type != type || c.points.size() < 2)
    {
      continue;
    }
    for (std::size_t k = 1; k < c.points.size(); ++k)
    {
      const Point2& a = c.points[k - 1];
      const Point2& b = c.points[k];
      const double len = std::hypot(b.x - a.x, b.y - a.y);
      if (len <= 0.0)
      {
        continue;
      }
      const double nx = -(b.y - a.y) / len;
      const double ny = (b.x - a.x) / len;
      for (double s = 0.0; s < len; s += 1.0)
      {
        const double px = a.x + (b.x - a.x) * s / len;
        const double py = a.y + (b.y - a.y) * s / len;
        double extreme = -std::numeric_limits<double>::infinity();
        bool ok = true;
        for (int d = -2; d <= 2; ++d)
        {
          const float z = sampleBilinear(t, px + d * nx, py + d * ny);
          ok = ok && !std::isnan(z);
          extreme = std::max(extreme, sign * z);
        }
        const float left = sampleBilinear(t, px + 8 * nx, py + 8 * ny);
        const float right = sampleBilinear(t, px - 8 * nx, py - 8 * ny);
        if (!ok || std::isnan(left) || std::isnan(right))
        {
          continue; // too close to the edge to judge
        }
        ++samples;
        good += (extreme > sign * left && extreme > sign * right) ? 1 : 0;
      }
    }
  }
  return samples > 0 ? static_cast<double>(good) / static_cast<double>(samples) : -1.0;
}

double laplacianPercentile(const Heightfield& hf, double fraction)
{
  std::vector<float> v;
  const double ix = 1.0 / (hf.cellX * hf.cellX);
  const double iy = 1.0 / (hf.cellY * hf.cellY);
  for (int j = 1; j + 1 < hf.height; ++j)
  {
    for (int i = 1; i + 1 < hf.width; ++i)
    {
      if (!hf.isValid(i, j) || !hf.isValid(i - 1, j) || !hf.isValid(i + 1, j) ||
        !hf.isValid(i, j - 1) || !hf.isValid(i, j + 1))
      {
        continue;
      }
      const double c = hf.at(i, j);
      const double lap = (hf.at(i + 1, j) - 2 * c + hf.at(i - 1, j)) * ix +
        (hf.at(i, j + 1) - 2 * c + hf.at(i, j - 1)) * iy;
      v.push_back(static_cast<float>(std::abs(lap)));
    }
  }
  if (v.empty())
  {
    return 0.0;
  }
  const std::size_t k =
    std::min(v.size() - 1, static_cast<std::size_t>(fraction * static_cast<double>(v.size() - 1)));
  std::nth_element(v.begin(), v.begin() + static_cast<long>(k), v.end());
  return v[k];
}

double seamIndex(const Heightfield& output, const Heightfield& exemplar)
{
  const double e = laplacianPercentile(exemplar);
  return e > 0 ? laplacianPercentile(output) / e : 0.0;
}

namespace
{

std::vector<double> slopeHistogram(const Heightfield& hf, double& mean)
{
  std::vector<double> h(900, 0.0); // 0.1 degree bins
  double n = 0.0;
  double sum = 0.0;
  for (int j = 0; j + 1 < hf.height; ++j)
  {
    for (int i = 0; i + 1 < hf.width; ++i)
    {
      if (!hf.isValid(i, j) || !hf.isValid(i + 1, j) || !hf.isValid(i, j + 1))
      {
        continue;
      }
      const double p = (hf.at(i + 1, j) - hf.at(i, j)) / hf.cellX;
      const double q = (hf.at(i, j + 1) - hf.at(i, j)) / hf.cellY;
      const double deg = std::atan(std::hypot(p, q)) * 180.0 / 3.14159265358979323846;
      h[std::min<std::size_t>(899, static_cast<std::size_t>(deg * 10.0))] += 1.0;
      sum += deg;
      n += 1.0;
    }
  }
  for (double& v : h)
  {
    v /= std::max(1.0, n);
  }
  mean = n > 0 ? sum / n : 0.0;
  return h;
}

} // namespace

double slopeDistance(const Heightfield& output, const Heightfield& exemplar)
{
  double mo = 0.0;
  double me = 0.0;
  const auto ho = slopeHistogram(output, mo);
  const auto he = slopeHistogram(exemplar, me);
  // W1 = integral of |CDF_o - CDF_e|.
  double co = 0.0;
  double ce = 0.0;
  double w1 = 0.0;
  for (std::size_t b = 0; b < ho.size(); ++b)
  {
    co += ho[b];
    ce += he[b];
    w1 += std::abs(co - ce) * 0.1;
  }
  return me > 0 ? w1 / me : 0.0;
}

double pitDensity(const Heightfield& hf)
{
  std::size_t pits = 0;
  std::size_t cells = 0;
  for (int j = 1; j + 1 < hf.height; ++j)
  {
    for (int i = 1; i + 1 < hf.width; ++i)
    {
      if (!hf.isValid(i, j))
      {
        continue;
      }
      ++cells;
      bool pit = true;
      for (int dj = -1; dj <= 1 && pit; ++dj)
      {
        for (int di = -1; di <= 1; ++di)
        {
          if ((di != 0 || dj != 0) &&
            (!hf.isValid(i + di, j + dj) || hf.at(i + di, j + dj) <= hf.at(i, j)))
          {
            pit = false;
            break;
          }
        }
      }
      pits += pit ? 1 : 0;
    }
  }
  return cells > 0 ? 1000.0 * static_cast<double>(pits) / static_cast<double>(cells) : 0.0;
}

TerrainEvaluation evaluateTerrain(const Heightfield& output,
  const Heightfield& exemplar,
  const FeatureGraph* sketch)
{
  TerrainEvaluation e;
  if (sketch != nullptr)
  {
    e.ridgeFidelity = featureFidelity(output, *sketch, FeatureType::Ridge);
    e.valleyFidelity = featureFidelity(output, *sketch, FeatureType::Valley);
  }
  e.seamIndex = seamIndex(output, exemplar);
  e.slopeDistance = slopeDistance(output, exemplar);
  e.pitDensity = pitDensity(output);
  e.exemplarPitDensity = pitDensity(exemplar);
  return e;
}

Heightfield tiledBaseline(const Heightfield& ex, int width, int height)
{
  Heightfield out(width, height);
  out.cellX = ex.cellX;
  out.cellY = ex.cellY;
  for (int j = 0; j < height; ++j)
  {
    for (int i = 0; i < width; ++i)
    {
      out.at(i, j) = ex.at(i % ex.width, j % ex.height);
    }
  }
  return out;
}

Heightfield randomPatchBaseline(const Heightfield& ex,
  int width,
  int height,
  int patch,
  unsigned seed)
{
  Heightfield out(width, height);
  out.cellX = ex.cellX;
  out.cellY = ex.cellY;
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> px(0, std::max(0, ex.width - patch));
  std::uniform_int_distribution<int> py(0, std::max(0, ex.height - patch));
  for (int y0 = 0; y0 < height; y0 += patch)
  {
    for (int x0 = 0; x0 < width; x0 += patch)
    {
      const int sx = px(rng);
      const int sy = py(rng);
      for (int j = 0; j < patch && y0 + j < height; ++j)
      {
        for (int i = 0; i < patch && x0 + i < width; ++i)
        {
          out.at(x0 + i, y0 + j) =
            ex.at(std::min(ex.width - 1, sx + i), std::min(ex.height - 1, sy + j));
        }
      }
    }
  }
  return out;
}

} // namespace tsynth
