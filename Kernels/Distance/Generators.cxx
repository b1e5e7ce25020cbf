#include "Generators.h"

#include "../Core/Error.h"
#include "../Core/Grid.h"
#include "../Core/Random.h"
#include "../Features/Sketch.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <utility>

namespace tsynth
{
namespace
{

constexpr std::uint64_t kPermutationStream = 0x5045524d5554454eULL; // Perlin's table
constexpr std::size_t kPermutationSize = 256;
// Samples per cell along a poly-line segment (at most half a cell apart).
constexpr double kLineSamplesPerCell = 2.0;

std::size_t cellIndex(int col, int row, int width)
{
  return rowMajor(col, row, width);
}

std::uint32_t packColour(const std::uint8_t* p)
{
  return (static_cast<std::uint32_t>(p[0]) << 16) | (static_cast<std::uint32_t>(p[1]) << 8) | p[2];
}

// 8-connected components of `mask` (row 0 south), numbered in scan order.
std::vector<std::vector<std::int32_t>> components(const std::vector<std::uint8_t>& mask,
  int width,
  int height)
{
  std::vector<std::uint8_t> seen(mask.size(), 0);
  std::vector<std::vector<std::int32_t>> out;
  std::vector<std::int32_t> stack;
  for (std::size_t start = 0; start < mask.size(); ++start)
  {
    if (!mask[start] || seen[start])
    {
      continue;
    }
    out.emplace_back();
    stack.assign(1, static_cast<std::int32_t>(start));
    seen[start] = 1;
    while (!stack.empty())
    {
      const std::int32_t k = stack.back();
      stack.pop_back();
      out.back().push_back(k);
      const int col = k % width;
      const int row = k / width;
      for (int dy = -1; dy <= 1; ++dy)
      {
        for (int dx = -1; dx <= 1; ++dx)
        {
          const int c = col + dx;
          const int r = row + dy;
          if (c < 0 || r < 0 || c >= width || r >= height)
          {
            continue;
          }
          const std::size_t m = cellIndex(c, r, width);
          if (mask[m] && !seen[m])
          {
            seen[m] = 1;
            stack.push_back(static_cast<std::int32_t>(m));
          }
        }
      }
    }
    std::sort(out.back().begin(), out.back().end());
  }
  return out;
}

// Improved Perlin noise (Perlin 2002) in 2D with a seeded permutation.
class PerlinNoise
{
public:
  explicit PerlinNoise(std::uint64_t seed)
  {
    std::array<int, kPermutationSize> p{};
    std::iota(p.begin(), p.end(), 0);
    for (std::size_t i = kPermutationSize - 1; i > 0; --i)
    {
      const auto j = static_cast<std::size_t>(
        seededUniform(seed, kPermutationStream, i) * static_cast<double>(i + 1));
      std::swap(p[i], p[std::min(j, i)]);
    }
    for (std::size_t i = 0; i < 2 * kPermutationSize; ++i)
    {
      perm_[i] = p[i % kPermutationSize];
    }
  }

