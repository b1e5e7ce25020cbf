// Profile recognition and target connection (Chang et al. 1998, as used by Zhou
// et al. 2007 and Tasse's thesis): ridge (or valley) lines of a heightfield as
// a forest, with Kruskal's maximum spanning forest in place of polygon breaking.
#pragma once

#include "../Core/Heightfield.h"
#include "FeatureGraph.h"
#include "PixelGraph.h"

#include <string>
#include <vector>

namespace tsynth
{

struct PpaOptions
{
  // A cell is a target if along at least one of the four axes (E-W, N-S and the
  // two diagonals) both directions reach, within this many cells, a height lower
  // than its own by more than minDip. 3 is Chang's recommendation for 90 m data.
  int halfProfileLength = 3;
  // Metres (or sketch units). 0 keeps every strict dip; raise it to ignore
  // ripples below the DEM's noise.
  double minDip = 0.0;
  // The dip on both sides must also reach this fraction of the local relief (the
  // largest height difference within the profile star). Unit-free: it rejects the
  // faint "both sides lower" of convex slopes (round hill flanks, ridge ends)
  // that are not ridges, on metres, feet or sketch grey levels alike.
  double relativeDip = 0.1;
  // Gaussian pre-smoothing (cells) before the profile test; 0 = none. Sketches
  // with flat-topped strokes need about half the stroke width.
  double presmoothSigma = 0.0;
  // Each pass removes the end cell of every dangling branch (Chang: L/2 passes).
  int endReductions = 3;
  // Dangling branches shorter than this many cells are removed after the end
  // reduction (World Machine's "short branch threshold").
  int minBranchLength = 15;
  // Trees with fewer cells are removed.
  int minTreeSize = 30;
  // Passes of [1 2 1] smoothing of chain interiors (geometry only).
  int smoothingPasses = 2;
  // Radius of the control-point circle in cells (half the patch size).
  double controlRadius = 40.0;
};

// Wall-clock seconds of each step, for the benchmark and reports.
struct PpaTimings
{
  double presmooth = 0.0;
  double profile = 0.0;
  double connect = 0.0;
  double spanningForest = 0.0;
  double pruning = 0.0;
  double graph = 0.0;
  double total() const { return presmooth + profile + connect + spanningForest + pruning + graph; }
};

struct PpaStatistics
{
  std::size_t targets = 0;
  std::size_t candidateEdges = 0; // after removing the lighter of crossing diagonals
  std::size_t forestEdges = 0;
  std::size_t prunedCells = 0; // cells left after pruning
};

struct FeatureExtraction
{
  FeatureGraph graph;
  PixelGraph pixels; // the pruned forest, one cell per feature point
  PpaTimings timings;
  PpaStatistics statistics;
  std::vector<std::string> warnings;
};

// Marks profile targets (1) of a height grid; invalid cells are never targets
// and never count as lower. See PpaOptions for the thresholds.
std::vector<std::uint8_t> profileTargets(const Heightfield& hf,
  int halfProfileLength,
  double minDip,
  double relativeDip = 0.0);

// An undirected edge between 8-neighbouring cells a and b, with its weight.
struct CellEdge
{
  std::uint32_t a = 0;
  std::uint32_t b = 0;
  float weight = 0.0f;
};

// Joins 8-adjacent targets; weight = sum of the two heights; of two crossing
// diagonals only the heavier is kept (the NE one on a tie).
std::vector<CellEdge> connectTargets(const Heightfield& hf,
  const std::vector<std::uint8_t>& targets);

// Maximum-weight spanning forest (Kruskal: heaviest first, union-find), ties
// broken by edge order so the result is deterministic.
PixelGraph maximumSpanningForest(int width, int height, const std::vector<CellEdge>& edges);

// The whole extraction on a heightfield: ridges, or valleys (run on -z).
FeatureExtraction extractFeatures(const Heightfield& hf,
  FeatureType type,
  const PpaOptions& options = {});

// Gaussian smoothing of valid cells (invalid neighbours get no weight).
Heightfield gaussianSmooth(const Heightfield& hf, double sigma);

} // namespace tsynth
