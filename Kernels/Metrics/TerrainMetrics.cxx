#include "TerrainMetrics.h"

#include "../Core/Constants.h"
#include "../Core/Random.h"
#include "../Features/Profiles.h"

#include <algorithm>
#include <cmath>
#include <utility>

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

namespace
{

// The seam index compares the tails of the curvature distributions.
constexpr double kSeamPercentile = 0.999;

// True if every valid height of every exemplar is the same.
bool flat(const std::vector<const Heightfield*>& exemplars)
{
  bool any = false;
  float lo = 0.0f;
  float hi = 0.0f;
  for (const Heightfield* x : exemplars)
  {
    const HeightRange r = computeHeightRange(*x);
    if (r.validCells == 0)
    {
      continue;
    }
    lo = any ? std::min(lo, r.min) : r.min;
    hi = any ? std::max(hi, r.max) : r.max;
    any = true;
  }
  return !any || lo == hi;
}

// Ridge and valley fidelity, NaN with a note where nothing of the kind is sketched.
void fidelities(const Heightfield& output, const FeatureGraph* sketch, TerrainEvaluation& e)
{
  const std::pair<FeatureType, double*> kinds[] = { { FeatureType::Ridge, &e.ridgeFidelity },
    { FeatureType::Valley, &e.valleyFidelity } };
  for (const auto& [type, field] : kinds)
  {
    const bool ridge = type == FeatureType::Ridge;
    const std::string name = ridge ? "ridgeFidelity" : "valleyFidelity";
    const double f = sketch != nullptr ? featureFidelity(output, *sketch, type) : -1.0;
    if (f >= 0.0)
    {
      *field = f;
    }
    else
    {
      e.notes[name] = sketch == nullptr ? "no sketch given"
                                        : std::string("no ") + (ridge ? "ridge" : "valley") +
          " is sketched far enough from the edges";
    }
  }
}

// |Laplacian| (cell-size aware, 1/m) at every cell whose four neighbours are valid.
void appendLaplacians(const Heightfield& hf, std::vector<float>& v)
{
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
}

// Slope-angle counts in 0.1 degree bins, and their sum and count.
void addSlopes(const Heightfield& hf, std::vector<double>& h, double& sum, double& n)
{
  h.resize(900, 0.0);
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
      const double deg = std::atan(std::hypot(p, q)) * 180.0 / kPi;
      h[std::min<std::size_t>(899, static_cast<std::size_t>(deg * 10.0))] += 1.0;
      sum += deg;
      n += 1.0;
    }
  }
}

} // namespace

double laplacianPercentile(const Heightfield& hf, double fraction)
{
  std::vector<float> v;
  appendLaplacians(hf, v);
  return percentile(std::move(v), fraction);
}

double seamIndex(const Heightfield& output, const std::vector<const Heightfield*>& exemplars)
{
  std::vector<float> v;
  for (const Heightfield* e : exemplars)
  {
    appendLaplacians(*e, v);
  }
  if (v.empty())
  {
    return std::numeric_limits<double>::quiet_NaN();
  }
  const double reference = percentile(std::move(v), kSeamPercentile);
  std::vector<float> own;
  appendLaplacians(output, own);
  if (!(reference > 0.0) || own.empty())
  {
    return std::numeric_limits<double>::quiet_NaN(); // a flat exemplar: no scale
  }
  return percentile(std::move(own), kSeamPercentile) / reference;
}

double seamIndex(const Heightfield& output, const Heightfield& exemplar)
{
  return seamIndex(output, std::vector<const Heightfield*>{ &exemplar });
}

double slopeDistance(const Heightfield& output, const std::vector<const Heightfield*>& exemplars)
{
  std::vector<double> ho, he;
  double so = 0.0, no = 0.0, se = 0.0, ne = 0.0;
  addSlopes(output, ho, so, no);
  for (const Heightfield* e : exemplars)
  {
    addSlopes(*e, he, se, ne);
  }
  if (no == 0.0 || ne == 0.0)
  {
    return std::numeric_limits<double>::quiet_NaN();
  }
  // W1 = integral of |CDF_o - CDF_e|.
  double co = 0.0;
  double ce = 0.0;
  double w1 = 0.0;
  for (std::size_t b = 0; b < ho.size(); ++b)
  {
    co += ho[b] / no;
    ce += he[b] / ne;
    w1 += std::abs(co - ce) * 0.1;
  }
  const double mean = se / ne;
  return mean > 0 ? w1 / mean : std::numeric_limits<double>::quiet_NaN();
}

double slopeDistance(const Heightfield& output, const Heightfield& exemplar)
{
  return slopeDistance(output, std::vector<const Heightfield*>{ &exemplar });
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
  return cells > 0 ? 1000.0 * static_cast<double>(pits) / static_cast<double>(cells)
                   : std::numeric_limits<double>::quiet_NaN();
}

TerrainEvaluation evaluateTerrain(const Heightfield& output,
  const std::vector<const Heightfield*>& exemplars,
  const FeatureGraph* sketch)
{
  TerrainEvaluation e;
  fidelities(output, sketch, e);
  e.seamIndex = seamIndex(output, exemplars);
  if (std::isnan(e.seamIndex))
  {
    e.notes["seamIndex"] = flat(exemplars)
      ? "the exemplars are flat: no curvature to compare the seams with"
      : "no cell with four valid neighbours to measure curvature on";
  }
  e.slopeDistance = slopeDistance(output, exemplars);
  if (std::isnan(e.slopeDistance))
  {
    e.notes["slopeDistance"] = flat(exemplars)
      ? "the exemplars are flat: no mean slope to compare with"
      : "no cell with valid neighbours to measure a slope on";
  }
  e.pitDensity = pitDensity(output);
  if (std::isnan(e.pitDensity))
  {
    e.notes["pitDensity"] = "no valid interior cell";
  }
  // Pits per 1000 cells over all exemplars together.
  double pits = 0.0;
  double cells = 0.0;
  for (const Heightfield* x : exemplars)
  {
    const double density = pitDensity(*x);
    const double n = static_cast<double>(x->validCount());
    pits += std::isnan(density) ? 0.0 : density * n;
    cells += std::isnan(density) ? 0.0 : n;
  }
  e.exemplarPitDensity = cells > 0 ? pits / cells : TerrainEvaluation::kNaN;
  return e;
}

TerrainEvaluation evaluateTerrain(const Heightfield& output,
  const Heightfield& exemplar,
  const FeatureGraph* sketch)
{
  return evaluateTerrain(output, std::vector<const Heightfield*>{ &exemplar }, sketch);
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
  // Streams of the baseline's seed (Random.h): a patch's source column, row.
  constexpr std::uint64_t kStreamSourceX = 1;
  constexpr std::uint64_t kStreamSourceY = 2;
  const std::uint64_t columns = static_cast<std::uint64_t>(std::max(0, ex.width - patch)) + 1;
  const std::uint64_t rows = static_cast<std::uint64_t>(std::max(0, ex.height - patch)) + 1;
  std::uint64_t placed = 0;
  for (int y0 = 0; y0 < height; y0 += patch)
  {
    for (int x0 = 0; x0 < width; x0 += patch, ++placed)
    {
      const int sx = static_cast<int>(seededIndex(seed, kStreamSourceX, placed, columns));
      const int sy = static_cast<int>(seededIndex(seed, kStreamSourceY, placed, rows));
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
