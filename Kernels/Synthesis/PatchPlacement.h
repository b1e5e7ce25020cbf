// The placement of a synthesis: the output as the patches make it, the
// choice of each patch among the matcher's candidates (line alignment, seam
// cost, repetition, the seed among near ties) and its graph-cut merge. The
// feature patches go in FeatureOrder.h's order, the fill in FillOrder.h's;
// finish() hands the placed terrain to Finishing.h. A tiled synthesis
// (Tiling.h) runs one per tile region, on the cells earlier tiles wrote, and
// one for the whole output that adopts each tile's outcome and finishes.
// It keeps references to the target, the graphs, the options and the
// matcher it is given (and to `known` only while constructed): they must
// outlive it.
#pragma once

#include "../Core/Heightfield.h"
#include "../Features/ChainPointGrid.h"
#include "../Features/FeatureGraph.h"
#include "../Matching/CandidatePool.h"
#include "../Matching/DenseSearch.h"
#include "../Matching/NoiseVariance.h"
#include "../Matching/PatchMatcher.h"
#include "../Merging/PatchMerger.h"
#include "Synthesiser.h"
#include "Tiling.h"

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <unordered_map>
#include <vector>

namespace tsynth
{

class PatchPlacement
{
public:
  // `known`: cells already synthesised (its valid ones, on the target's grid),
  // which the placement continues (a tile's neighbours done before it).
  // `matcher` null: only finish() will run (the whole terrain after its tiles).
  PatchPlacement(const SynthesisTarget& target,
    PatchMatcher* matcher,
    const std::vector<const FeatureGraph*>& graphs,
    const SynthesisOptions& o,
    const Heightfield* known = nullptr);

  // Heights a merged patch's free border may reach before it is anchored
  // (MergeOptions::lowestHeight): the exemplars' range, widened by
  // kHeightSlackShare of its span each way.
  void boundHeights(const std::vector<const Heightfield*>& exemplars);

  // The exemplars' typical roughness per noise level, which a drawn target's
  // queries ask of the fill (DenseMatcher::typicalNoise).
  void setTypicalNoise(const std::array<float, kNoiseLevels>& t);

  // The feature patches, one per site in FeatureOrder.h's order.
  void placeFeatures();

  // ... at these sites, in this order (a tile's share: sitesOf).
  void placeFeatures(const std::vector<FeatureSite>& sites);

  // The fill: windows over the output (fillGrid), visited as FillOrder.h's
  // runFill says, each filled by one patch from the dense matcher.
  void fill();

  // Frees what only the placement needs (the target's roughness tables and
  // low-pass, the distances to the strokes, the merger workspaces) and lets go
  // of the matcher, so the finishing's fields can take that memory: at 4096 x
  // 4096 from five exemplars the finishing is where memory peaks.
  void releasePlacement();

  // The result: cells no patch filled take the target's heights (with a
  // warning), then Finishing.h's finishSynthesis. Call once, last.
  SynthesisResult finish();

  // The result of a run stopped at SynthesisOptions::placementLimit: the
  // terrain as its patches made it (NaN where none is), not finished. Call
  // once, last, in place of finish().
  SynthesisResult unfinished();

  // Whether the options' placement limit is reached: nothing more is placed.
  bool placementsDone() const { return result_.placements.size() >= o_.placementLimit; }

  // Progress through the options' report (and a stop, Core/Progress.h).
  void report(double fraction, const char* stage) const;

  // Tiled synthesis (Tiling.h), on the state of the whole output: the feature
  // sites a tile owns (centres on its cells), in the whole output's order,
  // moved into the tile's region.
  std::vector<FeatureSite> sitesOf(const SynthesisTile& t,
    const std::vector<FeatureSite>& all) const;

  // Every feature site of the target in placement order (FeatureOrder.h).
  std::vector<FeatureSite> sitesInOrder() const;

  // Cells whose known heights no fill patch may change (frozen_).
  void freeze(std::vector<std::uint8_t> cells);

  // The region's cells as the tiles done so far left them: the filled ones
  // valid, the rest NaN.
  Heightfield knownIn(const SynthesisTile& t) const;

  // What this tile's placement made of its region (this state is the tile's),
  // less the `dropped` cells (over the region; may be empty).
  TileOutcome outcome(std::size_t tile, const std::vector<std::uint8_t>& dropped) const;

  // Takes over a tile's outcome (this state is the whole output's): its kept
  // cells, and its placements, numbered after those before and moved into the
  // output's frame.
  void adopt(const SynthesisTile& t, const TileOutcome& tile);

private:
  // A feature candidate's own lines of its site's kind within
  // kLineOffsetReachInPatches of its centre, as placed: offsets (cells) from
  // the patch centre.
  struct OwnLine
  {
    int type = 0; // +1 ridge, -1 valley; 0 for a dense candidate
    std::vector<Point2> cells;
  };

  OwnLine ownLine(const PatchCandidate& c) const;

  // Placement::lineOffset of a candidate's own line placed at (x0, y0).
  float lineOffset(const OwnLine& own, int x0, int y0) const;

  // The patch-sized window of the output at (x0, y0): its known cells, and
  // the low-passed target at the landform samples of the empty part. Heights
  // are compared as they are, so a window whose known part has drifted from
  // the target prefers patches that lead back to it.
  DenseQuery window(int x0, int y0) const;

  // The candidate's patch, read from the exemplar seen through its variant.
  Heightfield extract(const PatchCandidate& c) const;

  // Shift to fit what the patch overlaps (or, with no overlap, the target).
  float fitOffset(const Heightfield& patch, int x0, int y0) const;

