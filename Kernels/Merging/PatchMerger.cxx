#include "PatchMerger.h"

#include "../Core/Error.h"
#include "../Core/Grid.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tsynth
{

MergeMode parseMergeMode(const std::string& name)
{
  return static_cast<MergeMode>(choicesOf(kMergeModeWords).valueOf(name, "The merge mode"));
}

const char* mergeModeName(MergeMode mode)
{
  return choicesOf(kMergeModeWords).wordOf(static_cast<int>(mode), "Merge mode");
}

namespace
{

constexpr double NaN = std::numeric_limits<double>::quiet_NaN();
constexpr int Di[4] = { 1, -1, 0, 0 };
constexpr int Dj[4] = { 0, 0, 1, -1 };

// Per-cell differences of a and b along an axis (metres per cell), with the
// same stencil for both so identical surfaces give identical values: central
// where both have both neighbours, one-sided at the edge of their data, else 0.
std::pair<double, double> gradientPair(const std::vector<float>& a,
  const std::vector<float>& b,
  int w,
  int h,
  int i,
  int j,
  int axis)
{
  const std::size_t k = rowMajor(i, j, w);
  const std::ptrdiff_t step = axis == 0 ? 1 : w;
  const bool hasPlus = axis == 0 ? i + 1 < w : j + 1 < h;
  const bool hasMinus = axis == 0 ? i > 0 : j > 0;
  const bool plus = hasPlus && std::isfinite(a[k + step]) && std::isfinite(b[k + step]);
  const bool minus = hasMinus && std::isfinite(a[k - step]) && std::isfinite(b[k - step]);
  auto diff = [&](const std::vector<float>& f)
  {
    if (plus && minus)
      return 0.5 * (static_cast<double>(f[k + step]) - f[k - step]);
    if (plus)
      return static_cast<double>(f[k + step]) - f[k];
    if (minus)
      return static_cast<double>(f[k]) - f[k - step];
    return 0.0;
  };
  return { diff(a), diff(b) };
}

// The window cell of a seam point, whose coordinates are whole cell numbers
// held as float.
std::size_t seamCell(float x, float y, int width)
{
  return rowMajor(static_cast<int>(x), static_cast<int>(y), width);
}

} // namespace

MergeResult PatchMerger::prepare(const Heightfield& terrain,
  const std::vector<std::uint8_t>& filled,
  const Heightfield& patch,
  int x0,
  int y0,
  const std::vector<std::uint8_t>* core,
  const SeamCutOptions& options,
  const MergeResult* given)
{
  if (filled.size() != terrain.size())
  {
    throw Error("The filled mask must have one entry per terrain cell.");
  }
  if (core && core->size() != patch.size())
  {
    throw Error("The protected-core mask must have one entry per patch cell.");
  }
  if (patch.width <= 0 || patch.height <= 0)
  {
    throw Error("The patch is empty.");
  }
  if (terrain.cellSizeKnown && patch.cellSizeKnown &&
    (std::abs(patch.cellX - terrain.cellX) > 1e-3 * terrain.cellX ||
      std::abs(patch.cellY - terrain.cellY) > 1e-3 * terrain.cellY))
  {
    throw Error("The patch and the terrain have different cell sizes; resample the patch first.");
  }
  const int wx0 = std::max(x0, 0);
  const int wy0 = std::max(y0, 0);
  const int wx1 = std::min(x0 + patch.width, terrain.width);
  const int wy1 = std::min(y0 + patch.height, terrain.height);
  if (wx1 <= wx0 || wy1 <= wy0)
  {
    throw Error("The patch placed at (" + std::to_string(x0) + ", " + std::to_string(y0) +
      ") lies entirely outside the terrain.");
  }
  cellX_ = terrain.cellX;
  cellY_ = terrain.cellY;
  fx0_ = std::max(wx0 - 1, 0);
  fy0_ = std::max(wy0 - 1, 0);
  fw_ = std::min(wx1 + 1, terrain.width) - fx0_;
  fh_ = std::min(wy1 + 1, terrain.height) - fy0_;
  const std::size_t n = cellCount(fw_, fh_);
  const float fnan = std::numeric_limits<float>::quiet_NaN();
  old_.assign(n, fnan);
  new_.assign(n, fnan);
  oldMask_.assign(n, 0);
  newMask_.assign(n, 0);
  coreMask_.assign(n, 0);
  for (int j = 0; j < fh_; ++j)
  {
    for (int i = 0; i < fw_; ++i)
    {
      const std::size_t k = rowMajor(i, j, fw_);
      const int ti = fx0_ + i;
      const int tj = fy0_ + j;
      const std::size_t tk = terrain.index(ti, tj);
      if (filled[tk] && terrain.isValid(tk) && std::isfinite(terrain.z[tk]))
      {
        old_[k] = terrain.z[tk];
        oldMask_[k] = 1;
      }
      const int pi = ti - x0;
      const int pj = tj - y0;
      if (pi >= 0 && pj >= 0 && pi < patch.width && pj < patch.height)
      {
        const std::size_t pk = patch.index(pi, pj);
        if (patch.isValid(pk) && std::isfinite(patch.z[pk]))
        {
          new_[k] = patch.z[pk];
          newMask_[k] = 1;
          coreMask_[k] = core && (*core)[pk];
        }
      }
    }
  }
  MergeResult result;
  result.x0 = wx0;
  result.y0 = wy0;
  result.width = wx1 - wx0;
  result.height = wy1 - wy0;
  if (given != nullptr &&
    (given->x0 != wx0 || given->y0 != wy0 || given->width != result.width ||
      given->height != result.height ||
      given->takeNew.size() != cellCount(result.width, result.height) ||
      given->seam.size() != given->takeNew.size()))
  {
    throw Error("The given cut belongs to another placement of the patch.");
  }
  const SeamCutResult* cut = nullptr;
  if (given == nullptr)
  {
    const std::vector<SeamConstraint> constraints = buildSeamConstraints(
      fw_, fh_, oldMask_.data(), newMask_.data(), core ? coreMask_.data() : nullptr);
    cut =
      &cut_.cut(fw_, fh_, old_.data(), new_.data(), constraints.data(), cellX_, cellY_, options);
    result.cutCost = cut->cost;
    result.cutEdges = cut->cutEdges;
    result.normalisedCost = cut->normalisedCost();
  }
  else
  {
    result.cutCost = given->cutCost;
    result.cutEdges = given->cutEdges;
    result.normalisedCost = given->normalisedCost;
  }

  side_.assign(n, 0);
  result.takeNew.assign(cellCount(result.width, result.height), 0);
  result.seam.assign(result.takeNew.size(), 0);
  for (int j = 0; j < fh_; ++j)
  {
    for (int i = 0; i < fw_; ++i)
    {
      const std::size_t k = rowMajor(i, j, fw_);
      const int ri = fx0_ + i - wx0;
      const int rj = fy0_ + j - wy0;
      const bool inWindow = ri >= 0 && rj >= 0 && ri < result.width && rj < result.height;
      const std::size_t rk = inWindow ? rowMajor(ri, rj, result.width) : 0;
      // The frame around the window holds no patch cells, so a given cut (known
      // on the window only) decides every cell that matters.
      const bool cutNew = cut != nullptr ? cut->takeNew[k] != 0 : inWindow && given->takeNew[rk];
      const bool isNew = newMask_[k] && (!oldMask_[k] || cutNew);
      side_[k] = isNew ? 2 : (oldMask_[k] ? 1 : 0);
      if (inWindow)
      {
        result.takeNew[rk] = isNew;
        result.seam[rk] = cut != nullptr ? cut->seam[k] : given->seam[rk];
        result.overlapCells += oldMask_[k] && newMask_[k];
        result.newCells += isNew;
      }
    }
  }
  return result;
}

MergeResult PatchMerger::seamCost(const Heightfield& terrain,
  const std::vector<std::uint8_t>& filled,
  const Heightfield& patch,
  int x0,
  int y0,
  const std::vector<std::uint8_t>* core,
  const SeamCutOptions& options)
{
  return prepare(terrain, filled, patch, x0, y0, core, options, nullptr);
}

// Shepard interpolation (Shepard 1968, as in Tasse 3.5) of the seam values to
// every new cell, times a C1 fall-off that reaches 0 at the radius: the
// normalised weights alone sum to 1 up to the radius and 0 beyond, a step.
//
// A point at distance d >= radius has weight exactly 0, and d >= |dx|, |dy|, so
// only points with |dx| < radius and |dy| < radius are visited: the seam points
// come in row order, so those with |dy| < radius are one index range per row,
// gathered once per row; cells farther than the radius from every point of the
// range in x are skipped without a loop.
template<int V>
void PatchMerger::shepard(double radius, double power, std::vector<double>& out)
{
  const std::size_t n = cellCount(fw_, fh_);
  out.assign(n * V, 0.0);
  const std::size_t points = seamX_.size();
  if (points == 0)
    return;
  const float r = static_cast<float>(radius);
  const float r2 = r * r;
  pointAt_.assign(n, -1);
  for (std::size_t s = 0; s < points; ++s)
  {
    pointAt_[seamCell(seamX_[s], seamY_[s], fw_)] = static_cast<std::int32_t>(s);
  }
  bandX_.resize(points);
  bandDy2_.resize(points);
  // One array per value (bandValue_[v * points + s]), so that the weighted
  // sums below read consecutive points and vectorise.
  bandValue_.resize(points * V);
  weight_.resize(points);
  std::size_t lo = 0, hi = 0;
  for (int j = 0; j < fh_; ++j)
  {
    const float fj = static_cast<float>(j);
    // Points with |seamY - j| < r: [lo, hi) in the row-ordered list.
    while (lo < points && !(fj - seamY_[lo] < r))
      ++lo;
    hi = std::max(hi, lo);
    while (hi < points && seamY_[hi] - fj < r)
      ++hi;
    const std::size_t m = hi - lo;
    if (m == 0)
      continue;
    std::int32_t minX = std::numeric_limits<std::int32_t>::max();
    std::int32_t maxX = std::numeric_limits<std::int32_t>::lowest();
    for (std::size_t s = 0; s < m; ++s)
    {
      const std::int32_t dy = j - static_cast<std::int32_t>(seamY_[lo + s]);
      bandX_[s] = static_cast<std::int32_t>(seamX_[lo + s]);
      bandDy2_[s] = dy * dy;
      minX = std::min(minX, bandX_[s]);
      maxX = std::max(maxX, bandX_[s]);
      for (int v = 0; v < V; ++v)
        bandValue_[v * points + s] = seamValue_[(lo + s) * V + v];
    }
    const int iBegin = std::max(0, static_cast<int>(std::floor(minX - r)) + 1);
    const int iEnd = std::min(fw_, static_cast<int>(std::ceil(static_cast<float>(maxX) + r)));
    for (int i = iBegin; i < iEnd; ++i)
    {
      const std::size_t k = rowMajor(i, j, fw_);
      if (side_[k] != 2)
        continue;
      if (pointAt_[k] >= 0)
      {
        for (int v = 0; v < V; ++v)
          out[k * V + v] = seamValue_[pointAt_[k] * V + v];
        continue;
      }
      // Branch-free so the compiler vectorises it (sqrt needs -fno-math-errno,
      // see Sources.cmake); d > 0 here.
      // Squared distances are integers (exact in float); their minimum is
      // taken in integers, which vectorises where a float minimum does not.
      std::int32_t dmin2 = std::numeric_limits<std::int32_t>::max();
      const std::int32_t* __restrict bx = bandX_.data();
      const std::int32_t* __restrict by2 = bandDy2_.data();
      float* __restrict wt = weight_.data();
      for (std::size_t s = 0; s < m; ++s)
      {
        const std::int32_t dx = i - bx[s];
        const std::int32_t d2 = dx * dx + by2[s];
        dmin2 = std::min(dmin2, d2);
        const float d = std::sqrt(static_cast<float>(d2));
        const float base = std::max(r - d, 0.0f) / (r * d);
        wt[s] = base * base;
      }
      if (!(static_cast<float>(dmin2) < r2))
        continue;
      if (power != 2.0)
      {
        for (std::size_t s = 0; s < m; ++s)
          weight_[s] = static_cast<float>(std::pow(std::sqrt(weight_[s]), power));
      }
      // Four partial sums per value (a fixed order, so results stay
      // deterministic) to break the dependency chain of one running sum.
      double sumW[4] = { 0.0, 0.0, 0.0, 0.0 };
      double sum[V][4] = {};
      const double* __restrict value = bandValue_.data();
      std::size_t s = 0;
      for (; s + 4 <= m; s += 4)
      {
        for (int l = 0; l < 4; ++l)
        {
          const double w = wt[s + l];
          sumW[l] += w;
          for (int v = 0; v < V; ++v)
            sum[v][l] += w * value[v * points + s + l];
        }
      }
      for (; s < m; ++s)
      {
        const double w = wt[s];
        sumW[0] += w;
        for (int v = 0; v < V; ++v)
          sum[v][0] += w * value[v * points + s];
      }
      const double totalW = (sumW[0] + sumW[1]) + (sumW[2] + sumW[3]);
      const double t = 1.0 - std::sqrt(static_cast<double>(dmin2)) / radius;
      const double falloff = t * t * (3.0 - 2.0 * t);
      for (int v = 0; v < V; ++v)
      {
        const double total = (sum[v][0] + sum[v][1]) + (sum[v][2] + sum[v][3]);
        out[k * V + v] = falloff * total / totalW;
      }
    }
  }
}

void PatchMerger::blendShepard(const MergeOptions& options)
{
  // Seam points: new cells with an old 4-neighbour. The mismatch is A - B at
  // the point where both exist, else the mean over its old neighbours.
  seamX_.clear();
  seamY_.clear();
  seamValue_.clear();
  for (int j = 0; j < fh_; ++j)
  {
    for (int i = 0; i < fw_; ++i)
    {
      const std::size_t k = rowMajor(i, j, fw_);
      if (side_[k] != 2)
        continue;
      double sum = 0.0;
      int count = 0;
      for (int d = 0; d < 4; ++d)
      {
        const int ni = i + Di[d];
        const int nj = j + Dj[d];
        if (ni < 0 || nj < 0 || ni >= fw_ || nj >= fh_)
          continue;
        const std::size_t m = rowMajor(ni, nj, fw_);
        if (side_[m] != 1)
          continue;
        const double b = newMask_[m] ? new_[m] : new_[k];
        sum += old_[m] - b;
        ++count;
      }
      if (count == 0)
        continue;
      seamX_.push_back(static_cast<float>(i));
      seamY_.push_back(static_cast<float>(j));
      seamValue_.push_back(oldMask_[k] ? static_cast<double>(old_[k]) - new_[k] : sum / count);
    }
  }
  shepard<1>(options.shepardRadius, options.shepardPower, shepardOut_);
  for (std::size_t k = 0; k < out_.size(); ++k)
  {
    if (side_[k] == 2)
      out_[k] = new_[k] + shepardOut_[k];
  }
}

namespace
{
// The values spread from each seam point in New mode: the gradient mismatch
// (x, y) and the height mismatch.
constexpr int GradientX = 0, HeightMismatch = 2, Values = 3;
} // namespace

void PatchMerger::blendPoisson(const MergeOptions& options,
  bool gradientShepard,
  MergeResult& result)
{
  const std::size_t n = cellCount(fw_, fh_);
  // Tasse: the gradient mismatch G_A - G_B at seam points (new cells with an
  // old neighbour where the old terrain exists too), spread over the new side.
  // The height mismatch A - B rides along as a third value: the patch shifted
  // by it is a start close to the solution near the seam (one CG iteration
  // fewer); the start does not change what the solve converges to.
  if (gradientShepard)
  {
    seamX_.clear();
    seamY_.clear();
    seamValue_.clear();
    for (int j = 0; j < fh_; ++j)
    {
      for (int i = 0; i < fw_; ++i)
      {
        const std::size_t k = rowMajor(i, j, fw_);
        if (side_[k] != 2 || !oldMask_[k])
          continue;
        bool touchesOld = false;
        for (int d = 0; d < 4; ++d)
        {
          const int ni = i + Di[d];
          const int nj = j + Dj[d];
          touchesOld = touchesOld ||
            (ni >= 0 && nj >= 0 && ni < fw_ && nj < fh_ && side_[rowMajor(ni, nj, fw_)] == 1);
        }
        if (!touchesOld)
          continue;
        seamX_.push_back(static_cast<float>(i));
        seamY_.push_back(static_cast<float>(j));
        for (int axis = 0; axis < 2; ++axis)
        {
          const auto g = gradientPair(old_, new_, fw_, fh_, i, j, axis);
          seamValue_.push_back(g.first - g.second);
        }
        seamValue_.push_back(static_cast<double>(old_[k]) - new_[k]); // HeightMismatch
      }
    }
    shepard<Values>(options.shepardRadius, options.shepardPower, shepardOut_);
  }
  // Guidance differences per edge.
  gx_.assign(n, NaN);
  gy_.assign(n, NaN);
  for (int j = 0; j < fh_; ++j)
  {
    for (int i = 0; i < fw_; ++i)
    {
      const std::size_t p = rowMajor(i, j, fw_);
      for (int axis = 0; axis < 2; ++axis)
      {
        if (axis == 0 ? i + 1 >= fw_ : j + 1 >= fh_)
          continue;
        const std::size_t q = axis == 0 ? p + 1 : p + fw_;
        if (side_[p] == 0 || side_[q] == 0 || (side_[p] != 2 && side_[q] != 2))
          continue;
        const bool oldBoth = oldMask_[p] && oldMask_[q];
        const bool newBoth = newMask_[p] && newMask_[q];
        const double dOld = oldBoth ? static_cast<double>(old_[q]) - old_[p] : 0.0;
        double dNew = newBoth ? static_cast<double>(new_[q]) - new_[p] : 0.0;
        double g = 0.0;
        if (gradientShepard && newBoth)
        {
          // Corrected B gradient: mean of the correction at the new ends.
          double c = 0.0;
          int ends = 0;
          for (std::size_t e : { p, q })
          {
            if (side_[e] == 2)
            {
              c += shepardOut_[e * Values + GradientX + axis];
              ++ends;
            }
          }
          dNew += c / ends;
        }
        if (side_[p] == side_[q])
        {
          g = dNew; // both new
        }
        else if (gradientShepard)
        {
          // Across the seam, the old terrain's own step (it exists on both
          // ends in the overlap); else the corrected patch step.
          g = oldBoth ? dOld : (newBoth ? dNew : 0.0);
        }
        else
        {
          // Zhou zeroes the composite's gradient here. We take the mean step
          // of the sources that exist on both ends (0 if none): the jump is
          // still left out, and a perfect match is not flattened.
          const int sources = (oldBoth ? 1 : 0) + (newBoth ? 1 : 0);
          g = sources > 0 ? (dOld + dNew) / sources : 0.0;
        }
        (axis == 0 ? gx_ : gy_)[p] = g;
      }
    }
  }
  PoissonOptions poisson = options.poisson;
  if (!(poisson.errorTolerance > 0.0) && options.relativeHeightTolerance > 0.0)
  {
    float lo = std::numeric_limits<float>::max();
    float hi = std::numeric_limits<float>::lowest();
    for (std::size_t k = 0; k < n; ++k)
    {
      if (side_[k] == 0)
        continue;
      const float z = side_[k] == 2 ? new_[k] : old_[k];
      lo = std::min(lo, z);
      hi = std::max(hi, z);
    }
    if (hi > lo)
      poisson.errorTolerance = options.relativeHeightTolerance * (static_cast<double>(hi) - lo);
  }
  const bool canAnchor = gradientShepard && !seamX_.empty();
  const bool anchored = canAnchor && options.anchorFreeBorder;
  result.poisson = solveNewSide(gradientShepard, anchored, options.shepardRadius, poisson);
  result.anchored = anchored;
  if (canAnchor && !anchored && freeBorderOutside(options.lowestHeight, options.highestHeight))
  {
    result.poisson = solveNewSide(gradientShepard, true, options.shepardRadius, poisson);
    result.anchored = true;
  }
}

PoissonStatistics PatchMerger::solveNewSide(bool gradientShepard,
  bool anchored,
  double anchorDistance,
  const PoissonOptions& poisson)
{
  const std::size_t n = cellCount(fw_, fh_);
  std::vector<std::uint8_t>& unknown = coreMask_; // reused as scratch
  unknown.assign(n, 0);
  double meanMismatch = 0.0;
  if (anchored)
  {
    seamDistance(seamDistance_);
    for (std::size_t s = 0; s < seamX_.size(); ++s)
    {
      meanMismatch += seamValue_[s * Values + HeightMismatch];
    }
    meanMismatch /= static_cast<double>(seamX_.size());
  }
  for (std::size_t k = 0; k < n; ++k)
  {
    const bool anchor =
      anchored && side_[k] == 2 && seamDistance_[k] > anchorDistance && onFreeBorder(k);
    unknown[k] = side_[k] == 2 && !anchor;
    const double start = anchor ? new_[k] + meanMismatch
      : gradientShepard         ? new_[k] + shepardOut_[k * Values + HeightMismatch]
                                : new_[k];
    out_[k] = side_[k] == 2 ? start : (side_[k] == 1 ? old_[k] : NaN);
  }
  return poisson_.solveGuided(
    fw_, fh_, cellX_, cellY_, unknown.data(), gx_.data(), gy_.data(), out_.data(), poisson);
}

bool PatchMerger::freeBorderOutside(float lowest, float highest) const
{
  for (std::size_t k = 0; k < out_.size(); ++k)
  {
    if (side_[k] == 2 && onFreeBorder(k) && (out_[k] < lowest || out_[k] > highest))
    {
      return true;
    }
  }
  return false;
}

bool PatchMerger::onFreeBorder(std::size_t k) const
{
  // Column and row of window cell k (the window is at most an int wide).
  const auto [i, j] = cellOf(k, fw_);
  for (int d = 0; d < 4; ++d)
  {
    const int ni = i + Di[d];
    const int nj = j + Dj[d];
    if (ni < 0 || nj < 0 || ni >= fw_ || nj >= fh_ || side_[rowMajor(ni, nj, fw_)] == 0)
    {
      return true;
    }
  }
  return false;
}

void PatchMerger::seamDistance(std::vector<float>& out) const
{
  // Two chamfer passes (1 straight, 1.4 diagonal, in cells): within 8% of the
  // Euclidean distance, plenty to say where the correction has faded out.
  constexpr float kStraight = 1.0f;
  constexpr float kDiagonal = 1.4f;
  const std::size_t n = cellCount(fw_, fh_);
  out.assign(n, std::numeric_limits<float>::infinity());
  for (std::size_t s = 0; s < seamX_.size(); ++s)
  {
    out[seamCell(seamX_[s], seamY_[s], fw_)] = 0.0f;
  }
  auto relax = [&](int i, int j, int di, int dj, float step)
  {
    const int ni = i + di;
    const int nj = j + dj;
    if (ni < 0 || nj < 0 || ni >= fw_ || nj >= fh_)
      return;
    float& here = out[rowMajor(i, j, fw_)];
    here = std::min(here, out[rowMajor(ni, nj, fw_)] + step);
  };
  for (int j = 0; j < fh_; ++j)
  {
    for (int i = 0; i < fw_; ++i)
    {
      relax(i, j, -1, 0, kStraight);
      relax(i, j, 0, -1, kStraight);
      relax(i, j, -1, -1, kDiagonal);
      relax(i, j, 1, -1, kDiagonal);
    }
  }
  for (int j = fh_ - 1; j >= 0; --j)
  {
    for (int i = fw_ - 1; i >= 0; --i)
    {
      relax(i, j, 1, 0, kStraight);
      relax(i, j, 0, 1, kStraight);
      relax(i, j, 1, 1, kDiagonal);
      relax(i, j, -1, 1, kDiagonal);
    }
  }
}

MergeResult PatchMerger::merge(Heightfield& terrain,
  std::vector<std::uint8_t>& filled,
  const Heightfield& patch,
  int x0,
  int y0,
  const std::vector<std::uint8_t>* core,
  const MergeOptions& options,
  const MergeResult* cut)
{
  if (!(options.shepardRadius > 0.0) || !(options.shepardPower > 0.0))
  {
    throw Error("The Shepard radius and power must be positive.");
  }
  MergeResult result = prepare(terrain, filled, patch, x0, y0, core, options.cut, cut);
  const std::size_t n = cellCount(fw_, fh_);
  out_.assign(n, NaN);
  for (std::size_t k = 0; k < n; ++k)
  {
    if (side_[k] == 2)
      out_[k] = new_[k];
  }
  switch (options.mode)
  {
    case MergeMode::Cut:
      break;
    case MergeMode::Shepard:
      blendShepard(options);
      break;
    case MergeMode::Poisson:
      blendPoisson(options, false, result);
      break;
    case MergeMode::New:
      blendPoisson(options, true, result);
      break;
  }
  for (int j = 0; j < fh_; ++j)
  {
    for (int i = 0; i < fw_; ++i)
    {
      const std::size_t k = rowMajor(i, j, fw_);
      if (side_[k] != 2)
        continue;
      const std::size_t tk = terrain.index(fx0_ + i, fy0_ + j);
      terrain.z[tk] = static_cast<float>(out_[k]);
      filled[tk] = 1;
      if (terrain.hasMask())
        terrain.valid[tk] = 1;
    }
  }
  return result;
}

const std::vector<OptionRow>& mergeOptionRows()
{
  static const std::vector<OptionRow> rows = []
  {
    const MergeOptions d;
    return std::vector<OptionRow>{
      choiceRow("Mode",
        "",
        static_cast<int>(d.mode),
        choicesOf(kMergeModeWords),
        { "Cut", "Poisson", "Shepard", "New (Shepard gradients + Poisson)" }),
      numberRow("ShepardRadius",
        "",
        OptionType::Real,
        d.shepardRadius,
        kMinShepardRadius,
        kMaxShepardRadius),
    };
  }();
  return rows;
}

} // namespace tsynth
