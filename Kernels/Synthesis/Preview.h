// A quick look before the whole synthesis: the same sketch and exemplars on
// cells a few times coarser, with patches as many times smaller, so that every
// patch covers the same ground and the preview shows the same landforms at the
// same places, only with less detail. The command line writes it first
// (tsynth synth --preview) and the filter shows it while the whole synthesis
// refines it in the background (vtkTerrainSynthesis::PreviewFirst).
#pragma once

#include "Setup.h"

namespace tsynth
{

// The preview's cells are this many times coarser a side (a 1024^2 terrain is
// previewed on 257^2 cells), or half that when the patch would otherwise be
// smaller than kMinSynthesisPatch.
constexpr int kPreviewCoarsening = 4;
// The smallest patch with a preview: halved, it is still a patch the synthesis
// takes (front ends refuse a preview for less before any work).
constexpr int kMinPreviewedPatch = 2 * kMinSynthesisPatch;

// The whole synthesis and its preview level.
struct PreviewPlan
{
  int factor = 1;    // how much coarser a side; 1: no coarser level takes a patch
  OutputGrid full;   // the terrain asked for
  OutputGrid coarse; // the preview's grid: the same ground on coarser cells
  int patchSize = 0; // the preview's patch, in its own cells
  bool available() const { return factor > 1; }
};

// The plan for these inputs (the same grid prepareSynthesis() will make). Throws
// tsynth::Error as outputGrid() does.
PreviewPlan planPreview(const SetupInputs& full);

// The set-up and synthesis options of the preview level: the grid and patch of
// the plan, the style-region labels taken at the coarse cells, and a quicker
// fill: one candidate per window, windows spaced as wide as they may be
// (kMaxFillSpacing).
SetupInputs previewInputs(const SetupInputs& full, const PreviewPlan& plan);
SynthesisOptions previewOptions(const SynthesisOptions& full, const PreviewPlan& plan);

// A preview's heights on the whole synthesis' grid (bilinear between the coarse
// cell centres, clamped at the far edges; a cell next to a coarse nodata cell is
// nodata): what a front end shows in place of the terrain until it is done.
Heightfield upsampleOnto(const Heightfield& coarse, const OutputGrid& full);

struct Preview
{
  PreviewPlan plan;
  SynthesisSetup setup;        // at the preview's grid
  SynthesisResult result;      // at the preview's grid
  Heightfield onFullGrid;      // result.terrain upsampled onto plan.full
  double prepareSeconds = 0.0; // the set-up (sketch, exemplars at the coarse cells, target)
  double seconds = 0.0;        // set-up, synthesis and upsampling, wall clock
};

// The preview of what synthesise(prepareSynthesis(full), options) would give.
// Throws tsynth::Error when the plan has no coarser level (a patch under
// kMinPreviewedPatch) or the inputs are unusable, tsynth::Cancelled when the
// caller's CancellationScope says stop.
Preview synthesisePreview(const SetupInputs& full, const SynthesisOptions& options);

} // namespace tsynth