  double operator()(double x, double y) const
  {
    const double fx = std::floor(x);
    const double fy = std::floor(y);
    const int xi = static_cast<int>(static_cast<long long>(fx) & 255);
    const int yi = static_cast<int>(static_cast<long long>(fy) & 255);
    const double u = x - fx;
    const double v = y - fy;
    const double a = grad(hash(xi, yi), u, v);
    const double b = grad(hash(xi + 1, yi), u - 1.0, v);
    const double c = grad(hash(xi, yi + 1), u, v - 1.0);
    const double d = grad(hash(xi + 1, yi + 1), u - 1.0, v - 1.0);
    const double su = fade(u);
    const double sv = fade(v);
    const double bottom = a + su * (b - a);
    const double top = c + su * (d - c);
    return bottom + sv * (top - bottom);
  }

private:
  int hash(int x, int y) const
  {
    return perm_[static_cast<std::size_t>(perm_[static_cast<std::size_t>(x)] + y)];
  }
  static double fade(double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }
  // One of eight gradient directions.
  static double grad(int h, double x, double y)
  {
    switch (h & 7)
    {
      case 0:
        return x + y;
      case 1:
        return x - y;
      case 2:
        return -x + y;
      case 3:
        return -x - y;
      case 4:
        return x;
      case 5:
        return -x;
      case 6:
        return y;
      default:
        return -y;
    }
  }
  std::array<int, 2 * kPermutationSize> perm_{};
};

} // namespace

StrokeGenerators generatorsFromStrokes(const ColourImage& strokes,
  int profileCount,
  ProfileAssignment assignment,
  const ColourImage* labels)
{
  const int w = strokes.width;
  const int h = strokes.height;
  if (w < 1 || h < 1 || strokes.channels < 3)
  {
    throw Error("A generator stroke map must be a colour (RGB) image with red ridge strokes.");
  }
  if (labels && (labels->width != w || labels->height != h))
  {
    throw Error("The label image is " + std::to_string(labels->width) + "x" +
      std::to_string(labels->height) + " but the stroke map is " + std::to_string(w) + "x" +
      std::to_string(h) + "; give a label image of the stroke map's size.");
  }
  StrokeGenerators out;
  std::vector<std::uint8_t> mask(cellCount(w, h), 0);
  std::map<std::uint32_t, int> colours;
  for (int row = 0; row < h; ++row)
  {
    for (int col = 0; col < w; ++col)
    {
      const std::uint8_t* p = strokes.pixel(col, h - 1 - row);
      if (isRidgeColour(p))
      {
        mask[cellIndex(col, row, w)] = 1;
        colours.emplace(packColour(p), 0);
      }
      else if (isValleyColour(p))
      {
        ++out.valleyPixels;
      }
    }
  }
  int order = 0;
  for (auto& entry : colours)
  {
    entry.second = order++;
  }
  out.colours = order;
  const std::vector<std::vector<std::int32_t>> parts = components(mask, w, h);
  if (parts.empty())
  {
    throw Error("The stroke map has no red ridge strokes (R >= 200, G <= 80, B <= 80), so there "
                "are no generators; draw at least one.");
  }
  for (std::size_t f = 0; f < parts.size(); ++f)
  {
    DistanceFeature feature;
    for (const std::int32_t k : parts[f])
    {
      GeneratorNode node;
      node.cell = k;
      const int col = k % w;
      const int rowFromTop = h - 1 - k / w;
      if (profileCount > 0)
      {
        if (labels)
        {
          const int label = labels->pixel(col, rowFromTop)[0];
          if (label >= profileCount)
          {
            throw Error("The label image names profile " + std::to_string(label) + " at pixel (" +
              std::to_string(col) + ", " + std::to_string(rowFromTop) + ") but there are only " +
              std::to_string(profileCount) + " profiles (0 to " + std::to_string(profileCount - 1) +
              ").");
          }
          node.profile = label;
        }
        else if (assignment == ProfileAssignment::ByColour)
        {
          node.profile = colours.at(packColour(strokes.pixel(col, rowFromTop))) % profileCount;
        }
        else
        {
          node.profile = static_cast<int>(f % static_cast<std::size_t>(profileCount));
        }
      }
      feature.nodes.push_back(node);
    }
    out.features.push_back(std::move(feature));
  }
  return out;
}

namespace
{

// Cells reach half a cell beyond the first and last cell centres.
constexpr double kCellHalf = 0.5;

bool insideGrid(double x, double y, int width, int height)
{
  return x >= -kCellHalf && y >= -kCellHalf && x <= width - kCellHalf && y <= height - kCellHalf;
}

void requireFinitePoints(const GeneratorLine& line, std::size_t index)
{
  for (const Point2& p : line.points)
  {
    if (!std::isfinite(p.x) || !std::isfinite(p.y))
    {
      throw Error("A point of poly-line " + std::to_string(index) +
        " is not a finite number; the generators are damaged.");
    }
  }
}

} // namespace

std::vector<DistanceFeature> generatorsFromLines(const std::vector<GeneratorLine>& lines,
  int width,
  int height,
  int profileCount)
{
  std::vector<DistanceFeature> features;
  for (std::size_t f = 0; f < lines.size(); ++f)
  {
    const GeneratorLine& line = lines[f];
    if (!line.costs.empty() && line.costs.size() != line.points.size())
    {
      throw Error("Poly-line " + std::to_string(f) + " has " + std::to_string(line.costs.size()) +
        " costs for " + std::to_string(line.points.size()) +
        " points; give one per point or none.");
    }
    if (line.profile != kNoProfile && (line.profile < 0 || line.profile >= profileCount))
    {
      throw Error("Poly-line " + std::to_string(f) + " asks for profile " +
        std::to_string(line.profile) + " but there are " + std::to_string(profileCount) +
        " profiles.");
    }
    const int profile = line.profile != kNoProfile ? line.profile
      : profileCount > 0 ? static_cast<int>(f % static_cast<std::size_t>(profileCount))
                         : kNoProfile;
    DistanceFeature feature;
    auto add = [&](double x, double y, float cost)
    {
      if (!insideGrid(x, y, width, height))
      {
        return; // also keeps lround within int
      }
      const int col = static_cast<int>(std::lround(x));
      const int row = static_cast<int>(std::lround(y));
      if (col < 0 || row < 0 || col >= width || row >= height)
      {
        return;
      }
      const auto k = static_cast<std::int32_t>(cellIndex(col, row, width));
      if (feature.nodes.empty() || feature.nodes.back().cell != k)
      {
        feature.nodes.push_back({ k, cost, profile });
      }
    };
    const auto costAt = [&](std::size_t i)
    { return line.costs.empty() ? std::numeric_limits<float>::quiet_NaN() : line.costs[i]; };
    requireFinitePoints(line, f);
    for (std::size_t i = 0; i < line.points.size(); ++i)
    {
      const Point2 a = line.points[i];
      if (i + 1 == line.points.size())
      {
        add(a.x, a.y, costAt(i));
        break;
      }
      const Point2 b = line.points[i + 1];
      // Only the part on the grid is sampled: a segment of any length costs at
      // most the grid's diagonal.
      const auto [t0, t1] = partOnGrid(a, b, width, height); // Features/Sketch.h
      const double length = std::hypot(b.x - a.x, b.y - a.y) * (t1 - t0);
      const int steps =
        t1 < t0 ? 0 : std::max(1, static_cast<int>(std::ceil(length * kLineSamplesPerCell)));
      for (int s = 0; s < steps; ++s)
      {
        const double t = t0 + (t1 - t0) * static_cast<double>(s) / steps;
        const float cost = costAt(i) + static_cast<float>(t) * (costAt(i + 1) - costAt(i));
        add(a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), cost);
      }
    }
    // A closed or crossing line may visit a cell twice: keep its first sample.
    std::vector<GeneratorNode> unique;
    std::vector<std::int32_t> cells;
    for (const GeneratorNode& node : feature.nodes)
    {
      cells.push_back(node.cell);
    }
    std::sort(cells.begin(), cells.end());
    std::vector<std::uint8_t> taken(cells.size(), 0);
    for (const GeneratorNode& node : feature.nodes)
    {
      const auto at = static_cast<std::size_t>(
        std::lower_bound(cells.begin(), cells.end(), node.cell) - cells.begin());
      if (!taken[at])
      {
        std::fill(taken.begin() + static_cast<std::ptrdiff_t>(at),
          taken.begin() +
            static_cast<std::ptrdiff_t>(
              std::upper_bound(cells.begin(), cells.end(), node.cell) - cells.begin()),
          1);
        unique.push_back(node);
      }
    }
    feature.nodes = std::move(unique);
    if (!feature.nodes.empty())
    {
      features.push_back(std::move(feature));
    }
  }
  return features;
}

