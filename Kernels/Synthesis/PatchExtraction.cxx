#include "PatchExtraction.h"

#include "../Core/Grid.h"
#include "../Matching/Orientation.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tsynth
{
namespace
{

// A patch's height leans towards the target on its empty part with this
// weight per cell (times the confidence) against 1 per overlapping cell: enough
// to stop drift along a line of patches, small enough that the seams the
// merge has to absorb stay small.
constexpr double kTargetPull = 1.0;
// Overlap this small (a share of the window) says too little about a patch's
// height: the target decides its vertical offset instead.
constexpr double kMinOverlapForOffset = 0.05;

} // namespace

Heightfield extractPatch(const Heightfield& oriented,
  double orientedCentreX,
  double orientedCentreY,
  int exemplarWidth,
  int exemplarHeight,
  const PatchCandidate& candidate,
  int patchSize)
{
  // The candidate's centre in the oriented copy: m^-1 (centre - exemplar centre).
  const Variant v = variant(candidate.variant);
  const double dx = candidate.centreX - 0.5 * (exemplarWidth - 1);
  const double dy = candidate.centreY - 0.5 * (exemplarHeight - 1);
  const double det = v.m[0] * v.m[3] - v.m[1] * v.m[2];
  const int x0 = windowCorner(orientedCentreX + (v.m[3] * dx - v.m[1] * dy) / det, patchSize);
  const int y0 = windowCorner(orientedCentreY + (-v.m[2] * dx + v.m[0] * dy) / det, patchSize);
  Heightfield patch(patchSize, patchSize, std::numeric_limits<float>::quiet_NaN());
  patch.cellX = oriented.cellX;
  patch.cellY = oriented.cellY;
  patch.valid.assign(patch.size(), 0);
  for (int j = 0; j < patchSize; ++j)
  {
    for (int i = 0; i < patchSize; ++i)
    {
      const int x = x0 + i;
      const int y = y0 + j;
      if (x >= 0 && y >= 0 && x < oriented.width && y < oriented.height && oriented.isValid(x, y))
      {
        patch.at(i, j) = oriented.at(x, y);
        patch.valid[patch.index(i, j)] = 1;
      }
    }
  }
  normaliseMask(patch);
  return patch;
}

Heightfield extractPatch(const Heightfield& exemplar,
  const PatchCandidate& candidate,
  int patchSize)
{
  double cx = 0.0;
  double cy = 0.0;
  const Heightfield oriented = orientExemplar(exemplar, variant(candidate.variant), &cx, &cy);
  return extractPatch(oriented, cx, cy, exemplar.width, exemplar.height, candidate, patchSize);
}

float fitPatchOffset(const Heightfield& patch, int x0, int y0, const OffsetFitGrid& grid)
{
  const Heightfield& out = grid.terrain;
  const bool hasTarget = grid.lowTarget.size() == out.size();
  double sum = 0.0;
  double weight = 0.0;
  double sTarget = 0.0;
  double nTarget = 0.0;
  for (int j = 0; j < patch.height; ++j)
  {
    for (int i = 0; i < patch.width; ++i)
    {
      const int x = x0 + i;
      const int y = y0 + j;
      if (!patch.isValid(i, j) || x < 0 || y < 0 || x >= out.width || y >= out.height)
      {
        continue;
      }
      const std::size_t c = out.index(x, y);
      const bool targetHere = hasTarget && grid.lowTarget.isValid(c);
      if (grid.filled[c] != 0)
      {
        sum += static_cast<double>(out.z[c]) - patch.at(i, j);
        weight += 1.0;
      }
      else if (targetHere)
      {
        const double w = kTargetPull * grid.confidence[c];
        sum += w * (static_cast<double>(grid.lowTarget.z[c]) - patch.at(i, j));
        weight += w;
      }
      if (targetHere)
      {
        sTarget += static_cast<double>(grid.lowTarget.z[c]) - patch.at(i, j);
        nTarget += 1.0;
      }
    }
  }
  if (weight >= kMinOverlapForOffset * patch.width * patch.height)
  {
    return static_cast<float>(sum / weight);
  }
  return nTarget > 0 ? static_cast<float>(sTarget / nTarget) : 0.0f;
}

std::vector<std::uint8_t> featureCore(const std::vector<std::uint8_t>& line,
  int outputWidth,
  int outputHeight,
  int x0,
  int y0,
  int patchSize)
{
  const int P = patchSize;
  std::vector<std::uint8_t> core(cellCount(P, P), 0);
  for (int j = 0; j < P; ++j)
  {
    for (int i = 0; i < P; ++i)
    {
      const int x = x0 + i;
      const int y = y0 + j;
      const bool onLine = !line.empty() && x >= 0 && y >= 0 && x < outputWidth &&
        y < outputHeight && line[rowMajor(x, y, outputWidth)] != 0;
      // Within the disc, or on the line within its reach; the square test
      // spares hypot for the many cells outside both.
      const double limit = onLine ? std::max(kCoreDiscInPatches, kLineOffsetReachInPatches) * P
                                  : kCoreDiscInPatches * P;
      const double di = i - 0.5 * (P - 1);
      const double dj = j - 0.5 * (P - 1);
      if (std::abs(di) <= limit && std::abs(dj) <= limit && std::hypot(di, dj) <= limit)
      {
        core[rowMajor(i, j, P)] = 1;
      }
    }
  }
  return core;
}

std::vector<Point2> ownLineOffsets(const ChainPointGrid& lines,
  FeatureType type,
  const PatchCandidate& candidate,
  int patchSize)
{
  std::vector<Point2> offsets;
  const Variant v = variant(candidate.variant);
  const double det = v.m[0] * v.m[3] - v.m[1] * v.m[2];
  const double reach = kLineOffsetReachInPatches * patchSize;
  lines.forEachNear(type,
    candidate.centreX,
    candidate.centreY,
    reach,
    [&](const Point2& q)
    {
      const double dx = q.x - candidate.centreX;
      const double dy = q.y - candidate.centreY;
      if (std::hypot(dx, dy) <= reach)
      {
        // Source offset = m (u, v): the placed offset is m^-1 times the source one.
        offsets.push_back(
          { (v.m[3] * dx - v.m[1] * dy) / det, (-v.m[2] * dx + v.m[0] * dy) / det });
      }
    });
  return offsets;
}

void addOwnLineStrip(std::vector<std::uint8_t>& core,
  const std::vector<Point2>& ownLine,
  int patchSize)
{
  // As wide as the drawn line's: a one-cell strip forced into the old content
  // left seams along the crest.
  const int half = static_cast<int>(kLineHalfWidth);
  const int P = patchSize;
  for (const Point2& q : ownLine)
  {
    const int ci = static_cast<int>(std::lround(q.x)) + P / 2;
    const int cj = static_cast<int>(std::lround(q.y)) + P / 2;
    for (int j = std::max(0, cj - half); j <= std::min(P - 1, cj + half); ++j)
    {
      for (int i = std::max(0, ci - half); i <= std::min(P - 1, ci + half); ++i)
      {
        if ((i - ci) * (i - ci) + (j - cj) * (j - cj) <= half * half)
        {
          core[rowMajor(i, j, P)] = 1;
        }
      }
    }
  }
}

void protectKeptCells(Heightfield& patch, int x0, int y0, const KeptCells& kept)
{
  bool any = false;
  for (int j = 0; j < patch.height; ++j)
  {
    for (int i = 0; i < patch.width; ++i)
    {
      const int x = x0 + i;
      const int y = y0 + j;
      if (x < 0 || y < 0 || x >= kept.width || y >= kept.height)
      {
        continue;
      }
      const std::size_t c = rowMajor(x, y, kept.width);
      const bool keep = kept.line[c] != 0 || (!kept.frozen.empty() && kept.frozen[c] != 0);
      if (keep && kept.filled[c] != 0)
      {
        if (!any)
        {
          patch.valid.resize(patch.size(), 1);
          any = true;
        }
        patch.valid[patch.index(i, j)] = 0;
        patch.at(i, j) = std::numeric_limits<float>::quiet_NaN();
      }
    }
  }
}

const std::vector<OptionRow>& patchExtractionOptionRows()
{
  static const std::vector<OptionRow> rows = {
    numberRow("Rank", "", OptionType::Integer, 0, 0, kUnbounded),
    switchRow("VerticalOffset", "", true),
  };
  return rows;
}

} // namespace tsynth
