#include "PatchMatch.h"

#include "../Core/Error.h"
#include "../Core/Grid.h"
#include "../Core/Random.h"
#include "../Matching/Vectorise.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace tsynth::optim
{
namespace
{

// Rows per band of the parallel sweep: fixed so that the bands, and with them
// the result, do not depend on the thread count; 16 rows give 64 bands at
// 1024^2 (enough to balance two to eight threads) and lose the in-sweep
// propagation across only one row in 16.
constexpr int kBandRows = 16;
// Random draws a visit may use (the orientation draw plus two per halving of
// a radius below 2^31): the stride of the draw index per cell.
constexpr std::uint64_t kDrawsPerVisit = 64;
constexpr double kTwoToMinus32 = 1.0 / 4294967296.0;

std::size_t sz(int v)
{
  return static_cast<std::size_t>(v);
}

// Two numbers in [0, 1) from one hash: draw `draw` of the visit hashed `visit`.
std::array<double, 2> drawPair(std::uint64_t visit, std::uint64_t draw)
{
  const std::uint64_t h = mixBits(visit + draw);
  return { static_cast<double>(h & 0xffffffffULL) * kTwoToMinus32,
    static_cast<double>(h >> 32) * kTwoToMinus32 };
}

// The hash of one visit of a cell: seededUniform's mixing of (seed, stream,
// index), kept as bits.
std::uint64_t visitHash(std::uint64_t seed, std::uint64_t stream, std::uint64_t cell)
{
  return mixBits(mixBits(mixBits(seed) ^ stream) ^ cell) * kDrawsPerVisit;
}

// Uniform integer in -r..r from u in [0, 1).
int offsetIn(double u, int r)
{
  return std::min(r, static_cast<int>(u * (2.0 * r + 1.0)) - r);
}

float horizontalSum(const float* acc)
{
  return ((acc[0] + acc[1]) + (acc[2] + acc[3])) + ((acc[4] + acc[5]) + (acc[6] + acc[7]));
}

// A target patch laid out as the SSD reads it: rows of `lanes` floats, with
// weight 1 on the patch cells inside the grid and 0 elsewhere.
struct TargetPatch
{
  std::array<float, kMaxPatchLanes * kMaxPatchLanes> q{};
  std::array<float, kMaxPatchLanes * kMaxPatchLanes> m{};
};

void fillTargetPatch(const SourceLevel& s, const TargetGrid& g, int x, int y, TargetPatch& p)
{
  for (int r = 0; r < s.patch; ++r)
  {
    const int ty = y - s.half + r;
    for (int l = 0; l < s.lanes; ++l)
    {
      const int tx = x - s.half + l;
      const bool inside = l < s.patch && tx >= 0 && tx < g.width && ty >= 0 && ty < g.height;
      const std::size_t o = sz(r * s.lanes + l);
      p.q[o] = inside ? g.z[rowMajor(tx, ty, g.width)] : 0.0f;
      p.m[o] = inside ? 1.0f : 0.0f;
    }
  }
}

const float* patchOrigin(const SourceLevel& s, const Match& c)
{
  const OrientedCopy& copy = s.copies[sz(c.t)];
  return copy.z.data() + sz(c.y - s.half) * copy.stride + sz(c.x - s.half);
}

// The SSD, lane-wise (each lane one column of every kLanes, so the compiler
// vectorises it without reordering a sum), stopping after the first row whose
// partial sum reaches `bound`: the terms are not negative, so a stopped sum is
// at least the bound and the full one would be too (the comparison with the
// bound is the same as with the full sum).
inline float lanesSsd(const SourceLevel& s, const TargetPatch& p, const Match& c, float bound)
{
  const std::size_t stride = s.copies[sz(c.t)].stride;
  const float* src = patchOrigin(s, c);
  const float* q = p.q.data();
  const float* m = p.m.data();
  float acc[kLanes] = {};
  for (int r = 0; r < s.patch; ++r)
  {
    for (int b = 0; b < s.lanes; b += kLanes)
    {
      for (int l = 0; l < kLanes; ++l)
      {
        const float d = q[b + l] - src[b + l];
        acc[l] += m[b + l] * (d * d);
      }
    }
    src += stride;
    q += s.lanes;
    m += s.lanes;
    const float partial = horizontalSum(acc);
    if (partial >= bound)
    {
      return partial;
    }
  }
  return horizontalSum(acc);
}

// The reference: one running sum over the patch in row order, no early stop.
float plainSsd(const SourceLevel& s, const TargetPatch& p, const Match& c)
{
  const std::size_t stride = s.copies[sz(c.t)].stride;
  const float* src = patchOrigin(s, c);
  float sum = 0.0f;
  for (int r = 0; r < s.patch; ++r)
  {
    for (int l = 0; l < s.patch; ++l)
    {
      const std::size_t o = sz(r * s.lanes + l);
      if (p.m[o] != 0.0f)
      {
        const float d = p.q[o] - src[sz(r) * stride + sz(l)];
        sum += d * d;
      }
    }
  }
  return sum;
}

bool centreValid(const SourceLevel& s, const Match& c)
{
  const OrientedCopy& copy = s.copies[sz(c.t)];
  return c.x >= 0 && c.y >= 0 && c.x < copy.width && c.y < copy.height &&
    copy.centreOk[rowMajor(c.x, c.y, copy.width)] != 0;
}

// One cell's search state during a visit.
struct Visit
{
  const SourceLevel& s;
  const TargetPatch& patch;
  bool plain;
  Match best;
  float bestCost;

  void consider(const Match& c)
  {
    if ((c.x == best.x && c.y == best.y && c.t == best.t) || !centreValid(s, c))
    {
      return;
    }
    const float v = plain ? plainSsd(s, patch, c) : lanesSsd(s, patch, c, bestCost);
    if (v < bestCost)
    {
      best = c;
      bestCost = v;
    }
  }
};

struct Sweep
{
  const SourceLevel& s;
  const TargetGrid& g;
  const std::vector<Match>& before; // the map when the iteration started
  std::vector<Match>& map;
  std::vector<float>& cost;
  std::uint64_t seed;
  std::uint64_t stream;
  bool forward;
  bool plain;
};

// Random search: first the current patch turned to a random allowed
// orientation (about the same source cell), then windows around the best
// centre halving from the whole copy down to one cell.
void randomSearch(const Sweep& w, Visit& v, std::uint64_t hash)
{
  std::uint64_t draw = 0;
  const std::vector<int>& orientations = w.s.orientations;
  if (orientations.size() > 1)
  {
    const double u = drawPair(hash, draw++)[0];
    const int t = orientations[std::min(orientations.size() - 1,
      static_cast<std::size_t>(u * static_cast<double>(orientations.size())))];
    const std::array<int, 2> at = toSource(w.s, v.best);
    v.consider(fromSource(w.s, at[0], at[1], t));
  }
  const OrientedCopy& copy = w.s.copies[sz(v.best.t)];
  for (int r = std::max(copy.width, copy.height); r >= 1; r /= 2)
  {
    const std::array<double, 2> u = drawPair(hash, draw++);
    Match c = v.best;
    c.x = std::clamp(v.best.x + offsetIn(u[0], r), w.s.half, copy.width - 1 - w.s.half);
    c.y = std::clamp(v.best.y + offsetIn(u[1], r), w.s.half, copy.height - 1 - w.s.half);
    v.consider(c);
  }
}

void visitCell(const Sweep& w, int x, int y, int y0, int y1, TargetPatch& patch)
{
  const std::size_t p = rowMajor(x, y, w.g.width);
  fillTargetPatch(w.s, w.g, x, y, patch);
  Visit v{ w.s, patch, w.plain, w.map[p], w.cost[p] };
  const int dir = w.forward ? 1 : -1;
  // Propagation: the neighbours visited before this cell, their centres moved by one cell.
  const int nx = x - dir;
  if (nx >= 0 && nx < w.g.width)
  {
    Match c = w.map[rowMajor(nx, y, w.g.width)];
    c.x += dir;
    v.consider(c);
  }
  const int ny = y - dir;
  if (ny >= 0 && ny < w.g.height)
  {
    const std::size_t n = rowMajor(x, ny, w.g.width);
    Match c = ny >= y0 && ny < y1 ? w.map[n] : w.before[n];
    c.y += dir;
    v.consider(c);
  }
  randomSearch(w, v, visitHash(w.seed, w.stream, p));
  w.map[p] = v.best;
  w.cost[p] = v.bestCost;
}

TSYNTH_VECTOR_CLONES void sweepBand(const Sweep& w, int y0, int y1)
{
  TargetPatch patch;
  if (w.forward)
  {
    for (int y = y0; y < y1; ++y)
    {
      for (int x = 0; x < w.g.width; ++x)
      {
        visitCell(w, x, y, y0, y1, patch);
      }
    }
  }
  else
  {
    for (int y = y1 - 1; y >= y0; --y)
    {
      for (int x = w.g.width - 1; x >= 0; --x)
      {
        visitCell(w, x, y, y0, y1, patch);
      }
    }
  }
}

TSYNTH_VECTOR_CLONES void costRow(const SourceLevel& s,
  const TargetGrid& g,
  const std::vector<Match>& map,
  std::vector<float>& cost,
  int y,
  bool plain)
{
  TargetPatch patch;
  for (int x = 0; x < g.width; ++x)
  {
    const std::size_t p = rowMajor(x, y, g.width);
    fillTargetPatch(s, g, x, y, patch);
    cost[p] = plain ? plainSsd(s, patch, map[p])
                    : lanesSsd(s, patch, map[p], std::numeric_limits<float>::infinity());
  }
}

OrientedCopy makeCopy(const Heightfield& src, const Orientation& o, int patch, int lanes)
{
  OrientedCopy c;
  const bool swapped = o.a[0] == 0;
  c.width = swapped ? src.height : src.width;
  c.height = swapped ? src.width : src.height;
  c.stride = sz(c.width + lanes - patch);
  c.toSource = o;
  c.z.assign(c.stride * sz(c.height), 0.0f);
  std::vector<std::uint8_t> valid(sz(c.width) * sz(c.height), 0);
  for (int v = 0; v < c.height; ++v)
  {
    for (int u = 0; u < c.width; ++u)
    {
      const int x = o.a[0] * u + o.a[1] * v + o.b[0];
      const int y = o.a[2] * u + o.a[3] * v + o.b[1];
      const std::size_t k = src.index(x, y);
      if (src.isValid(k) && std::isfinite(src.z[k]))
      {
        c.z[sz(v) * c.stride + sz(u)] = src.z[k];
        valid[rowMajor(u, v, c.width)] = 1;
      }
    }
  }
  // Summed-area table of valid cells: a centre is usable if its window is all valid.
  const std::size_t w1 = sz(c.width) + 1;
  std::vector<std::int32_t> sat(w1 * (sz(c.height) + 1), 0);
  for (int v = 0; v < c.height; ++v)
  {
    for (int u = 0; u < c.width; ++u)
    {
      sat[sz(v + 1) * w1 + sz(u + 1)] = valid[rowMajor(u, v, c.width)] +
        sat[sz(v) * w1 + sz(u + 1)] + sat[sz(v + 1) * w1 + sz(u)] - sat[sz(v) * w1 + sz(u)];
    }
  }
  const int half = patch / 2;
  c.centreOk.assign(valid.size(), 0);
  for (int v = half; v + half < c.height; ++v)
  {
    for (int u = half; u + half < c.width; ++u)
    {
      const std::size_t x0 = sz(u - half), x1 = sz(u + half + 1);
      const std::size_t y0 = sz(v - half), y1 = sz(v + half + 1);
      const std::int32_t n =
        sat[y1 * w1 + x1] - sat[y0 * w1 + x1] - sat[y1 * w1 + x0] + sat[y0 * w1 + x0];
      if (n == patch * patch)
      {
        const std::size_t k = rowMajor(u, v, c.width);
        c.centreOk[k] = 1;
        c.centres.push_back(static_cast<std::int32_t>(k));
      }
    }
  }
  return c;
}

} // namespace

Orientation makeOrientation(int turns, bool mirrored, int width, int height)
{
  // A = M * R^turns, R the counter-clockwise quarter turn, M = diag(-1, 1).
  std::array<int, 4> a{ 1, 0, 0, 1 };
  for (int t = 0; t < turns; ++t)
  {
    a = { -a[2], -a[3], a[0], a[1] };
  }
  if (mirrored)
  {
    a[0] = -a[0];
    a[1] = -a[1];
  }
  const bool swapped = a[0] == 0;
  const int cw = swapped ? height : width;
  const int ch = swapped ? width : height;
  Orientation o;
  o.a = a;
  o.b[0] = -(std::min(0, a[0] * (cw - 1)) + std::min(0, a[1] * (ch - 1)));
  o.b[1] = -(std::min(0, a[2] * (cw - 1)) + std::min(0, a[3] * (ch - 1)));
  return o;
}

SourceLevel makeSourceLevel(const Heightfield& source,
  int patch,
  bool rotations,
  bool reflections,
  int level)
{
  SourceLevel s;
  s.width = source.width;
  s.height = source.height;
  s.patch = patch;
  s.half = patch / 2;
  s.lanes = (patch + kLanes - 1) / kLanes * kLanes;
  for (int m = 0; m <= (reflections ? 1 : 0); ++m)
  {
    for (int r = 0; r <= (rotations ? 3 : 0); ++r)
    {
      const int t = r + 4 * m;
      s.orientations.push_back(t);
      s.copies[sz(t)] =
        makeCopy(source, makeOrientation(r, m != 0, source.width, source.height), patch, s.lanes);
    }
  }
  if (s.copies[0].centres.empty())
  {
    throw Error("The source has no " + std::to_string(patch) + " x " + std::to_string(patch) +
      " block of valid cells at pyramid level " + std::to_string(level) +
      ": use a smaller patch, fewer levels or a source with more valid data.");
  }
  return s;
}

std::array<int, 2> toSource(const SourceLevel& s, const Match& m)
{
  const Orientation& o = s.copies[sz(m.t)].toSource;
  return { o.a[0] * m.x + o.a[1] * m.y + o.b[0], o.a[2] * m.x + o.a[3] * m.y + o.b[1] };
}

Match fromSource(const SourceLevel& s, int x, int y, int t)
{
  // A is orthogonal: its inverse is its transpose.
  const Orientation& o = s.copies[sz(t)].toSource;
  const int dx = x - o.b[0];
  const int dy = y - o.b[1];
  return { o.a[0] * dx + o.a[2] * dy, o.a[1] * dx + o.a[3] * dy, t };
}

namespace
{

Match randomMatch(const SourceLevel& s, std::uint64_t hash)
{
  const std::array<double, 2> u = drawPair(hash, 0);
  const std::vector<int>& ts = s.orientations;
  const int t =
    ts[std::min(ts.size() - 1, static_cast<std::size_t>(u[0] * static_cast<double>(ts.size())))];
  const OrientedCopy& c = s.copies[sz(t)];
  const std::size_t i = std::min(
    c.centres.size() - 1, static_cast<std::size_t>(u[1] * static_cast<double>(c.centres.size())));
  const std::int32_t k = c.centres[i];
  return { k % c.width, k / c.width, t };
}

} // namespace

std::vector<Match> randomMatches(const SourceLevel& s,
  int width,
  int height,
  std::uint64_t seed,
  std::uint64_t stream)
{
  std::vector<Match> map(sz(width) * sz(height));
#pragma omp parallel for schedule(static)
  for (int y = 0; y < height; ++y)
  {
    for (int x = 0; x < width; ++x)
    {
      const std::size_t p = rowMajor(x, y, width);
      map[p] = randomMatch(s, visitHash(seed, stream, p));
    }
  }
  return map;
}

std::vector<Match> randomRegions(const SourceLevel& s,
  int width,
  int height,
  int block,
  std::uint64_t seed,
  std::uint64_t stream)
{
  const int blocksX = (width + block - 1) / block;
  const int blocksY = (height + block - 1) / block;
  const std::vector<Match> starts = randomMatches(s, blocksX, blocksY, seed, stream);
  std::vector<Match> map(sz(width) * sz(height));
#pragma omp parallel for schedule(static)
  for (int y = 0; y < height; ++y)
  {
    for (int x = 0; x < width; ++x)
    {
      const Match& start = starts[sz(y / block) * sz(blocksX) + sz(x / block)];
      Match m = start;
      m.x += x % block;
      m.y += y % block;
      const OrientedCopy& c = s.copies[sz(m.t)];
      const bool inside = m.x < c.width && m.y < c.height;
      map[rowMajor(x, y, width)] =
        inside && c.centreOk[rowMajor(m.x, m.y, c.width)] != 0 ? m : start;
    }
  }
  return map;
}

std::vector<Match> upsampleMatches(const std::vector<Match>& coarse,
  int coarseWidth,
  const SourceLevel& coarseSource,
  const SourceLevel& fineSource,
  int width,
  int height,
  std::uint64_t seed,
  std::uint64_t stream)
{
  std::vector<Match> map(sz(width) * sz(height));
#pragma omp parallel for schedule(static)
  for (int y = 0; y < height; ++y)
  {
    for (int x = 0; x < width; ++x)
    {
      const Match& m = coarse[sz(y / 2) * sz(coarseWidth) + sz(x / 2)];
      const Orientation& o = coarseSource.copies[sz(m.t)].toSource;
      const std::array<int, 2> at = toSource(coarseSource, m);
      const int dx = x - 2 * (x / 2);
      const int dy = y - 2 * (y / 2);
      Match c = fromSource(fineSource,
        2 * at[0] + o.a[0] * dx + o.a[1] * dy,
        2 * at[1] + o.a[2] * dx + o.a[3] * dy,
        m.t);
      const OrientedCopy& copy = fineSource.copies[sz(m.t)];
      c.x = std::clamp(c.x, fineSource.half, copy.width - 1 - fineSource.half);
      c.y = std::clamp(c.y, fineSource.half, copy.height - 1 - fineSource.half);
      const std::size_t p = rowMajor(x, y, width);
      map[p] = centreValid(fineSource, c) ? c : randomMatch(fineSource, visitHash(seed, stream, p));
    }
  }
  return map;
}

void matchCosts(const SourceLevel& s,
  const TargetGrid& target,
  const std::vector<Match>& map,
  std::vector<float>& cost,
  bool plain)
{
  cost.resize(map.size());
#pragma omp parallel for schedule(static)
  for (int y = 0; y < target.height; ++y)
  {
    costRow(s, target, map, cost, y, plain);
  }
}

bool patchMatch(const SourceLevel& s,
  const TargetGrid& target,
  std::vector<Match>& map,
  std::vector<float>& cost,
  const PatchMatchSettings& settings)
{
  matchCosts(s, target, map, cost, settings.plainSsd);
  const int bands = (target.height + kBandRows - 1) / kBandRows;
  std::vector<Match> before;
  for (int it = 0; it < settings.iterations; ++it)
  {
    before = map;
    const Sweep w{ s,
      target,
      before,
      map,
      cost,
      settings.seed,
      mixBits(settings.stream) + static_cast<std::uint64_t>(it),
      it % 2 == 0,
      settings.plainSsd };
#pragma omp parallel for schedule(dynamic)
    for (int b = 0; b < bands; ++b)
    {
      sweepBand(w, b * kBandRows, std::min(target.height, (b + 1) * kBandRows));
    }
    if (settings.afterIteration && !settings.afterIteration(it + 1))
    {
      return false;
    }
  }
  return true;
}

void reconstruct(const SourceLevel& s,
  const std::vector<Match>& map,
  int width,
  int height,
  const std::vector<float>& guide,
  const std::vector<float>& guideWeight,
  double weight,
  std::vector<float>& out)
{
  out.resize(sz(width) * sz(height));
  const int h = s.half;
#pragma omp parallel for schedule(static)
  for (int y = 0; y < height; ++y)
  {
    for (int x = 0; x < width; ++x)
    {
      double sum = 0.0;
      int count = 0;
      for (int qy = std::max(-h, -y); qy <= std::min(h, height - 1 - y); ++qy)
      {
        for (int qx = std::max(-h, -x); qx <= std::min(h, width - 1 - x); ++qx)
        {
          const Match& m = map[sz(y + qy) * sz(width) + sz(x + qx)];
          const OrientedCopy& c = s.copies[sz(m.t)];
          sum += c.z[sz(m.y - qy) * c.stride + sz(m.x - qx)];
          ++count;
        }
      }
      const std::size_t p = rowMajor(x, y, width);
      const double mean = sum / count;
      const double w = guideWeight.empty() ? weight : weight * guideWeight[p];
      out[p] = static_cast<float>(w > 0.0 ? w * guide[p] + (1.0 - w) * mean : mean);
    }
  }
}

} // namespace tsynth::optim
