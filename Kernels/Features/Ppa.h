// Profile recognition and target connection (Chang et al. 1998, as used by Zhou
// et al. 2007 and Tasse's thesis): ridge (or valley) lines of a heightfield as
// a forest, with Kruskal's maximum spanning forest in place of polygon breaking.
// In ParaView: vtkTerrainFeatureExtractor (Terrain Feature Extractor), in Filters/.
#pragma once

#include "../Core/Heightfield.h"
#include "../Core/OptionTable.h"
#include "../Core/Progress.h"
#include "FeatureGraph.h"
#include "PixelGraph.h"
#include "PpaLimits.h"

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
  // Significance at the scale of a landform, unit-free: a target is kept only if
  // along one of the four axes both directions descend by the significant drop
  // within significanceRadius cells, each before climbing that much above the
  // cell. The drop is the larger of `significance` x the field's robust relief
  // (robustRelief) and `significanceNoise` x its cell-scale noise (cellNoise).
  // The short profile above accepts every ripple: on a plane with a few metres
  // of noise most cells are targets and the trees cover the plane. Significance
  // 0 switches the test off (PPA as before).
  //
  // 0.02 of the relief: a landform a patch should carry stands a few percent of
  // the DEM's relief above its surroundings (35 m on the Colorado DEM's 1760 m,
  // 60 m on Mont Blanc's 3030 m). At 0.02 the noise meshes on salt flats,
  // glaciers and dune floors go and the main ridges and valleys stay (checked on
  // nine DEMs); higher values also take minor real spurs and gullies, which the
  // synthesis needs as candidates: its quality bar (slope distance <= 0.15)
  // fails from 0.03 on the Colorado exemplar and from 0.05 on Mont Blanc.
  double significance = 0.02;
  // 4 noise sigmas: a tilted plane of white noise still grows trees with a drop
  // of 2 sigmas (and a few at 2.5), none from 3; 4 leaves a sigma of margin.
  // The floor decides only where the relief is small against the noise (dunes,
  // nearly flat ground): on the nine DEMs it is 4-16 m, under 0.02 x relief
  // except on the Sahara's dunes (8 m against 4 m).
  double significanceNoise = 4.0;
  // Cells: the half-length of the cross-section profiles the matcher compares
  // (ProfileOptions::acrossHalfLength), so a feature stands out within the span a
  // patch is matched on.
  int significanceRadius = 20;
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
  double significance = 0.0; // robust relief and the significance test
  double spanningForest = 0.0;
  double pruning = 0.0;
  double graph = 0.0;
  double total() const
  {
    return presmooth + profile + significance + connect + spanningForest + pruning + graph;
  }
};

struct PpaStatistics
{
  std::size_t targets = 0;        // after the significance test
  std::size_t insignificant = 0;  // profile targets the significance test removed
  double relief = 0.0;            // robust relief of the field (0 when the test is off)
  double noise = 0.0;             // cell-scale noise sigma of the field (0 when off)
  double significantDrop = 0.0;   // the drop the test asked for, in height units
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

// Height range between the 1st and 99th percentiles of the valid heights (nearest
// rank), so that a few spikes or pits do not set it; the full range when that is
// zero (a DEM that is almost all one height), 0 without valid cells. Grids over
// 2^18 cells are sampled at a fixed stride (percentiles within a few 1e-4).
double robustRelief(const Heightfield& hf);

// Standard deviation of cell-scale noise: the median absolute residual of the
// least-squares quadric through each 3 x 3 block of valid cells, (1 -2 1) x
// (1 -2 1) / 9 of the heights, which is 0 on any quadric surface and 2/3 sigma
// for white noise of sigma; scaled so white noise gives its sigma. Real terrain
// gives little: 1.0-4.0 m on nine 90 m DEMs. Sampled as robustRelief; 0 without
// a full block.
double cellNoise(const Heightfield& hf);

// Clears the targets that do not stand out by minDrop: a target stays if along
// one of the four axes both directions reach a valid height at least minDrop
// below it within `radius` cells, each before reaching one minDrop above it
// (invalid cells are skipped; the grid edge ends a direction). Returns how many
// targets were cleared.
std::size_t removeInsignificantTargets(const Heightfield& hf,
  std::vector<std::uint8_t>& targets,
  int radius,
  double minDrop);

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

// Ridges and valleys of one heightfield in one graph, the ridges first.
FeatureGraph ridgesAndValleys(const Heightfield& hf, const PpaOptions& options);

// Gaussian smoothing of valid cells (invalid neighbours get no weight).
Heightfield gaussianSmooth(const Heightfield& hf, double sigma);

// Which lines a feature extraction keeps: the Feature Extractor's Features
// property and tsynth features' --features, in this order.
enum class FeatureSelection
{
  Ridges,
  Valleys,
  Both
};
inline constexpr const char* kFeatureSelectionWords[] = { "ridges", "valleys", "both" };
// True if `selection` keeps lines of `type`.
bool keeps(FeatureSelection selection, FeatureType type);

// The lines `selection` keeps, ridges first, in one graph on hf's grid, with
// every warning and the statistics of the last extraction (the relief and the
// drop are the same for both kinds); no pixel forest or timings. `progress`
// hears 0 before the ridges and 0.5 before the valleys.
FeatureExtraction extractSelectedFeatures(const Heightfield& hf,
  FeatureSelection selection,
  const PpaOptions& options,
  const ProgressReport& progress = {});

// The PPA options tsynth features and the Terrain Feature Extractor filter share
// (Core/OptionTable.h), their defaults a default PpaOptions', with Features (a
// FeatureSelection) first. SmoothingPasses and
// ControlRadius are the filter's alone: tsynth features smooths as the default
// does and takes the control radius from --patch (half of it).
const std::vector<OptionRow>& ppaOptionRows();

} // namespace tsynth
