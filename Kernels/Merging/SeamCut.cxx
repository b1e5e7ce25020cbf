#include "SeamCut.h"

#include "../Core/Grid.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tsynth
{

std::vector<SeamConstraint> buildSeamConstraints(int width,
  int height,
  const std::uint8_t* oldMask,
  const std::uint8_t* newMask,
  const std::uint8_t* core)
{
  const std::size_t n = cellCount(std::max(width, 0), std::max(height, 0));
  std::vector<SeamConstraint> out(n, SeamConstraint::Outside);
  auto oldOnly = [&](std::size_t k) { return oldMask[k] && !newMask[k]; };
  auto newOnly = [&](std::size_t k) { return newMask[k] && !oldMask[k]; };
  for (int j = 0; j < height; ++j)
  {
    for (int i = 0; i < width; ++i)
    {
      const std::size_t k = rowMajor(i, j, width);
      if (!oldMask[k] || !newMask[k])
      {
        continue;
      }
      bool nextToOld = false;
      bool nextToNew = false;
      const int di[4] = { 1, -1, 0, 0 };
      const int dj[4] = { 0, 0, 1, -1 };
      for (int d = 0; d < 4; ++d)
      {
        const int ni = i + di[d];
        const int nj = j + dj[d];
        if (ni < 0 || nj < 0 || ni >= width || nj >= height)
        {
          continue;
        }
        const std::size_t m = rowMajor(ni, nj, width);
        nextToOld = nextToOld || oldOnly(m);
        nextToNew = nextToNew || newOnly(m);
      }
      if (core && core[k])
      {
        out[k] = SeamConstraint::ForceNew;
      }
      else if (nextToOld)
      {
        out[k] = SeamConstraint::ForceOld;
      }
      else if (nextToNew)
      {
        out[k] = SeamConstraint::ForceNew;
      }
      else
      {
        out[k] = SeamConstraint::Free;
      }
    }
  }
  return out;
}

namespace
{

// Gradient of f along one axis at k: central where both neighbours are finite,
// one-sided at the edge of the data, 0 where the pixel is isolated.
inline double axisGradient(const float* f,
  std::size_t k,
  std::ptrdiff_t step,
  bool hasMinus,
  bool hasPlus,
  double inv)
{
  const bool plus = hasPlus && std::isfinite(f[k + step]);
  const bool minus = hasMinus && std::isfinite(f[k - step]);
  if (plus && minus)
  {
    return 0.5 * inv * (static_cast<double>(f[k + step]) - f[k - step]);
  }
  if (plus)
  {
    return inv * (static_cast<double>(f[k + step]) - f[k]);
  }
  if (minus)
  {
    return inv * (static_cast<double>(f[k]) - f[k - step]);
  }
  return 0.0;
}

} // namespace

void SeamCut::computeWeights(int width,
  int height,
  const float* oldZ,
  const float* newZ,
  const std::vector<SeamConstraint>& constraints,
  double cellX,
  double cellY,
  const SeamCutOptions& options,
  SeamWeights& out)
{
  const std::size_t n = cellCount(width, height);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  out.wx.assign(n, nan);
  out.wy.assign(n, nan);
  const double invX = 1.0 / cellX;
  const double invY = 1.0 / cellY;
  auto inOverlap = [&](std::size_t k) { return constraints[k] != SeamConstraint::Outside; };
  // First pass: the Kwatra denominators, kept in wx / wy until eps is known
  // (no scratch arrays); the second pass turns them into the weights.
  double denSum = 0.0;
  std::size_t edges = 0;
  for (int j = 0; j < height; ++j)
  {
    for (int i = 0; i < width; ++i)
    {
      const std::size_t s = rowMajor(i, j, width);
      if (!inOverlap(s))
      {
        continue;
      }
      if (i + 1 < width && inOverlap(s + 1))
      {
        const std::size_t t = s + 1;
        out.wx[s] = std::abs(axisGradient(oldZ, s, 1, i > 0, true, invX)) +
          std::abs(axisGradient(oldZ, t, 1, true, i + 2 < width, invX)) +
          std::abs(axisGradient(newZ, s, 1, i > 0, true, invX)) +
          std::abs(axisGradient(newZ, t, 1, true, i + 2 < width, invX));
        denSum += out.wx[s];
        ++edges;
      }
      if (j + 1 < height && inOverlap(s + width))
      {
        const std::size_t t = s + width;
        out.wy[s] = std::abs(axisGradient(oldZ, s, width, j > 0, true, invY)) +
          std::abs(axisGradient(oldZ, t, width, true, j + 2 < height, invY)) +
          std::abs(axisGradient(newZ, s, width, j > 0, true, invY)) +
          std::abs(axisGradient(newZ, t, width, true, j + 2 < height, invY));
        denSum += out.wy[s];
        ++edges;
      }
    }
  }
  out.epsilon = std::max(options.absoluteEpsilon,
    edges > 0 ? options.relativeEpsilon * denSum / static_cast<double>(edges) : 0.0);
  auto mismatch = [&](std::size_t k) { return std::abs(static_cast<double>(oldZ[k]) - newZ[k]); };
  for (int j = 0; j < height; ++j)
  {
    for (int i = 0; i < width; ++i)
    {
      const std::size_t s = rowMajor(i, j, width);
      for (int axis = 0; axis < 2; ++axis)
      {
        double& w = (axis == 0 ? out.wx : out.wy)[s];
        if (std::isnan(w))
        {
          continue;
        }
        const double numerator = mismatch(s) + mismatch(axis == 0 ? s + 1 : s + width);
        w = options.gradientTerm ? numerator / (w + out.epsilon) : numerator;
      }
    }
  }
}

const SeamCutResult& SeamCut::cut(int width,
  int height,
  const float* oldZ,
  const float* newZ,
  const SeamConstraint* constraints,
  double cellX,
  double cellY,
  const SeamCutOptions& options)
{
  width = std::max(width, 0);
  height = std::max(height, 0);
  const std::size_t n = cellCount(width, height);
  constraints_.resize(n);
  for (std::size_t k = 0; k < n; ++k)
  {
    const bool bothValid = std::isfinite(oldZ[k]) && std::isfinite(newZ[k]);
    const SeamConstraint c = constraints ? constraints[k] : SeamConstraint::Free;
    constraints_[k] = bothValid ? c : SeamConstraint::Outside;
  }
  computeWeights(width, height, oldZ, newZ, constraints_, cellX, cellY, options, weights_);

  // Forced pixels are not graph nodes: an edge from a free pixel to a forced
  // one becomes a terminal capacity of the free pixel, an edge between two
  // forced pixels of different sides a constant. Same min cut, no infinities.
  // The flow runs on the bounding box of the free pixels only (the overlap is
  // often a small part of the window).
  int bx0 = width, by0 = height, bx1 = 0, by1 = 0;
  for (int j = 0; j < height; ++j)
  {
    for (int i = 0; i < width; ++i)
    {
      if (constraints_[rowMajor(i, j, width)] == SeamConstraint::Free)
      {
        bx0 = std::min(bx0, i);
        by0 = std::min(by0, j);
        bx1 = std::max(bx1, i + 1);
        by1 = std::max(by1, j + 1);
      }
    }
  }
  const int bw = std::max(bx1 - bx0, 0);
  const int bh = std::max(by1 - by0, 0);
  auto node = [&](int i, int j) { return (j - by0) * bw + (i - bx0); };
  flow_.reset(bw, bh);
  double constant = 0.0;
  for (int j = 0; j < height; ++j)
  {
    for (int i = 0; i < width; ++i)
    {
      const std::size_t s = rowMajor(i, j, width);
      for (int axis = 0; axis < 2; ++axis)
      {
        const double w = axis == 0 ? weights_.wx[s] : weights_.wy[s];
        if (std::isnan(w))
        {
          continue;
        }
        const std::size_t t = axis == 0 ? s + 1 : s + width;
        const SeamConstraint cs = constraints_[s];
        const SeamConstraint ct = constraints_[t];
        const bool freeS = cs == SeamConstraint::Free;
        const bool freeT = ct == SeamConstraint::Free;
        if (freeS && freeT)
        {
          flow_.setEdge(node(i, j), axis == 0 ? GridMaxFlow::PlusX : GridMaxFlow::PlusY, w, w);
        }
        else if (freeS || freeT)
        {
          const bool forcedNew = (freeS ? ct : cs) == SeamConstraint::ForceNew;
          const int f = freeS ? node(i, j) : node(axis == 0 ? i + 1 : i, axis == 0 ? j : j + 1);
          flow_.addTerminal(f, forcedNew ? w : 0.0, forcedNew ? 0.0 : w);
        }
        else if (cs != ct)
        {
          constant += w;
        }
      }
    }
  }
  result_.flow = flow_.solve() + constant;

  result_.width = width;
  result_.height = height;
  result_.takeNew.assign(n, 0);
  result_.seam.assign(n, 0);
  result_.cost = 0.0;
  result_.cutEdges = 0;
  for (int j = 0; j < height; ++j)
  {
    for (int i = 0; i < width; ++i)
    {
      const std::size_t k = rowMajor(i, j, width);
      const SeamConstraint c = constraints_[k];
      result_.takeNew[k] = c == SeamConstraint::ForceNew ||
        (c == SeamConstraint::Free && flow_.sourceSide(node(i, j)));
    }
  }
  for (std::size_t s = 0; s < n; ++s)
  {
    for (int axis = 0; axis < 2; ++axis)
    {
      const double w = axis == 0 ? weights_.wx[s] : weights_.wy[s];
      const std::size_t t = axis == 0 ? s + 1 : s + width;
      if (std::isnan(w) || result_.takeNew[s] == result_.takeNew[t])
      {
        continue;
      }
      result_.cost += w;
      ++result_.cutEdges;
      result_.seam[s] = 1;
      result_.seam[t] = 1;
    }
  }
  return result_;
}

} // namespace tsynth
