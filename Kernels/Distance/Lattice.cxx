#include "Lattice.h"

#include "../Core/Error.h"
#include "../Core/Grid.h"
#include "../Core/Random.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace tsynth
{
namespace
{

// The seeded stream of edge weights (any constant distinct from other streams).
constexpr std::uint64_t kEdgeStream = 0x4c41545449434531ULL;
// Grey value weights of eq. 4.4.
constexpr double kRedWeight = 0.3;
constexpr double kGreenWeight = 0.59;
constexpr double kBlueWeight = 0.11;

std::array<float, kDirectionCount> directionFactors(bool sqrt2Diagonals)
{
  const float diagonal = sqrt2Diagonals ? static_cast<float>(std::sqrt(2.0)) : 1.0f;
  return { 1.0f, 1.0f, 1.0f, 1.0f, diagonal, diagonal, diagonal, diagonal };
}

void requireSize(int width, int height)
{
  if (width < 1 || height < 1)
  {
    throw Error("The lattice needs at least one cell in each direction.");
  }
}

} // namespace

Lattice Lattice::random(int width, int height, const LatticeOptions& options)
{
  requireSize(width, height);
  const double mu = options.meanWeight;
  const double r = options.roughness;
  if (!(mu > 0.0) || !std::isfinite(mu) || !(r >= 0.0) || !(r < mu))
  {
    std::ostringstream message;
    message << "Edge weights need mu_w > 0 and 0 <= r < mu_w (got mu_w = " << mu << ", r = " << r
            << ").";
    throw Error(message.str());
  }
  Lattice lattice;
  lattice.width_ = width;
  lattice.height_ = height;
  lattice.meanWeight_ = mu;
  lattice.minWeight_ = mu - r;
  const std::array<float, kDirectionCount> factor = directionFactors(options.sqrt2Diagonals);
  const auto n = static_cast<std::ptrdiff_t>(lattice.size());
  const auto w = static_cast<std::ptrdiff_t>(width);
  // Edge e = 4 * (its southern/western node) + slot (E, N, NE, NW): the weight
  // of an undirected edge depends only on (seed, e), whichever way it is read.
  auto edgeWeight = [&](std::ptrdiff_t owner, int slot)
  {
    const auto e = static_cast<std::uint64_t>(4 * owner + slot);
    const double v = 2.0 * seededUniform(options.seed, kEdgeStream, e) - 1.0; // [-1, 1)
    return static_cast<float>(mu + r * v);
  };
  // Directions E, N, NE, NW (even d) are the edges a node owns; W, S, SW, SE
  // (odd d) are the next lower direction's edge of the owner, with the same
  // diagonal factor: copied, not drawn again.
  const std::array<std::ptrdiff_t, kDirectionCount> owner = { 0, -1, 0, -w, 0, -w - 1, 0, -w + 1 };
  lattice.weights_.assign(kDirectionCount * lattice.size(), 0.0f);
  float* weights = lattice.weights_.data();
#pragma omp parallel
  {
#pragma omp for schedule(static)
    for (std::ptrdiff_t k = 0; k < n; ++k)
    {
      for (std::size_t d = 0; d < kDirectionCount; d += 2)
      {
        weights[rowMajor(d, k, kDirectionCount)] =
          edgeWeight(k, static_cast<int>(d / 2)) * factor[d];
      }
    }
#pragma omp for schedule(static)
    for (std::ptrdiff_t k = 0; k < n; ++k)
    {
      for (std::size_t d = 1; d < kDirectionCount; d += 2)
      {
        const std::ptrdiff_t o = k + owner[d];
        if (o >= 0 && o < n) // edges off the grid are never read
        {
          weights[rowMajor(d, k, kDirectionCount)] = weights[rowMajor(d - 1, o, kDirectionCount)];
        }
      }
    }
  }
  lattice.findEdgeRange();
  return lattice;
}

Lattice Lattice::fromNodeWeights(int width,
  int height,
  std::vector<float> weights,
  bool sqrt2Diagonals)
{
  requireSize(width, height);
  Lattice lattice;
  lattice.width_ = width;
  lattice.height_ = height;
  if (weights.size() != lattice.size())
  {
    throw Error("The edge-weight image must have one value per lattice cell.");
  }
  double sum = 0.0;
  double lowest = weights.empty() ? 1.0 : weights.front();
  for (const float w : weights)
  {
    if (!(w > 0.0f) || !std::isfinite(w))
    {
      throw Error("Edge weights from an image must be finite and positive.");
    }
    sum += w;
    lowest = std::min(lowest, static_cast<double>(w));
  }
  lattice.meanWeight_ = sum / static_cast<double>(weights.size());
  lattice.minWeight_ = lowest;
  const std::array<float, kDirectionCount> factor = directionFactors(sqrt2Diagonals);
  lattice.weights_.resize(kDirectionCount * weights.size());
  for (std::size_t k = 0; k < weights.size(); ++k)
  {
    for (std::size_t d = 0; d < kDirectionCount; ++d)
    {
      lattice.weights_[kDirectionCount * k + d] = weights[k] * factor[d];
    }
  }
  lattice.findEdgeRange();
  return lattice;
}

void Lattice::findEdgeRange()
{
  float least = std::numeric_limits<float>::infinity();
  float greatest = 0.0f;
#pragma omp parallel for schedule(static) reduction(min : least) reduction(max : greatest)
  for (int row = 0; row < height_; ++row)
  {
    for (int col = 0; col < width_; ++col)
    {
      const float* w = weights(rowMajor(col, row, width_));
      for (std::size_t d = 0; d < kDirectionCount; ++d)
      {
        const int c = col + kDirectionDx[d];
        const int r = row + kDirectionDy[d];
        if (c >= 0 && r >= 0 && c < width_ && r < height_)
        {
          least = std::min(least, w[d]);
          greatest = std::max(greatest, w[d]);
        }
      }
    }
  }
  leastEdge_ = least;
  greatestEdge_ = greatest;
}

std::vector<float> greyToWeights(const std::uint8_t* pixels,
  int width,
  int height,
  int channels,
  double low,
  double high)
{
  if (!(low > 0.0) || !(high >= low) || !std::isfinite(high))
  {
    throw Error("The edge-weight range needs 0 < low <= high.");
  }
  const std::size_t w = static_cast<std::size_t>(width);
  const std::size_t h = static_cast<std::size_t>(height);
  const std::size_t c = static_cast<std::size_t>(channels);
  std::vector<double> grey(w * h);
  for (std::size_t row = 0; row < h; ++row)
  {
    for (std::size_t col = 0; col < w; ++col)
    {
      const std::uint8_t* p = pixels + ((h - 1 - row) * w + col) * c; // row 0 south
      grey[row * w + col] =
        c >= 3 ? kRedWeight * p[0] + kGreenWeight * p[1] + kBlueWeight * p[2] : p[0];
    }
  }
  const auto [lo, hi] = std::minmax_element(grey.begin(), grey.end());
  const double span = *hi - *lo;
  std::vector<float> weights(grey.size());
  for (std::size_t k = 0; k < grey.size(); ++k)
  {
    const double v = span > 0.0 ? (grey[k] - *lo) / span : 0.0;
    weights[k] = static_cast<float>(low + (high - low) * v);
  }
  return weights;
}

} // namespace tsynth
