// Distance-based terrain synthesis (Rusnell 2009, "Feature-rich distance-based
// terrain synthesis", MSc thesis, Univ. of Saskatchewan; digest in
// shared/papers/004): heights are least-cost path distances on a randomly
// weighted 8-connected lattice from generator nodes, shaped by cross-section
// profiles, h = c_s - c. One multi-source search gives the approximate field;
// one bounded search per feature, halted by the sea-level and approximate-
// terrain thresholds, gives that feature's heights; the features are blended
// by h = sum h_i^(b+1) / sum h_i^b (eq. 3.7).
//
// Choices the thesis leaves open (digest §10), each an option or stated here:
// - diagonals: sqrt(2) by default (round features; the literal lattice gives
//   square cones at small r), sqrt2Diagonals = false for the thesis's lattice;
// - profile x-scale: one profile distance unit per lattice step, profileScale;
// - w_s tables: profileBins equal cost bins over [0, c_s], each the mean slope
//   over the bin (several slopes at one cost are averaged), read by linear
//   interpolation; bins below min t_s interpolated from their neighbours;
// - fBm: improved Perlin noise with a seeded permutation, sampled at cell
//   centres, octaves = the number of terms, normalised to [0, 1] over the grid
//   and mapped by eq. 4.1 (FbmOptions::low, high) onto [0, scale];
// - halting: a halted node keeps its cost (if below c_s) but is not expanded;
//   the approximate search stops at c_s; cells no feature reaches are sea level;
// - blending: heights are divided by c_s before the powers (b <= 64), summed in
//   feature order, so any thread count gives the same bits;
// - ridges: random reached cells outside regions, traced back to the first
//   generator on their least-cost path; cost by RidgeCost (ScaledRise default:
//   the literal f C_a puts a dimple at every peak);
// - regions: a search from a region cell uses the region's profile; no other
//   feature's search enters it (so it neither blends nor passes through), and
//   other features' generators inside it are not used;
// - image edge weights: a node's weight on all its outgoing edges (directed,
//   as the thesis says), and w_s divides by the image's mean weight;
// - generators costing c_s or more are dropped with a warning (s < 1, §3.5);
//   negative costs are allowed (the thesis's crater rings use them).
// In ParaView: vtkTerrainDistanceSynthesis (Terrain Distance Synthesis), in Filters/.
#pragma once

#include "../Core/Heightfield.h"
#include "../Core/OptionTable.h"
#include "../Core/Progress.h"
#include "CostScaling.h"
#include "DistanceLimits.h"
#include "Generators.h"
#include "Lattice.h"
#include "Profile.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <iterator>
#include <string>
#include <vector>