std::vector<float> fbmCosts(int width, int height, const FbmOptions& options, std::uint64_t seed)
{
  if (options.octaves < 1 || !(options.lacunarity > 1.0) || !(options.domain > 0.0) ||
    !(options.scale >= 0.0) || !(options.low <= options.high) || !std::isfinite(options.h))
  {
    throw Error("fBm costs need octaves >= 1, lacunarity > 1, a domain > 0, a scale >= 0 and "
                "low <= high.");
  }
  const PerlinNoise noise(seed);
  const std::size_t n = cellCount(width, height);
  std::vector<double> value(n);
  const double stepX = options.domain / width;
  const double stepY = options.domain / height;
  std::vector<double> amplitude(static_cast<std::size_t>(options.octaves)); // lacunarity^(-H i)
  for (std::size_t i = 0; i < amplitude.size(); ++i)
  {
    amplitude[i] = std::pow(options.lacunarity, -options.h * i);
  }
#pragma omp parallel for schedule(static)
  for (int row = 0; row < height; ++row)
  {
    for (int col = 0; col < width; ++col)
    {
      double x = (col + 0.5) * stepX; // cell centres: noise is 0 at integer points
      double y = (row + 0.5) * stepY;
      double sum = 0.0;
      for (const double a : amplitude)
      {
        sum += noise(x, y) * a;
        x *= options.lacunarity;
        y *= options.lacunarity;
      }
      value[cellIndex(col, row, width)] = sum;
    }
  }
  const auto [lo, hi] = std::minmax_element(value.begin(), value.end());
  const double span = *hi - *lo;
  std::vector<float> costs(n);
  for (std::size_t k = 0; k < n; ++k)
  {
    const double v = span > 0.0 ? (value[k] - *lo) / span : 0.0;
    costs[k] = static_cast<float>(options.scale * (options.low + (options.high - options.low) * v));
  }
  return costs;
}