  // Fill patches leave the sketched lines that feature patches already hold,
  // and the frozen cells (a tile's border that it does not keep).
  void protectLines(Heightfield& patch, int x0, int y0) const;

  // Chooses among candidates by seam cost and merges the winner at (x0, y0).
  // The exemplars that may serve the region at the window's centre (null: all).
  const std::vector<int>* regionExemplars(int x0, int y0) const;

  // Keeps the candidates whose exemplar may serve the region at the window's centre.
  std::vector<PatchCandidate> allowed(std::vector<PatchCandidate> candidates,
    int x0,
    int y0,
    std::size_t keep) const;

  // How many placements already took a source within half a patch of this one.
  int reuses(const PatchCandidate& c) const;

  // Sources used so far, bucketed by exemplar and half-patch cell, so reuses()
  // looks at neighbours only instead of every earlier placement.
  static std::int64_t sourceKey(int exemplar, long x, long y);

  void recordSource(std::size_t placement);

  // The cells a feature patch owns whatever the seam: the sketched line near
  // its centre (where its own feature was matched) and a small disc around
  // the centre.
  std::vector<std::uint8_t> strokeCore(int x0, int y0) const;

  // One candidate tried at a window: for a feature candidate its own line and
  // how far that lies from the stroke (all eligible() needs); then, if it is
  // eligible, its patch at the fitted height, the cells it owns and the
  // merge's dry run.
  struct Trial
  {
    OwnLine own;
    float lineOffset = std::numeric_limits<float>::quiet_NaN();
    Heightfield patch;
    float offset = 0.0f;
    MergeResult dry;
    std::vector<std::uint8_t> core;
  };

  // A feature candidate's own line and its offset from the stroke.
  void alignTrial(const PatchCandidate& candidate, int x0, int y0, Trial& t) const;

  // The trial before its merge: the patch at its height and, for a feature
  // patch, the cells it owns (alignTrial first).
  void prepareTrial(const PatchCandidate& candidate,
    int x0,
    int y0,
    bool feature,
    const std::vector<std::uint8_t>& strokeCells,
    Trial& t) const;

  // The best-aligned feature candidate's line offset (+inf if none has one).
  static float bestAlignment(const std::vector<Trial>& trials);

  // Whether choose() may take the trial: among feature candidates only those
  // that lay their own line within kLineOffsetSlack cells of the best-aligned
  // one; the others need no merge's dry run.
  static bool eligible(const Trial& t, float aligned);

  // Leaves eligible only the first kMostFeatureSeamTrials eligible feature
  // trials (the candidates come best first by the matcher's cost): the others
  // are marked as laying no line (an infinite line offset). Where sites crowd.
  static void keepBestAligned(std::vector<Trial>& trials, float aligned);

  // The candidate to place: the lowest seam cost (plus the repetition penalty,
  // near-ties by the seed), among feature candidates only those that lay their
  // own line within kLineOffsetSlack cells of the best-aligned one.
  std::size_t choose(const std::vector<PatchCandidate>& candidates,
    const std::vector<Trial>& trials,
    float aligned,
    double& bestSeam) const;

  // Writes the placement's ids, costs and seams.
  void record(const PatchCandidate& chosen,
    const Trial& t,
    const MergeResult& r,
    int x0,
    int y0,
    double seam);

  // Chooses among candidates and merges the winner at (x0, y0). Returns how
  // many empty cells the placement filled (0 if none could be).
  std::size_t place(const std::vector<PatchCandidate>& candidates, int x0, int y0, bool feature);

  // Share of a window already filled (1 for a window wholly outside).
  double filledShare(int x0, int y0) const;

  const SynthesisTarget& target_;
  PatchMatcher* matcher_; // null once the placement is over (releasePlacement)
  const std::vector<const FeatureGraph*>& graphs_;
  // Per exemplar, its graph's chain points by kind, for ownLine.
  std::vector<ChainPointGrid> linePoints_;
  std::vector<float> toRidge_, toValley_; // cells to the sketched ridges, valleys (empty: none)
  const SynthesisOptions& o_;
  int P_;
  // Feature sites crowd (featureSitesCrowd): a DEM target's own tree, or lines
  // closer than patches draw. The seam is then cut for the best few aligned
  // candidates only (keepBestAligned).
  bool crowded_;
  Heightfield out_;
  std::vector<std::uint8_t> filled_;
  std::vector<std::uint8_t> line_;
  std::vector<std::uint8_t> frozen_; // empty: none
  NoiseVariance noise_;              // empty unless target_.detailed
  float lowest_ = -std::numeric_limits<float>::infinity();
  std::array<float, kNoiseLevels> typicalNoise_{};
  float highest_ = std::numeric_limits<float>::infinity();
  Heightfield lowTarget_;                // the target through the landform term's low-pass
  std::vector<float> ownConfidence_;     // 1 everywhere, for targets that give none
  const std::vector<float>& confidence_; // the target's confidence per cell
  std::vector<PatchMerger> mergers_;     // one per OpenMP thread
  SynthesisResult result_;
  std::unordered_map<std::int64_t, std::vector<std::size_t>> sources_;
};

// The matcher a synthesis with these options places its patches with: the
// options' patch, backend, candidates per placement, vertical offset and
// prepared pool.
std::unique_ptr<PatchMatcher> makeSynthesisMatcher(const std::vector<const Heightfield*>& exemplars,
  const std::vector<const FeatureGraph*>& graphs,
  const SynthesisOptions& options);

} // namespace tsynth
