// Landforms at the scale of the drawing. A sketched ridge stands for a
// mountain ridge with the cross-section of the exemplars' own major ridges, a
// sketched valley for a valley whose floor descends to an outlet, with flanks
// like the exemplars' valley sides. measureLandforms() reads those
// cross-sections off the exemplars' feature trees; landformField() turns the
// sketch's lines into the target field T_tar and a confidence that is 1 near
// the lines and 0 where no line is near (there the land is left free).
#pragma once

#include "../Core/Heightfield.h"
#include "../Core/PatchSize.h"
#include "../Distance/Profile.h"
#include "../Features/CrossSections.h"
#include "../Features/FeatureGraph.h"

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace tsynth
{

// One kind of landform (ridge or valley) as the exemplars have it.
struct LandformProfile
{
  // Height relative to the line against distance from it (metres, both), from
  // 0 at the line: falling for ridges, rising for valleys. Empty if unmeasured.
  MonotoneProfile section;
  double level = 0.0;      // typical height of the major lines themselves (crest or floor), m
  double relief = 0.0;     // height between the line and the land it stands on, m
  double width = 0.0;      // distance in which 90% of the relief is made, m
  double lineLength = 0.0; // metres of major line measured
};

struct LandformStatistics
{
  LandformProfile ridge;
  LandformProfile valley;
  double base = 0.0;          // the land ridges stand on and valleys are cut into, m
  double floorGradient = 0.0; // typical descent of major valley floors, m per m
  // The exemplars' own relief per half width (in cells of their grid), which
  // a sketched landform must stand out of to be seen.
  LandRelief land;
  // Heights sketched landforms keep within: the exemplars' 0.5th and 99.5th
  // percentiles (a crest above their highest land would be no crest of theirs).
  double lowest = 0.0;
  double highest = 0.0;
  std::vector<std::string> warnings;
};

struct LandformMeasureOptions
{
  int patchSize = kDefaultSynthesisPatch;
  // Share of an exemplar's ridge (valley) cells, the highest (lowest), taken as
  // its major features: the main ranges and trunk valleys, not the spurs and
  // gullies between them, whose cross-sections end at the next spur.
  double majorShare = 0.25;
  // Cross-sections are measured this many patches out from the lines: a
  // landform is wider than a patch.
  double reachInPatches = 1.5;
};

// Cross-sections of the exemplars' major ridges and valleys, pooled over the
// exemplars (each counts by its length of line), and the levels they share.
// Exemplars without one kind of feature fall back on the other kind or on
// their height distribution, with a warning.
LandformStatistics measureLandforms(const std::vector<const Heightfield*>& exemplars,
  const std::vector<const FeatureGraph*>& graphs,
  const LandformMeasureOptions& options = {});

// The same landforms with their relief (height of the ridges over the base,
// depth of the valleys below it) times `factor`, shapes and widths unchanged.
LandformStatistics withReliefScaled(const LandformStatistics& statistics, double factor);

struct LandformFieldOptions
{
  int patchSize = kDefaultSynthesisPatch;
  // A sketched ridge's crest (valley's floor) stands out of its sides by at
  // least this many times the land's own relief at its half width (as
  // sectionProminence measures both), its relief raised where need be, but
  // never so far that its flank is steeper than the land's steep end at that
  // width (LandRelief::steepSlope; for ridges ridgeFlankAllowance times it),
  // nor its crest higher than crestPastHighestShare allows, nor its floor
  // below LandformStatistics::lowest. The legibility measure calls a stroke
  // legible at 1 (Metrics/Legibility.h); the texture the patches lay over the
  // landform scatters it by about 1 more, and the eye wants it to stand out at
  // a glance; on the bundled rugged exemplars the caps bind first. 0 turns the
  // rule off.
  double standOut = 4.0;
  // The patches lay the land's own texture over a ridge's flanks, and it is as
  // steep as the land's steep end somewhere all around: a ridge whose flank
  // was capped at that slope read as one slope among many. Ridges drawn over
  // Colorado (the bundled Y, letters, the meander's spurs), raised to at most
  // the steep end, were lost in the land where Tasse's code drew them
  // (hillshades side by side); allowed 1.5 times it, they read. At 2 they
  // were bolder, but the seams showed (seam index 1.14 on parallel ridges
  // from Mont Blanc, past the 1.1 the bundled sketches are held to,
  // Testing/Python/test_synth.py). Valleys keep the steep end itself: they
  // read already, and allowed 1.5 times it too they drained less and took
  // the slopes of the bundled meander from two exemplars past that test's
  // bar (slope distance 0.106 against at most 0.1).
  double ridgeFlankAllowance = 1.5;
  // A sketched crest may rise past the exemplars' highest land (their 99.5th
  // percentile, LandformStatistics::highest) by this share of the span from
  // their lowest to their highest: held to the highest itself, a crest was no
  // higher than the summits around it (Colorado's ridges were raised x1.23 at
  // most) and did not stand out of them. At 0.2 it stays inside the bound the
  // finished terrain is compressed into (the exemplars' maximum and a tenth of
  // their span, Synthesiser), which lies 0.24 to 0.45 of that span past the
  // highest on the eight DEMs of ../shared/data, so the crest is not flattened
  // against it. Floors keep to the lowest land: given the same room below it,
  // the deeper valleys drained less.
  double crestPastHighestShare = 0.2;
  std::uint64_t seed = 0; // breaks ties between equally good valley outlets
  // A ridge's crest keeps this share of its relief at a free end (a spur ends
  // in a slope, not a cliff), rising to all of it half a patch along the line.
  double endRelief = 0.4;
  // A valley's floor rises from its outlet towards its heads by at most this
  // many times its depth (the land around rises with it: the basin tilts
  // towards its outlet) ...
  double headRise = 1.0;
  // ... and the valley becomes shallower towards its heads, keeping this share
  // of its depth at the farthest head.
  double headDepth = 0.6;
  // Chains from this index on are lines the drawing implies (the divides
  // between its valleys and the troughs between its ridges, ImpliedLines.h).
  // They are shaped like drawn ones (a trough as a valley with no outlet:
  // floor the valley relief below the base, rim the base), and squeeze them
  // as drawn ones do, but the relief raise and the scale
  // the result follows each landform at (halfWidth) are read off the drawn
  // lines alone: at half a valley's width, the final correction drew the
  // target's smooth flanks finer and the terrain came out flatter (slope
  // distance 0.061 against 0.043 over the 44-run sweep).
  std::size_t impliedChainsFrom = std::numeric_limits<std::size_t>::max();
};

// Heights along the sketch's lines, when the sketch says them (a grey map or
// DEM, or poly-line Elevation): per chain point of `graph`, NaN where unknown.
using LineHeights = std::vector<std::vector<float>>;

struct LandformField
{
  Heightfield field;         // T_tar, metres
  std::vector<float> weight; // confidence 0..1 of T_tar, per cell
  // Per cell: the room the drawing leaves the landform nearest it, cells:
  // half the spacing to the facing stroke (StrokeSpacing), at most the
  // landform's own width. The scale the result must follow the target at.
  std::vector<float> halfWidth;
  // The factors sketched ridges' and valleys' relief was raised by to stand
  // out (LandformFieldOptions::standOut); 1: as the exemplars' own.
  double ridgeRaise = 1.0;
  double valleyRaise = 1.0;
  // Along the sketched valleys: per cell of their rasterised lines the flow
  // distance to the outlet (metres), NaN elsewhere. Water runs towards smaller
  // values, so the result's floors can be made to descend the same way.
  std::vector<float> downstream;
  std::vector<std::string> warnings;
};

// The target of a graph already on the output grid (cells of cellX x cellY m).
// `base`, when given, is the land's height per cell (a grey map's background);
// else the statistics' base everywhere. `heights` optionally fixes crest and
// floor heights along the lines (linear between given points). The lines are
// taken with a point per cell at least, so crest tapers, concave floors and
// flow distances follow a poly-line between its vertices too.
LandformField landformField(const FeatureGraph& graph,
  int width,
  int height,
  double cellX,
  double cellY,
  const LandformStatistics& statistics,
  const LandformFieldOptions& options,
  const Heightfield* base = nullptr,
  const LineHeights* heights = nullptr);

} // namespace tsynth