std::vector<DistanceRegion> enclosedRegions(const std::vector<DistanceFeature>& features,
  int width,
  int height,
  int profile)
{
  std::vector<DistanceRegion> regions;
  for (std::size_t f = 0; f < features.size(); ++f)
  {
    const DistanceFeature& feature = features[f];
    if (feature.nodes.empty())
    {
      continue;
    }
    int c0 = width;
    int c1 = -1;
    int r0 = height;
    int r1 = -1;
    for (const GeneratorNode& node : feature.nodes)
    {
      c0 = std::min(c0, node.cell % width);
      c1 = std::max(c1, node.cell % width);
      r0 = std::min(r0, node.cell / width);
      r1 = std::max(r1, node.cell / width);
    }
    // The box one cell larger than the feature, so its border is outside.
    const int bw = c1 - c0 + 3;
    const int bh = r1 - r0 + 3;
    std::vector<std::uint8_t> state(cellCount(bw, bh), 0);
    for (const GeneratorNode& node : feature.nodes)
    {
      state[cellIndex(node.cell % width - c0 + 1, node.cell / width - r0 + 1, bw)] = 1; // wall
    }
    std::vector<std::size_t> stack = { 0 };
    state[0] = 2; // outside
    while (!stack.empty())
    {
      const std::size_t k = stack.back();
      stack.pop_back();
      const auto [col, row] = cellOf(k, bw);
      const std::array<std::array<int, 2>, 4> steps = {
        { { 1, 0 }, { -1, 0 }, { 0, 1 }, { 0, -1 } }
      };
      for (const auto& s : steps)
      {
        const int c = col + s[0];
        const int r = row + s[1];
        if (c < 0 || r < 0 || c >= bw || r >= bh)
        {
          continue;
        }
        const std::size_t m = cellIndex(c, r, bw);
        if (state[m] == 0)
        {
          state[m] = 2;
          stack.push_back(m);
        }
      }
    }
    DistanceRegion region;
    region.feature = static_cast<std::int32_t>(f);
    region.profile = profile;
    for (int row = 1; row + 1 < bh; ++row)
    {
      for (int col = 1; col + 1 < bw; ++col)
      {
        if (state[cellIndex(col, row, bw)] == 0)
        {
          region.cells.push_back(
            static_cast<std::int32_t>(cellIndex(col - 1 + c0, row - 1 + r0, width)));
        }
      }
    }
    if (!region.cells.empty())
    {
      regions.push_back(std::move(region));
    }
  }
  return regions;
}

} // namespace tsynth
