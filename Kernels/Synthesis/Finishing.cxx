#include "Finishing.h"

#include "../Core/Error.h"
#include "../Core/Grid.h"
#include "../Core/Smoothing.h"
#include "../Distance/DistanceField.h"
#include "../Hydrology/Flow.h"
#include "../Hydrology/MultiscalePitRemoval.h"
#include "../Hydrology/PitRemoval.h"
#include "../Merging/Poisson.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <queue>
#include <unordered_map>

namespace tsynth
{
namespace
{

// The nearest seed of cell c, an int32 cell (-1: none, which the caller has ruled out).
std::size_t nearestSeed(const NearestSeeds& near, std::size_t c)
{
  return static_cast<std::size_t>(near.nearest[c]);
}

// Scale of the final landform correction, in patches: relief coarser than a
// sixth of a patch is pulled towards the target (what the patches missed or
// drifted off); the detail within it stays the patches' own. Applied once, at
// the end: also pulling what was placed during the synthesis drew the
// landforms more strongly but flattened the land (slope distance 0.18-0.21
// against 0.04-0.08 on the bundled sketches). A quarter patch left lone
// strokes to the texture (legible 0.55 and 0.36 on Everest's letters and
// Colorado's spiral; 0.64 and 0.47 at a sixth); an eighth (0.77, 0.60) made
// the bundled sketches flatter than the exemplars (slope distance 0.063 over
// 44 terrains against 0.043 at a sixth, 0.039 at a quarter) and drain worse.
constexpr double kCorrectionScaleInPatches = 1.0 / 6.0;
// Where sketched landforms are narrower than that (strokes drawn close), the
// correction works at this share of their half width (a valley 25 cells wide
// each side: relief coarser than 8 cells), so each one is drawn at its own
// scale; the texture finer than it stays the patches'.
constexpr double kCorrectionShareOfHalfWidth = 1.0 / kCorrectionSigmasPerHalfWidth;
// ... but never finer than kFinestCorrectionInPatches (Finishing.h).
// A drawn target's landforms replace the output's relief coarser than that
// scale in their own shape, smoothed over this many cells only
// (correctLandformAtScales' targetSigma): a crest or floor a few cells wide.
// Taken at the correction's own scale, as a DEM target still is, strokes
// closer than a patch came out at about half their depth and read faintly
// (legible share over the 44-run sweep of the bundled sketches 0.61; block
// letters carved into Colorado 0.48, Tasse's code 0.63). Over 20 of those
// runs 3 cells drew them crisper still (0.84) but steeper than the exemplars'
// own slopes (slope distance 0.053 against 0.045), 5 read 0.80 at 0.046; 6
// keeps their slopes (0.044 over all 44, as before) and reads 0.79.
constexpr double kDrawnTargetSigmaCells = 6.0;
// Where the target leaves the land free, the final correction only removes
// drift coarser than this (in patches), toward the target's base level.
constexpr double kDriftScaleInPatches = 2.0;
// Valley carving fades out over this share of a patch beside the line.
constexpr double kDrainageReachInPatches = 0.25;
// Drainage (--drainage) starts on blocks of this share of a patch: the width
// of the cross-sections the landform term matches, so a basin that a seam
// closed off is opened by a valley of the patches' own scale.
constexpr double kPitRemovalCoarsestInPatches = 0.25;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Rounds of drainage smoothing, each at half the radius of the one before.
constexpr int kSmoothingRounds = 3;
// The cuts that make the lines exact are widened this many cells each side:
// in full over kCutFloorCells (every 8-neighbour of a line cell), so the cut
// is a floor a few cells wide and not a slot one cell wide (which, following
// the staircase of a slanted line's cells, showed as a dotted line along the
// floor in a hillshade), then fading out smoothly.
constexpr double kCutWideningCells = 5.0;
constexpr double kCutFloorCells = 1.5;
// The widened floor rises away from the line by this many channel depths
// per cell (widenCuts).
constexpr double kFloorCrossFall = 2.0;
constexpr std::array<int, 8> kDx{ 1, 1, 0, -1, -1, -1, 0, 1 };
constexpr std::array<int, 8> kDy{ 0, 1, 1, 1, 0, -1, -1, -1 };

// A biweight fade over t = 0..1: flat across a valley's floor, no kink at
// the line or at the reach.
double biweight(double t)
{
  return (1.0 - t * t) * (1.0 - t * t);
}

// Visits the valid 8-neighbours of (i, j) with their distance in metres.
template<typename Visit>
void forNeighbours(const Heightfield& hf, int i, int j, Visit visit)
{
  for (std::size_t n = 0; n < 8; ++n)
  {
    const int x = i + kDx[n];
    const int y = j + kDy[n];
    if (x >= 0 && y >= 0 && x < hf.width && y < hf.height && hf.isValid(x, y))
    {
      visit(hf.index(x, y), std::hypot(kDx[n] * hf.cellX, kDy[n] * hf.cellY));
    }
  }
}

// Lowers each line cell below every line cell upstream of it by the minimum
// gradient; `order` lists the line cells upstream first.
void descendAlongLines(Heightfield& out,
  const std::vector<std::size_t>& order,
  const std::vector<float>& downstream,
  double gradient)
{
  for (std::size_t c : order)
  {
    const auto [i, j] = cellOf(c, out.width);
    forNeighbours(out,
      i,
      j,
      [&](std::size_t u, double dist)
      {
        if (downstream[u] > downstream[c])
        {
          out.z[c] = std::min(out.z[c], static_cast<float>(out.z[u] - gradient * dist));
        }
      });
  }
}

// The lowest valid 8-neighbour of (i, j) that is not on a line (+inf: none).
double lowestSide(const Heightfield& hf, const std::vector<std::uint8_t>& line, std::size_t c)
{
  const auto [i, j] = cellOf(c, hf.width);
  double side = std::numeric_limits<double>::infinity();
  forNeighbours(hf,
    i,
    j,
    [&](std::size_t n, double)
    {
      if (line[n] == 0)
      {
        side = std::min(side, static_cast<double>(hf.z[n]));
      }
    });
  return side;
}

// A line cell's channel floor: `depth` below the cells beside the line, but
// lowered by `maxCut` at most (where the line runs along a steep side the
// water finds the valley floor beside it; cutting a slot there would crease).
double channelFloor(const Heightfield& out,
  const std::vector<std::uint8_t>& line,
  std::size_t c,
  double depth,
  double maxCut)
{
  const double z = out.z[c];
  const double side = lowestSide(out, line, c);
  return std::isfinite(side) ? std::min(z, std::max(side - depth, z - maxCut)) : z;
}

void cutChannel(Heightfield& out,
  const std::vector<std::size_t>& order,
  const std::vector<std::uint8_t>& line,
  double depth,
  double maxCut)
{
  for (std::size_t c : order)
  {
    out.z[c] = static_cast<float>(channelFloor(out, line, c, depth, maxCut));
  }
}

// Cells beside the lines take part of the cut their nearest line cell took
// after the smoothing (`before`: the terrain then): the whole cut within
// kCutFloorCells of it, fading to none `radius` cells away, never down below
// a floor `depth` above that line cell and rising away from it, so the line
// stays the lowest and water keeps to it.
void widenCuts(Heightfield& out,
  const Heightfield& before,
  const std::vector<std::uint8_t>& line,
  const NearestSeeds& near,
  double depth,
  double radius)
{
  for (std::size_t c = 0; c < out.size(); ++c)
  {
    if (line[c] != 0 || !out.isValid(c) || near.nearest[c] < 0 || !(near.distance[c] < radius))
    {
      continue;
    }
    const std::size_t at = nearestSeed(near, c);
    const double cut = static_cast<double>(before.z[at]) - out.z[at];
    if (cut > 0.0)
    {
      const double u =
        std::clamp((near.distance[c] - kCutFloorCells) / (radius - kCutFloorCells), 0.0, 1.0);
      const double lowered = out.z[c] - cut * (1.0 - u * u * (3.0 - 2.0 * u));
      // The floor falls towards the line across it, more steeply than the
      // line falls along (kFloorCrossFall channel depths per cell): level
      // with the line's own fall, D8 ran water down the floor beside the line
      // as well as down the line.
      const double floor = out.z[at] + depth * (1.0 + kFloorCrossFall * near.distance[c]);
      out.z[c] = static_cast<float>(std::max(lowered, std::min<double>(out.z[c], floor)));
    }
  }
}

constexpr std::uint32_t kOffLines = 0;

// Per cell, a label shared by the cells of one line network (8-connected
// cells with a finite flow distance), kOffLines elsewhere.
std::vector<std::uint32_t> labelNetworks(const Heightfield& hf, const std::vector<float>& flow)
{
  std::vector<std::uint32_t> label(flow.size(), kOffLines);
  std::uint32_t next = kOffLines;
  std::vector<std::size_t> stack;
  for (std::size_t seed = 0; seed < flow.size(); ++seed)
  {
    if (!std::isfinite(flow[seed]) || label[seed] != kOffLines)
    {
      continue;
    }
    label[seed] = ++next;
    stack.push_back(seed);
    while (!stack.empty())
    {
      const std::size_t c = stack.back();
      stack.pop_back();
      const GridCell at = cellOf(c, hf.width);
      forNeighbours(hf,
        at.i,
        at.j,
        [&](std::size_t q, double)
        {
          if (std::isfinite(flow[q]) && label[q] == kOffLines)
          {
            label[q] = next;
            stack.push_back(q);
          }
        });
    }
  }
  return label;
}

// Whether water at cell c leaves the map: on its border or beside nodata.
bool onTheEdge(const Heightfield& hf, std::size_t c)
{
  const auto [i, j] = cellOf(c, hf.width);
  if (i == 0 || j == 0 || i == hf.width - 1 || j == hf.height - 1)
  {
    return true;
  }
  for (std::size_t n = 0; n < kDx.size(); ++n)
  {
    if (!hf.isValid(i + kDx[n], j + kDy[n]))
    {
      return true;
    }
  }
  return false;
}

// The way out of a closed outlet over the lowest crossing that does not run
// back up the outlet's own network: cells are flooded from the outlet in order
// of height, never into that network, until the flood reaches the map's edge
// (or nodata) or another network's line. The way back from there is the one
// whose highest cell is as low as any way out's, the crossing breaching cuts.
// Returns the cells from the outlet's neighbour to that end. The flood covers
// the basin up to its spill height, so what it reached is kept in a map, not
// in a full-size array.
std::vector<std::size_t> lowestWayOut(const Heightfield& out,
  const std::vector<std::uint32_t>& network,
  std::size_t outlet)
{
  using Entry = std::pair<float, std::size_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> flood;
  std::unordered_map<std::size_t, std::size_t> parent{ { outlet, outlet } };
  flood.emplace(out.z[outlet], outlet);
  std::size_t end = outlet;
  while (!flood.empty() && end == outlet)
  {
    const std::size_t c = flood.top().second;
    flood.pop();
    const auto [i, j] = cellOf(c, out.width);
    const bool otherLine = network[c] != kOffLines && network[c] != network[outlet];
    forNeighbours(out,
      i,
      j,
      [&](std::size_t q, double)
      {
        if (network[q] != network[outlet] && parent.emplace(q, c).second)
        {
          flood.emplace(out.z[q], q);
        }
      });
    end = (c != outlet && (otherLine || onTheEdge(out, c))) ? c : outlet;
  }
  std::vector<std::size_t> way;
  for (std::size_t k = end; k != outlet; k = parent.at(k))
  {
    way.push_back(k);
  }
  std::reverse(way.begin(), way.end());
  return way;
}

// Metres between two neighbouring cells.
double stepLength(const Heightfield& hf, std::size_t a, std::size_t b)
{
  const auto w = static_cast<std::ptrdiff_t>(hf.width);
  const auto ia = static_cast<std::ptrdiff_t>(a);
  const auto ib = static_cast<std::ptrdiff_t>(b);
  return std::hypot(static_cast<double>(ib % w - ia % w) * hf.cellX,
    static_cast<double>(ib / w - ia / w) * hf.cellY);
}

// Per line cell, the channel floor (below its sides) fitted, in the least-
// squares sense, by floors that rise with the flow distance at `gradient` at
// least (pool adjacent violators over the cells sorted by flow distance), each
// network on its own: unconnected valleys drain apart, and pooled together a
// high valley's floors were pulled down towards a low one's and the low one's up.
std::vector<double> monotoneFloors(const Heightfield& out,
  const std::vector<std::size_t>& upstreamFirst,
  const std::vector<std::uint8_t>& line,
  const std::vector<std::uint32_t>& network,
  const std::vector<float>& downstream,
  double depth,
  double maxCut,
  double gradient)
{
  struct Block
  {
    double sum = 0.0;
    double count = 0.0;
    std::size_t first = 0, last = 0;
    std::uint32_t network = kOffLines;
    double mean() const { return sum / count; }
  };
  // Outlet first within each network; the minimum gradient is taken out and
  // put back afterwards.
  std::vector<std::size_t> outletFirst(upstreamFirst.rbegin(), upstreamFirst.rend());
  std::stable_sort(outletFirst.begin(),
    outletFirst.end(),
    [&](std::size_t a, std::size_t b) { return network[a] < network[b]; });
  std::vector<Block> blocks;
  for (std::size_t r = 0; r < outletFirst.size(); ++r)
  {
    const std::size_t c = outletFirst[r];
    const double channel = channelFloor(out, line, c, depth, maxCut);
    blocks.push_back({ channel - gradient * downstream[c], 1.0, r, r, network[c] });
    while (blocks.size() > 1 && blocks[blocks.size() - 2].network == blocks.back().network &&
      blocks[blocks.size() - 2].mean() > blocks.back().mean())
    {
      const Block top = blocks.back();
      blocks.pop_back();
      blocks.back().sum += top.sum;
      blocks.back().count += top.count;
      blocks.back().last = top.last;
    }
  }
  std::vector<double> floors(out.size(), 0.0);
  for (const Block& b : blocks)
  {
    for (std::size_t r = b.first; r <= b.last; ++r)
    {
      const std::size_t c = outletFirst[r];
      floors[c] = b.mean() + gradient * downstream[c];
    }
  }
  return floors;
}

// The mean of a per line cell value over the line cells within `radius`.
std::vector<double> meanAlongLines(const std::vector<double>& values,
  const std::vector<std::uint8_t>& line,
  int w,
  int h,
  double radius)
{
  const int r = std::max(1, static_cast<int>(std::ceil(radius)));
  std::vector<double> mean(values.size(), 0.0);
  for (std::size_t c = 0; c < values.size(); ++c)
  {
    if (line[c] == 0)
    {
      continue;
    }
    const auto [i, j] = cellOf(c, w);
    double sum = 0.0;
    double count = 0.0;
    for (int y = std::max(0, j - r); y <= std::min(h - 1, j + r); ++y)
    {
      for (int x = std::max(0, i - r); x <= std::min(w - 1, i + r); ++x)
      {
        const std::size_t q = rowMajor(x, y, w);
        if (line[q] != 0 && (x - i) * (x - i) + (y - j) * (y - j) <= radius * radius)
        {
          sum += values[q];
          count += 1.0;
        }
      }
    }
    mean[c] = sum / count;
  }
  return mean;
}

} // namespace

double correctLandform(Heightfield& out,
  const Heightfield& lowTarget,
  const std::vector<float>& confidence,
  double sigma)
{
  if (!(sigma > 0.0))
  {
    return 0.0;
  }
  const Heightfield lowOut = smoothLarge(out, sigma);
  double largest = 0.0;
  for (std::size_t c = 0; c < out.size(); ++c)
  {
    if (out.isValid(c) && lowTarget.isValid(c))
    {
      const double w = confidence.empty() ? 1.0 : confidence[c];
      const double change = w * (lowTarget.z[c] - lowOut.z[c]);
      out.z[c] = static_cast<float>(out.z[c] + change);
      largest = std::max(largest, std::abs(change));
    }
  }
  return largest;
}

double correctLandformAtScales(Heightfield& out,
  const Heightfield& target,
  const std::vector<float>& confidence,
  const std::vector<float>& sigma,
  double largestSigma,
  double finestSigma,
  double targetSigma)
{
  if (!(largestSigma > 0.0))
  {
    return 0.0;
  }
  float finest = static_cast<float>(largestSigma);
  for (float s : sigma)
  {
    finest = std::min(finest, s);
  }
  finest = std::max(finest, static_cast<float>(std::min(finestSigma, largestSigma)));
  // The levels, coarsest first, and each one's correction per cell.
  std::vector<double> levels{ largestSigma };
  while (levels.back() * 0.5 >= finest * (1.0 - 1e-6))
  {
    levels.push_back(levels.back() * 0.5);
  }
  if (levels.back() > finest)
  {
    levels.push_back(finest);
  }
  // The scale asked for, made smooth from cell to cell (in log sigma, over
  // the finest level): where it jumped (at a medial axis, between a ridge's
  // width and a valley's) the blend of two levels' corrections jumped with it
  // and cut a crease into the terrain.
  Heightfield logSigma(out.width, out.height, 0.0f);
  for (std::size_t c = 0; c < out.size(); ++c)
  {
    const double want = c < sigma.size() ? sigma[c] : largestSigma;
    logSigma.z[c] = static_cast<float>(std::log(std::clamp(want, levels.back(), levels.front())));
  }
  logSigma = smoothLarge(logSigma, levels.back());
  // The confidence too: it kinks where the nearest landform changes (a medial
  // axis), and times a correction of hundreds of metres the kink is a crease.
  Heightfield sure(out.width, out.height, 1.0f);
  if (!confidence.empty())
  {
    std::copy(confidence.begin(), confidence.end(), sure.z.begin());
    sure = smoothLarge(sure, levels.back());
  }
  // Each level's correction, made one at a time: a cell is corrected when the
  // two levels around its scale are at hand (the only one, with one level),
  // into a copy, since every level is measured on the uncorrected terrain.
  // Two corrections are held, not every level's (seven fields at 4096 x 4096).
  // Between levels l - 1 (coarser) and l: the first l from 1 at or below the
  // scale asked for, else the last.
  const auto wantAt = [&](std::size_t c) {
    return std::clamp(std::exp(static_cast<double>(logSigma.z[c])), levels.back(), levels.front());
  };
  if (levels.size() > std::numeric_limits<std::uint8_t>::max())
  {
    throw Error("Internal error: the landform correction has too many levels.");
  }
  std::vector<std::uint8_t> pair(out.size(), 0);
  for (std::size_t c = 0; c < out.size(); ++c)
  {
    const double want = wantAt(c);
    std::size_t l = 1;
    while (l + 1 < levels.size() && levels[l] > want)
    {
      ++l;
    }
    pair[c] = static_cast<std::uint8_t>(l);
  }
  const auto correctionAt = [&](double level)
  {
    const Heightfield lowOut = smoothLarge(out, level);
    Heightfield lowTarget =
      smoothLarge(target, targetSigma > 0.0 ? std::min(level, targetSigma) : level);
    // The change is written over the low-passed target, cell by cell after
    // reading it: one plane fewer at the finishing's peak.
    for (std::size_t c = 0; c < out.size(); ++c)
    {
      const bool known = out.isValid(c) && lowTarget.isValid(c) && lowOut.isValid(c);
      lowTarget.z[c] = known ? lowTarget.z[c] - lowOut.z[c] : 0.0f;
    }
    return std::move(lowTarget.z);
  };
  std::vector<float> corrected = out.z;
  double largest = 0.0;
  const auto apply = [&](std::size_t c, double value)
  {
    const double w = sure.z[c];
    corrected[c] = static_cast<float>(out.z[c] + w * value);
    largest = std::max(largest, std::abs(w * value));
  };
  std::vector<float> coarser = correctionAt(levels.front());
  if (levels.size() == 1)
  {
    for (std::size_t c = 0; c < out.size(); ++c)
    {
      if (out.isValid(c))
      {
        apply(c, coarser[c]);
      }
    }
  }
  for (std::size_t l = 1; l < levels.size(); ++l)
  {
    std::vector<float> finer = correctionAt(levels[l]);
    for (std::size_t c = 0; c < out.size(); ++c)
    {
      if (!out.isValid(c) || pair[c] != l)
      {
        continue;
      }
      const double t = std::clamp(
        std::log(levels[l - 1] / wantAt(c)) / std::log(levels[l - 1] / levels[l]), 0.0, 1.0);
      apply(c, (1.0 - t) * coarser[c] + t * finer[c]);
    }
    coarser = std::move(finer);
  }
  out.z = std::move(corrected);
  return largest;
}

// The flow distances of the lines, continued past each outlet that lies
// inside the map down the way complete breaching would drain it to the
// border (Hydrology/PitRemoval.h), with distances below 0: a valley whose end
// is a closed basin is led out of it as a channel of its own, shaped by the
// same fit and spread as the drawn lines, instead of filling to a lake that
// drowned its lower part. Where that way runs back up the valley's own lines
// (the land falls the other way along the valley, so breaching drains it
// backwards), the valley is led out over the lowest crossing that leaves its
// lines alone instead: without it a valley drawn to end in a closed basin
// came out as a lake hundreds of metres deep.
std::vector<float> throughClosedOutlets(const Heightfield& out,
  const std::vector<float>& downstream)
{
  std::vector<float> flow = downstream;
  const auto closed = [&](std::size_t c) { return downstream[c] <= 0.0f && !onTheEdge(out, c); };
  bool anyClosed = false;
  for (std::size_t c = 0; c < out.size() && !anyClosed; ++c)
  {
    anyClosed = closed(c);
  }
  if (!anyClosed)
  {
    return flow; // every outlet lets its water leave the map: no way out to find
  }
  const Heightfield breached = breachDepressions(out);
  const std::vector<std::int8_t> dir = flowDirections(breached);
  const std::vector<std::uint32_t> network = labelNetworks(out, downstream);
  for (std::size_t c = 0; c < out.size(); ++c)
  {
    if (!closed(c))
    {
      continue; // not an outlet, or one whose water leaves the map
    }
    std::vector<std::size_t> way;
    bool backUpItsOwnLines = false;
    for (std::size_t k = c; dir[k] != kNoFlow;)
    {
      k = offsetCell(k, d8Offset(dir[k], out.width));
      way.push_back(k);
      if (std::isfinite(flow[k]))
      {
        backUpItsOwnLines = network[k] == network[c];
        break; // joined a line (or a path already led out)
      }
    }
    if (backUpItsOwnLines)
    {
      way = lowestWayOut(out, network, c);
    }
    double distance = 0.0;
    std::size_t from = c;
    for (std::size_t k : way)
    {
      if (std::isfinite(flow[k]))
      {
        break;
      }
      distance -= stepLength(out, from, k);
      flow[k] = static_cast<float>(distance);
      from = k;
    }
  }
  return flow;
}

DrainageReport drainValleys(Heightfield& out,
  const std::vector<float>& drawnDownstream,
  const DrainageOptions& o)
{
  DrainageReport report;
  if (drawnDownstream.size() != out.size())
  {
    return report; // no valley lines on this grid
  }
  const std::vector<float> downstream = throughClosedOutlets(out, drawnDownstream);
  const std::vector<std::uint32_t> network = labelNetworks(out, downstream);
  std::vector<std::size_t> order;
  std::vector<std::uint8_t> line(out.size(), 0);
  for (std::size_t c = 0; c < out.size() && c < downstream.size(); ++c)
  {
    if (std::isfinite(downstream[c]) && out.isValid(c))
    {
      order.push_back(c);
      line[c] = 1;
    }
  }
  if (order.empty())
  {
    return report;
  }
  std::sort(order.begin(),
    order.end(),
    [&](std::size_t a, std::size_t b)
    { return downstream[a] > downstream[b] || (downstream[a] == downstream[b] && a < b); });
  // The line cells' heights before, for the report (the rest of the terrain
  // is not asked for).
  std::vector<float> before(order.size());
  for (std::size_t n = 0; n < order.size(); ++n)
  {
    before[n] = out.z[order[n]];
  }

  // 1. The floors the lines should have: each line cell below the cells beside
  // it (a channel), and descending towards the outlet with the least change in
  // the least-squares sense (isotonic regression over the flow distance:
  // bumps are cut and hollows filled, instead of one deep cut running down
  // from the lowest hollow).
  const double depth = o.channelDepth * std::min(out.cellX, out.cellY);
  const double maxCut = o.maximumChannelCut * std::min(out.cellX, out.cellY);
  const NearestSeeds near = nearestSeeds(line, out.width, out.height);
  // 2. The change made smooth along the lines and spread smoothly beside them
  // (a change that jumped from cell to cell, or a kink at the line, would show
  // as a crease); a few rounds of finer smoothing take it close to the floors
  // without creasing.
  for (int round = 0; round < kSmoothingRounds; ++round)
  {
    // Each plane of doubles is let go once the next is made from it: at
    // 4096 x 4096 each is 134 MB, and they set the finishing's peak.
    std::vector<double> change(out.size(), 0.0);
    {
      const std::vector<double> floors =
        monotoneFloors(out, order, line, network, downstream, depth, maxCut, o.minimumGradient);
      for (std::size_t c : order)
      {
        change[c] = floors[c] - out.z[c];
      }
    }
    const double radius = 0.5 * o.reach / static_cast<double>(1 << round);
    std::vector<double> smooth = meanAlongLines(change, line, out.width, out.height, radius);
    std::vector<double>().swap(change);
    Heightfield spread(out.width, out.height, 0.0f);
    for (std::size_t c = 0; c < out.size(); ++c)
    {
      if (!out.isValid(c) || near.nearest[c] < 0 || !(near.distance[c] < o.reach))
      {
        continue;
      }
      spread.z[c] =
        static_cast<float>(smooth[nearestSeed(near, c)] * biweight(near.distance[c] / o.reach));
    }
    // Each cell took the change of its nearest line cell, which steps from one
    // line cell to the next: spread out along those rays, the steps combed the
    // valley sides with creases across the line (the 99.9th-percentile
    // Laplacian of a valley network on Colorado 1.10 times the exemplar's;
    // 0.92 smoothed). Smoothed across as along the line, and faded again so
    // that nothing leaks past the reach.
    std::vector<double>().swap(smooth);
    spread = smoothLarge(spread, std::max(1.0, radius));
    for (std::size_t c = 0; c < out.size(); ++c)
    {
      if (out.isValid(c) && near.nearest[c] >= 0 && near.distance[c] < o.reach)
      {
        out.z[c] += spread.z[c] * static_cast<float>(biweight(near.distance[c] / o.reach));
      }
    }
  }
  // 3. What the smoothing left: the channel and the descent made exact by
  // lowering line cells, and those cuts widened into a narrow V beside the
  // line (a one-cell slot through a bump was the sharpest crease of the map).
  const Heightfield smoothed = out;
  cutChannel(out, order, line, depth, maxCut);
  descendAlongLines(out, order, downstream, o.minimumGradient);
  widenCuts(out, smoothed, line, near, depth, kCutWideningCells);

  double sum = 0.0;
  for (std::size_t n = 0; n < order.size(); ++n)
  {
    const std::size_t c = order[n];
    if (!std::isfinite(drawnDownstream[c]))
    {
      continue; // a way out of a closed basin, not a drawn line
    }
    ++report.cells;
    const double lowered = before[n] - out.z[c];
    report.lowered += lowered > 0.0 ? 1 : 0;
    report.largest = std::max(report.largest, lowered);
    sum += lowered;
  }
  report.mean = report.cells > 0 ? sum / static_cast<double>(report.cells) : 0.0;
  return report;
}

std::size_t compressIntoRange(Heightfield& out, double low, double high, double slack)
{
  if (!(slack > 0.0) || !(low <= high))
  {
    return 0;
  }
  std::size_t moved = 0;
  for (std::size_t c = 0; c < out.size(); ++c)
  {
    if (!out.isValid(c))
    {
      continue;
    }
    const double z = out.z[c];
    if (z < low)
    {
      out.z[c] = static_cast<float>(low - slack * std::tanh((low - z) / slack));
      ++moved;
    }
    else if (z > high)
    {
      out.z[c] = static_cast<float>(high + slack * std::tanh((z - high) / slack));
      ++moved;
    }
  }
  return moved;
}

void meetConstraints(Heightfield& out, const FeatureGraph& graph, double reach)
{
  const int w = out.width;
  const int h = out.height;
  std::vector<double> correction(out.size(), kNaN);
  std::vector<std::uint8_t> onLine(out.size(), 0);
  bool any = false;
  for (const FeatureChain& c : graph.chains)
  {
    if (c.constraint.size() != c.points.size())
    {
      continue;
    }
    // Heights along the chain: given values, linear in between, none past the ends.
    std::vector<double> z(c.points.size(), kNaN);
    std::size_t last = c.points.size();
    for (std::size_t k = 0; k < c.points.size(); ++k)
    {
      if (std::isnan(c.constraint[k]))
      {
        continue;
      }
      z[k] = c.constraint[k];
      if (last < c.points.size())
      {
        for (std::size_t m = last + 1; m < k; ++m)
        {
          const double t = static_cast<double>(m - last) / static_cast<double>(k - last);
          z[m] = (1 - t) * c.constraint[last] + t * c.constraint[k];
        }
      }
      last = k;
    }
    forEachChainCell(c,
      w,
      h,
      [&](int i, int j, std::size_t k, double t)
      {
        if (std::isnan(z[k - 1]) || std::isnan(z[k]) || !out.isValid(i, j))
        {
          return;
        }
        const std::size_t cell = out.index(i, j);
        correction[cell] = (1 - t) * z[k - 1] + t * z[k] - out.z[cell];
        onLine[cell] = 1;
        any = true;
      });
  }
  if (!any)
  {
    return;
  }
  const std::vector<float> d = distanceTransform(onLine, w, h);
  std::vector<std::uint8_t> unknown(out.size(), 0);
  for (std::size_t c = 0; c < out.size(); ++c)
  {
    if (onLine[c] == 0)
    {
      // Unknown within reach, else Dirichlet: no change.
      unknown[c] = d[c] < reach && out.isValid(c) ? 1 : 0;
      correction[c] = 0.0;
    }
  }
  std::vector<double> zero(out.size(), 0.0);
  MaskedPoissonSolver solver;
  PoissonOptions po;
  po.tolerance = 1e-6;
  solver.solveLaplacian(
    w, h, out.cellX, out.cellY, unknown.data(), zero.data(), correction.data(), po);
  for (std::size_t c = 0; c < out.size(); ++c)
  {
    if (out.isValid(c) && std::isfinite(correction[c]))
    {
      out.z[c] = static_cast<float>(out.z[c] + correction[c]);
    }
  }
}

namespace
{

// The coarsest scale of the landform correction, cells.
double correctionScale(const FinishingPlan& plan)
{
  return plan.correctionScale < 0.0 ? kCorrectionScaleInPatches * plan.patchSize
                                    : plan.correctionScale;
}

// Per cell, the scale the landform correction pulls the relief coarser than
// towards the target: kCorrectionShareOfHalfWidth of the sketched landform's
// half width there, at most correctionScale().
std::vector<float> correctionScales(const SynthesisTarget& target, const FinishingPlan& plan)
{
  const float largest = static_cast<float>(correctionScale(plan));
  std::vector<float> sigma(target.field.size(), largest);
  if (target.halfWidth.size() == sigma.size())
  {
    for (std::size_t c = 0; c < sigma.size(); ++c)
    {
      sigma[c] =
        std::min(largest, static_cast<float>(kCorrectionShareOfHalfWidth * target.halfWidth[c]));
    }
  }
  return sigma;
}

void drainEverywhere(Heightfield& out, PitRemovalMethod method, int patchSize, FinishingReport& f)
{
  MultiscalePitRemovalOptions d;
  d.pitRemoval.method = method;
  d.coarsestFactor = std::max(1, static_cast<int>(kPitRemovalCoarsestInPatches * patchSize));
  const MultiscalePitRemovalReport r = removePitsMultiscale(out, d);
  f.drained = true;
  f.pitsBefore = r.pitsBefore;
  f.pitsAfter = r.pitsAfter;
  f.largestDrainageRaise = r.largestRaise;
  f.largestDrainageLowering = r.largestLowering;
  f.meanDrainageChange = r.meanAbsoluteChange;
}

} // namespace

FinishingReport finishSynthesis(Heightfield& out,
  const SynthesisTarget& target,
  const std::vector<float>& confidence,
  const FinishingPlan& plan)
{
  if (out.width != target.field.width || out.height != target.field.height)
  {
    throw Error("The terrain to finish and its target differ in size.");
  }
  const double P = plan.patchSize;
  FinishingReport f;
  f.landformCorrection = correctLandformAtScales(out,
    target.field,
    confidence,
    correctionScales(target, plan),
    correctionScale(plan),
    kFinestCorrectionInPatches * P,
    target.detailed ? 0.0 : kDrawnTargetSigmaCells);
  {
    // Free land: only the drift at the scale of several patches.
    std::vector<float> free(confidence.size());
    std::transform(
      confidence.begin(), confidence.end(), free.begin(), [](float w) { return 1.0f - w; });
    const double drift = kDriftScaleInPatches * P;
    correctLandform(out, smoothLarge(target.field, drift), free, drift);
  } // the weights go before the drainage's planes come
  if (plan.drainValleys)
  {
    DrainageOptions d;
    d.reach = kDrainageReachInPatches * P;
    const DrainageReport r = drainValleys(out, target.downstream, d);
    f.valleyCells = r.cells;
    f.valleyCellsLowered = r.lowered;
    f.deepestValleyCut = r.largest;
    f.meanValleyCut = r.mean;
  }
  // A patch holding a deep valley, merged where the land had already come
  // down to the exemplars' lowest, took the land past it (a spiral on Mont
  // Blanc, seed 3: 650 m under its lowest land, though every patch's free
  // border kept within the merge's bounds). Height constraints come after:
  // the user's heights win.
  f.cellsBroughtIntoRange = compressIntoRange(out, plan.lowest, plan.highest, plan.slack);
  meetConstraints(out, target.graph, P);
  if (plan.drainage)
  {
    drainEverywhere(out, *plan.drainage, plan.patchSize, f);
  }
  return f;
}

} // namespace tsynth