namespace tsynth
{

// How a traced dendritic ridge node gets its cost from the approximate cost C_a
// there and the cost c_g of the generator its path starts from.
enum class RidgeCost
{
  ScaledRise, // c_g + f (C_a - c_g): the ridge leaves its peak at the peak's height
  ScaledCost  // f C_a, the thesis read literally: ridges rise above their own peak near it
};
// The ridge costs' words, by value (Core/OptionTable.h).
inline constexpr const char* kRidgeCostWords[] = { "rise", "cost" };
static_assert(std::size(kRidgeCostWords) == static_cast<std::size_t>(RidgeCost::ScaledCost) + 1);

// The priority queue of the searches; all give the same bits (for the one
// exception, exact double ties, see LatticeSearch.h).
enum class DijkstraQueue
{
  Bucket,    // Dial's buckets of width under the least step: whole buckets settle at once;
             // the radix heap where the steps are too uneven (DistanceTerrain::radixSearches)
  Radix,     // a radix heap on the float costs' bits (monotone: costs never fall)
  BinaryHeap // std::priority_queue, for comparison
};

struct DistanceInputs
{
  int width = 0;
  int height = 0;
  std::vector<DistanceFeature> features; // generators; a feature's id is its index
  std::vector<MonotoneProfile> profiles; // falling cross-sections; ids index this
  std::vector<DistanceRegion> regions;   // optional crater/cone interiors
  // Optional: one edge weight per cell (row 0 south), used on all the cell's
  // outgoing edges instead of mu_w and r (thesis §4.4, e.g. greyToWeights).
  std::vector<float> nodeWeights;
};

// Every parameter of Table 3.1, with the thesis's defaults where it gives one.
struct DistanceOptions
{
  // Lattice (eq. 3.3).
  double meanWeight = 1.0;    // mu_w > 0: steepness without profiles
  double roughness = 0.75;    // r in [0, mu_w): roughness (the mountain range's 0.75 mu_w)
  bool sqrt2Diagonals = true; // the thesis is silent; sqrt(2) makes round, not square, features
  // Sea level and blending.
  double seaLevelScale = 2.0;   // s >= 0: c_s = s c_max (eq. 3.1); 2 as the valleys, canyon, cone
  double blendBias = 4.0;       // b in [0, 64]: 0 the mean, large the maximum (eq. 3.7)
  double seaLevelEpsilon = 0.5; // eps_s: a feature's search stops within eps_s of c_s
  double approximateFraction = 0.05; // p_f: ... or where it is below p_f of the approximate height
  double minScaling = 0.001;         // min t_s: the least cost-scaling value kept as it is
  // Profiles.
  int profileBins = 1024;    // cost bins of each w_s table over [0, c_s] (few bins: "strata")
  double profileScale = 1.0; // lattice cells per profile distance unit
  // Default generator costs: fBm over Perlin noise (H, lacunarity, octaves, domain of §2).
  FbmOptions fbm;
  // Dendritic ridges (§4.1): paths traced back from random cells to their generator.
  int ridgeCount = 0;         // random cells traced (0: none)
  double ridgeFraction = 0.5; // f in (0, 1]: the mountain range's 50%
  RidgeCost ridgeCost = RidgeCost::ScaledRise;
  // Output scale.
  double cellSize = 10.0;       // metres per lattice step
  double heightScale = 5.0;     // metres per cost unit (so mu_w = 1 rises 1:2 at the crests)
  std::uint64_t seed = 1;       // edge weights, fBm and ridge cells
  bool approximateOnly = false; // steps 1-6 only: the fast preview of §7 (seams and all)
  DijkstraQueue queue = DijkstraQueue::Bucket;
  // Told the fraction done (0..1, stage "distance"; Core/Progress.h); the
  // caller's CancellationScope stops the synthesis with tsynth::Cancelled.
  ProgressReport progress;
  // A synthesis whose distanceMemoryEstimate (DistanceMemory.h) is above this
  // many bytes (0: defaultMemoryBudget()) is refused before any work, naming the
  // front end's options.
  double memoryBudget = 0.0;
  std::string memoryOption = "the memory budget";
  std::string sizeOption = "grid";
};

struct DistanceTerrain
{
  Heightfield heights;                     // metres above sea level (0 where no feature reaches)
  Heightfield approximate;                 // the multi-source field C_a as heights (metres)
  std::vector<std::uint16_t> contributors; // features blended at each cell (saturating)
  double seaLevelCost = 0.0;               // c_s
  double maxGeneratorCost = 0.0;           // c_max
  std::size_t features = 0;                // features with visible generators
  std::size_t generators = 0;              // generator nodes after ridges, clipped ones excluded
  std::size_t ridgeNodes = 0;              // nodes the ridges added
  // Each traced ridge's cells, from its random start back towards its generator.
  std::vector<std::vector<std::int32_t>> ridges;
  std::size_t featureVisits = 0; // cells the per-feature searches settled, in total
  // Searches (the approximate ones and one per feature) that DijkstraQueue::Bucket
  // left to the radix heap because their greatest step exceeds the least too far.
  std::size_t radixSearches = 0;
  std::vector<std::string> warnings;
};

// Throws tsynth::Error with one sentence for bad input: a run estimated above
// options.memoryBudget (checkDistanceMemory, before any work), no generators, a
// parameter out of range, profiles that do not fall, a profile or region id out
// of range, images (node weights) of the wrong size, costs that are not finite
// or so large that float costs would swallow the smallest edge step; throws
// tsynth::Cancelled if the open CancellationScope says stop. The result depends only
// on the inputs, the options and the seed, never on the number of threads.
DistanceTerrain synthesiseByDistance(const DistanceInputs& inputs, const DistanceOptions& options);

} // namespace tsynth
