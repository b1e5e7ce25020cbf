#include "Preview.h"

#include "../Core/Error.h"
#include "../Core/Grid.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace tsynth
{

namespace
{

// The preview's patches are small (20 cells for the default 80) and its
// exemplars a sixteenth of the cells: the CPU matcher answers sooner than
// OpenCL's set-up and transfers, with the same bits (the backends agree).
constexpr Backend kPreviewBackend = Backend::Cpu;

// Fill candidates compared by their seams in the preview: the seam dry runs are
// much of a small patch's cost, and the preview's seams are blurred by the
// upsampling anyway.
constexpr std::size_t kPreviewFillCandidates = 1;
// The preview's fill windows stand as far apart as they may (a quarter patch of
// overlap, no jitter): 0.44 times as many patches as at half a patch, fill 0.43
// -> 0.17 s for 1024^2 from Colorado, and no seam showed in its hillshade.
constexpr double kPreviewFillSpacing = kMaxFillSpacing;

int coarsePatch(int patchSize, int factor)
{
  return patchSize / factor / kPatchSizeStep * kPatchSizeStep;
}

// Enough coarse cells that their centres reach the last full cell's centre.
int coarseCells(int cells, int factor)
{
  return (cells - 1 + factor - 1) / factor + 1;
}

} // namespace

PreviewPlan planPreview(const SetupInputs& full)
{
  PreviewPlan plan;
  plan.full = plannedGrid(full);
  for (int factor = kPreviewCoarsening; factor > 1; factor /= 2)
  {
    if (coarsePatch(full.patchSize, factor) >= kMinSynthesisPatch)
    {
      plan.factor = factor;
      break;
    }
  }
  plan.coarse = plan.full;
  plan.patchSize = full.patchSize;
  if (plan.available())
  {
    plan.coarse.width = coarseCells(plan.full.width, plan.factor);
    plan.coarse.height = coarseCells(plan.full.height, plan.factor);
    plan.coarse.cellX = plan.full.cellX * plan.factor;
    plan.coarse.cellY = plan.full.cellY * plan.factor;
    plan.patchSize = coarsePatch(full.patchSize, plan.factor);
  }
  return plan;
}

SetupInputs previewInputs(const SetupInputs& full, const PreviewPlan& plan)
{
  SetupInputs in = full;
  in.grid.width = plan.coarse.width;
  in.grid.height = plan.coarse.height;
  in.grid.cellX = plan.coarse.cellX;
  in.grid.cellY = plan.coarse.cellY;
  in.patchSize = plan.patchSize;
  in.rasterSketchPatch = full.rasterSketchPatch > 0 ? full.rasterSketchPatch : full.patchSize;
  in.matcherBackend = kPreviewBackend;
  in.pool = nullptr; // a given pool is the whole synthesis', at its patch size and cells
  return in;
}

SynthesisOptions previewOptions(const SynthesisOptions& full, const PreviewPlan& plan)
{
  SynthesisOptions o = full;
  o.patchSize = plan.patchSize;
  o.backend = kPreviewBackend;
  o.fillK = std::min(o.fillK, kPreviewFillCandidates);
  o.fillSpacing = std::max(o.fillSpacing, kPreviewFillSpacing);
  o.pool = nullptr;     // the preview set-up's, at its patch size
  o.previous = nullptr; // tile records are the whole synthesis', at its patch size
  o.keepRecord = false;
  if (o.correctionScale > 0.0)
  {
    o.correctionScale /= plan.factor; // given in the full grid's cells
  }
  if (!full.regionLabels.empty())
  {
    o.regionLabels.assign(cellCount(plan.coarse.width, plan.coarse.height), -1);
    for (int j = 0; j < plan.coarse.height; ++j)
    {
      const int fj = std::min(plan.full.height - 1, j * plan.factor);
      for (int i = 0; i < plan.coarse.width; ++i)
      {
        const int fi = std::min(plan.full.width - 1, i * plan.factor);
        o.regionLabels[rowMajor(i, j, plan.coarse.width)] =
          full.regionLabels[rowMajor(fi, fj, plan.full.width)];
      }
    }
  }
  return o;
}

Heightfield upsampleOnto(const Heightfield& coarse, const OutputGrid& full)
{
  Heightfield out(full.width, full.height, std::numeric_limits<float>::quiet_NaN());
  out.cellX = full.cellX;
  out.cellY = full.cellY;
  out.cellSizeKnown = true;
  out.sourceZUnit = coarse.sourceZUnit;
  // The coarse cells either side of a full cell's centre and the weight of the
  // second (the same cell twice where the centres coincide, so that a nodata
  // neighbour of weight 0 does not spread).
  struct Span
  {
    int first = 0;
    int second = 0;
    double t = 0.0;
  };
  auto locate = [](int i, double fullCell, double coarseCell, int coarseCells)
  {
    const double x = std::min(i * fullCell / coarseCell, coarseCells - 1.0);
    Span s;
    s.first = std::min(static_cast<int>(x), coarseCells - 1);
    s.t = x - s.first;
    s.second = s.t > 0.0 ? std::min(s.first + 1, coarseCells - 1) : s.first;
    return s;
  };
  for (int j = 0; j < full.height; ++j)
  {
    const Span y = locate(j, full.cellY, coarse.cellY, coarse.height);
    for (int i = 0; i < full.width; ++i)
    {
      const Span x = locate(i, full.cellX, coarse.cellX, coarse.width);
      if (coarse.isValid(x.first, y.first) && coarse.isValid(x.second, y.first) &&
        coarse.isValid(x.first, y.second) && coarse.isValid(x.second, y.second))
      {
        const double south =
          (1 - x.t) * coarse.at(x.first, y.first) + x.t * coarse.at(x.second, y.first);
        const double north =
          (1 - x.t) * coarse.at(x.first, y.second) + x.t * coarse.at(x.second, y.second);
        out.at(i, j) = static_cast<float>((1 - y.t) * south + y.t * north);
      }
    }
  }
  normaliseMask(out);
  return out;
}

Preview synthesisePreview(const SetupInputs& full, const SynthesisOptions& options)
{
  const auto start = std::chrono::steady_clock::now();
  Preview p;
  p.plan = planPreview(full);
  if (!p.plan.available())
  {
    throw Error("No preview for a patch of " + std::to_string(full.patchSize) +
      " cells: a coarser level would need patches under " + std::to_string(kMinSynthesisPatch) +
      " cells; give a patch of at least " + std::to_string(kMinPreviewedPatch) + ".");
  }
  p.setup = prepareSynthesis(previewInputs(full, p.plan));
  p.prepareSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  p.result = synthesise(p.setup, previewOptions(options, p.plan));
  p.onFullGrid = upsampleOnto(p.result.terrain, p.plan.full);
  p.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return p;
}

} // namespace tsynth
