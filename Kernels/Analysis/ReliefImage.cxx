#include "ReliefImage.h"

#include "../Core/Grid.h"

#include <algorithm>
#include <cmath>

namespace tsynth
{
namespace
{

// Nodata in a flat blue-grey, apart from any land colour.
constexpr std::array<double, 3> kNodataColour = { 0.55, 0.60, 0.68 };
// The tint is lit from a quarter (full shadow) to 1.1 times (full light) its colour.
constexpr double kShadowLight = 0.25;
constexpr double kLitLight = 0.85;

} // namespace

std::array<double, 3> terrainColour(double t)
{
  // Lowland green, upland tan, rock brown, snow white.
  static const std::array<std::array<double, 4>, 6> stops = { {
    { 0.00, 0.20, 0.42, 0.26 },
    { 0.20, 0.46, 0.62, 0.34 },
    { 0.45, 0.80, 0.74, 0.50 },
    { 0.70, 0.62, 0.50, 0.40 },
    { 0.88, 0.78, 0.75, 0.72 },
    { 1.00, 0.98, 0.98, 0.98 },
  } };
  t = std::clamp(t, 0.0, 1.0);
  for (std::size_t s = 1; s < stops.size(); ++s)
  {
    if (t <= stops[s][0])
    {
      const auto& a = stops[s - 1];
      const auto& b = stops[s];
      const double u = (t - a[0]) / (b[0] - a[0]);
      return { a[1] + u * (b[1] - a[1]), a[2] + u * (b[2] - a[2]), a[3] + u * (b[3] - a[3]) };
    }
  }
  return { stops.back()[1], stops.back()[2], stops.back()[3] };
}

namespace
{

// The picture's pixels, first row at the top, from a colour per valid cell.
template<typename Colour>
std::vector<std::uint8_t> paint(const Heightfield& hf, Colour colour)
{
  std::vector<std::uint8_t> rgb(hf.size() * 3);
  for (int r = 0; r < hf.height; ++r)
  {
    const int j = hf.height - 1 - r;
    for (int i = 0; i < hf.width; ++i)
    {
      const std::size_t k = hf.index(i, j);
      const std::array<double, 3> c = hf.isValid(k) ? colour(k) : kNodataColour;
      const std::size_t o = rowMajor(i, r, hf.width) * 3;
      for (std::size_t ch = 0; ch < 3; ++ch)
      {
        rgb[o + ch] = static_cast<std::uint8_t>(std::lround(std::clamp(c[ch], 0.0, 1.0) * 255.0));
      }
    }
  }
  return rgb;
}

} // namespace

std::vector<std::uint8_t> renderGreyRelief(const Heightfield& hf, const ShadedRelief& relief)
{
  return paint(hf,
    [&](std::size_t k)
    {
      const double g = relief.shade[k];
      return std::array<double, 3>{ g, g, g };
    });
}

std::vector<std::uint8_t> renderRelief(const Heightfield& hf, const ShadedRelief& relief)
{
  const HeightRange range = computeHeightRange(hf);
  const double span = range.max > range.min ? range.max - range.min : 1.0;
  return paint(hf,
    [&](std::size_t k)
    {
      std::array<double, 3> c = terrainColour((hf.z[k] - range.min) / span);
      const double light = kShadowLight + kLitLight * relief.shade[k];
      for (double& v : c)
      {
        v *= light;
      }
      return c;
    });
}

} // namespace tsynth
