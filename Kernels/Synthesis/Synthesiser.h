// Sketch-driven, patch-based terrain synthesis (Zhou et al. 2007; Tasse's
// thesis): feature patches placed breadth-first along the target's feature
// tree, then best-first non-feature filling, every patch chosen among the
// matcher's top k by its graph-cut seam cost and merged in the gradient domain.
// In ParaView: vtkTerrainSynthesis (Terrain Synthesis), in Filters/.
#pragma once

#include "../Core/Heightfield.h"
#include "../Core/PatchSize.h"
#include "../Core/Progress.h"
#include "../Features/FeatureGraph.h"
#include "../Hydrology/PitRemoval.h"
#include "../Matching/PatchMatcher.h"
#include "../Merging/PatchMerger.h"
#include "FillOrder.h"
#include "Finishing.h"
#include "OptionLimits.h"
#include "Target.h"

#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace tsynth
{

struct PlacementRecord; // TileRecord.h

// SynthesisOptions::placementLimit of a whole synthesis: every placement, then the finishing.
constexpr std::size_t kAllPlacements = std::numeric_limits<std::size_t>::max();
// The placement limit a front end's number asks for (kAllPlacementsNumber,
// OptionLimits.h, or any negative: all).
constexpr std::size_t placementLimitOf(int limit)
{
  return limit < 0 ? kAllPlacements : static_cast<std::size_t>(limit);
}

struct SynthesisOptions
{
  int patchSize = kDefaultSynthesisPatch;
  Backend backend = Backend::Auto;
  MergeMode merge = MergeMode::New;
  FillOrder fill = FillOrder::BestFirst;
  // Seeds every arbitrary choice; the same seed gives the same bits on every backend.
  std::uint64_t seed = 0;
  // Candidates compared by seam cost per feature placement (per exemplar): 16
  // leave choices among the candidates that lay their own ridge or valley on
  // the stroke (within kLineOffsetSlack of the best-aligned); at 8 the median
  // line offset was 2.5 cells, but the seams cost 3.5 times as much.
  std::size_t k = 16;
  std::size_t fillK = 4; // ... per fill placement (8 measured no better, 20% slower)
  // How far apart the fill's windows stand, in patches (kDefaultFillSpacing, up
  // to kMaxFillSpacing: wider is fewer patches, so faster, with narrower overlaps).
  double fillSpacing = kDefaultFillSpacing;
  bool verticalOffset = true; // shift each patch to fit what it overlaps
  // Added to a candidate's seam cost (per seam edge) for every earlier placement
  // that took a source within half a patch of it: discourages visible repeats.
  double repetitionPenalty = 0.5;
  // The final correction (Tasse's final deformation): the output's relief
  // coarser than this Gaussian sigma (cells) is pulled towards the target's,
  // as far as the target is confident; where sketched landforms are narrower
  // it works at a third of their half width, down to kFinestCorrectionInPatches.
  // The detail finer stays the patches' own. <0: a sixth of a patch; 0: off.
  double correctionScale = -1.0;
  // Sketched valleys are made to drain: floors descend to their outlets and a
  // channel runs along them (Finishing.h).
  bool drainValleys = true;
  // Every cell made to drain at the very end (nullopt: off): pits removed by
  // this method on a pyramid of block means from a quarter patch down to 2
  // cells, the few-cell pits left then filled (MultiscalePitRemoval.h), so the
  // changes are broad and smooth and the seams stay hidden.
  std::optional<PitRemovalMethod> drainage;
  // Style regions (Zhou's Middle-earth): a label per output cell (row 0 south;
  // empty = one region) and, per label, the exemplars that may serve it (a
  // label missing from the map may use every exemplar).
  std::vector<int> regionLabels;
  std::vector<std::vector<int>> regionExemplars;
  // Tiled synthesis (Tiling.h): square tiles of this many cells (at least two
  // patches), each synthesised on its own with a halo of one patch in an order
  // fixed by the tile grid, then the whole output finished at once; peak
  // memory of the placement follows the tile, not the output. 0: one piece.
  int tileSize = 0;
  // A tiled synthesis shared among processes (ParaView's MPI ranks): tile k of
  // each step (one pass over one colour class) is placed by rank k mod ranks,
  // and after each step allGather hands every rank's outcomes (its argument,
  // this rank's) to every rank, in rank order. Every rank then holds the same
  // whole terrain, bit for bit what one process makes. ranks 1: no sharing.
  struct TileSharing
  {
    int rank = 0;
    int ranks = 1;
    std::function<std::vector<std::string>(const std::string& mine)> allGather;
  } sharing;
  // Stop after this many placements and return the terrain as those patches
  // made it, unfinished (no final correction, drainage or height range; NaN
  // where no patch is yet): a user steps through the synthesis, one patch at a
  // time, and the first N placements are the whole synthesis' first N, bit for
  // bit. kAllPlacements: every placement, then the finishing. One piece only
  // (tileSize 0).
  std::size_t placementLimit = kAllPlacements;
  // Local re-synthesis of an edited sketch (TileRecord.h; tiled, one process):
  // the record of an earlier run, from which each tile whose placement would
  // read the same inputs takes its outcome instead of being placed again.
  // Null: none. A record that cannot serve this run (recordMismatch) is refused.
  std::shared_ptr<const PlacementRecord> previous;
  // Tiled: keep this run's own record in SynthesisResult::record.
  bool keepRecord = false;
  // The exemplars' feature candidate pool at this patch size, prepared before
  // (SynthesisSetup::pool, perhaps read from the exemplar cache); null: built here.
  std::shared_ptr<const CandidatePool> pool;
  // Told the fraction done (0..1) and the stage's name (Core/Progress.h); the
  // caller's CancellationScope stops the synthesis with tsynth::Cancelled.
  ProgressReport progress;
};

struct Placement
{
  int order = 0;
  bool feature = true;
  int exemplar = 0;
  int variant = 0;
  double sourceX = 0.0; // patch centre in the exemplar, cells
  double sourceY = 0.0;
  int x0 = 0; // patch's lower-left cell in the output
  int y0 = 0;
  float matchCost = 0.0f;
  float landformMisfit = 0.0f; // fill placements: rms landform misfit at the samples, m
  double seamCost = 0.0;       // graph-cut cost per seam edge
  float offset = 0.0f;         // vertical shift applied, metres
  // Feature placements: median distance (cells) from the exemplar's own lines
  // of the site's kind, where the patch carries them within a quarter patch of
  // its centre, to the sketched lines of that kind: how well the patch lays its
  // real ridge or valley on the stroke (NaN: no such line in reach).
  float lineOffset = std::numeric_limits<float>::quiet_NaN();
  // Candidates whose seam was cut in a dry run before choosing this one.
  int seamTrials = 0;
};

// What the final steps changed, for reports.
struct SynthesisTimings
{
  double setup = 0.0;    // pools and dense tables
  double features = 0.0; // feature placement
  double fill = 0.0;     // non-feature filling
  double finish = 0.0;   // final correction, valley drainage, height range and constraints
  double total() const { return setup + features + fill + finish; }
};

// How long one tile of a tiled synthesis took to place in one pass, on the
// process that placed it (measured, for the report and the tile cost model).
struct TileTiming
{
  int column = 0;
  int row = 0;
  int colour = 0;          // its colour class (Tiling.h)
  bool fill = false;       // the fill pass; else the feature pass
  double seconds = 0.0;    // wall clock
  double cpuSeconds = 0.0; // this process's CPU time meanwhile, all its threads
  bool takenOver = false;  // from the previous run's record, not placed
};

struct SynthesisResult
{
  Heightfield terrain;
  std::vector<int> patchId;       // placement that wrote each cell (-1: none)
  std::vector<std::uint8_t> seam; // 1 on seam cells
  std::vector<float> matchCost;   // match cost of the placement that wrote each cell
  std::vector<Placement> placements;
  std::size_t anchoredMerges = 0; // merges whose free border left the height bounds (MergeOptions)
  SynthesisTimings timings;
  FinishingReport finishing;
  // The terrain as the patches made it, before the final corrections.
  Heightfield patches;
  // Tiled: the tiles this process placed, in the order it placed them, and
  // the time it waited for the other processes' tiles after each step.
  std::vector<TileTiming> tiles;
  double waitedSeconds = 0.0;
  // SynthesisOptions::keepRecord: this run's record (null otherwise), and how
  // many tile passes were taken over from SynthesisOptions::previous.
  std::shared_ptr<const PlacementRecord> record;
  std::size_t tilesTakenOver = 0;
  std::vector<std::string> warnings;
  std::string backend;
};

// Throws tsynth::Error for unusable input (no exemplar, an exemplar or output
// smaller than a patch). The options are taken by value: their candidate pool
// is let go once the placement ends, so when the caller handed over its only
// reference (synthesiseTakingPool) the finishing runs without it.
SynthesisResult synthesise(const SynthesisTarget& target,
  const std::vector<const Heightfield*>& exemplars,
  const std::vector<const FeatureGraph*>& graphs,
  SynthesisOptions options);

} // namespace tsynth
