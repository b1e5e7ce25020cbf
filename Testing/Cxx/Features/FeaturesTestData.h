// Helpers shared by the Features and Metrics tests: ridge lines with a known answer (PPA and the
// profiles along its chains), and analytic and seeded rough surfaces (cross-sections, legibility).
#pragma once

#include "Core/Constants.h"
#include "Core/Heightfield.h"
#include "Core/Random.h"
#include "Features/FeatureGraph.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

namespace tsynth::test::features
{

inline double segmentDistance(const Point2& p, const Point2& a, const Point2& b)
{
  const double dx = b.x - a.x;
  const double dy = b.y - a.y;
  const double len2 = dx * dx + dy * dy;
  double t = len2 > 0 ? ((p.x - a.x) * dx + (p.y - a.y) * dy) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(p.x - (a.x + t * dx), p.y - (a.y + t * dy));
}

inline double polylineDistance(const Point2& p, const std::vector<Point2>& line)
{
  double d = std::numeric_limits<double>::infinity();
  for (std::size_t k = 1; k < line.size(); ++k)
  {
    d = std::min(d, segmentDistance(p, line[k - 1], line[k]));
  }
  return d;
}

// Ridge lines with a known answer: a Y junction and a closed loop.
struct KnownRidges
{
  std::vector<std::vector<Point2>> lines;
  Point2 junction{ 128, 128 };
  KnownRidges()
  {
    lines.push_back({ { 128, 20 }, { 128, 128 } });  // trunk, pointing south
    lines.push_back({ { 128, 128 }, { 50, 230 } });  // left arm
    lines.push_back({ { 128, 128 }, { 210, 230 } }); // right arm
    std::vector<Point2> ring;
    for (int k = 0; k <= 72; ++k)
    {
      ring.push_back(
        { 55 + 32 * std::cos(2 * kPi * k / 72), 62 + 32 * std::sin(2 * kPi * k / 72) });
    }
    lines.push_back(ring);
  }
  double distance(const Point2& p) const
  {
    double d = std::numeric_limits<double>::infinity();
    for (const auto& l : lines)
    {
      d = std::min(d, polylineDistance(p, l));
    }
    return d;
  }
  // Gaussian ridges of 300 m, sigma 6 cells, on a gentle tilt; 30 m cells.
  Heightfield surface(double sign) const
  {
    Heightfield hf(256, 256);
    hf.cellX = hf.cellY = 30.0;
    for (int j = 0; j < hf.height; ++j)
    {
      for (int i = 0; i < hf.width; ++i)
      {
        const double d = distance({ static_cast<double>(i), static_cast<double>(j) });
        const double z = 1000.0 + 0.4 * i + 300.0 * std::exp(-d * d / (2.0 * 36.0));
        hf.at(i, j) = static_cast<float>(sign * z);
      }
    }
    return hf;
  }
  // Cells on the true lines (sampled every quarter cell).
  std::vector<Point2> truthCells() const
  {
    std::vector<Point2> cells;
    for (const auto& l : lines)
    {
      for (std::size_t k = 1; k < l.size(); ++k)
      {
        const double len = std::hypot(l[k].x - l[k - 1].x, l[k].y - l[k - 1].y);
        for (double t = 0; t <= len; t += 0.25)
        {
          cells.push_back({ std::round(l[k - 1].x + (l[k].x - l[k - 1].x) * t / len),
            std::round(l[k - 1].y + (l[k].y - l[k - 1].y) * t / len) });
        }
      }
    }
    return cells;
  }
};

inline Heightfield surface(int w, int h, const std::function<double(int, int)>& f)
{
  Heightfield hf(w, h);
  hf.cellX = hf.cellY = 30.0;
  hf.cellSizeKnown = true;
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      hf.at(i, j) = static_cast<float>(f(i, j));
    }
  }
  return hf;
}

// Smooth random relief: a sum of seeded sines of wavelengths 8 to 64 cells,
// each `amplitude` metres.
inline Heightfield rough(int w, int h, double amplitude, std::uint64_t seed)
{
  return surface(w,
    h,
    [&](int i, int j)
    {
      double z = 0.0;
      for (int k = 0; k < 24; ++k)
      {
        const double wave = 8.0 * std::pow(2.0, 3.0 * seededUniform(seed, 1, k));
        const double a = 2.0 * kPi * seededUniform(seed, 2, k);
        const double p = 2.0 * kPi * seededUniform(seed, 3, k);
        z += amplitude * std::sin(2.0 * kPi * (i * std::cos(a) + j * std::sin(a)) / wave + p);
      }
      return z;
    });
}

} // namespace tsynth::test::features
