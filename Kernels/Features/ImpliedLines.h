// The lines a drawing implies without drawing them: two valleys drawn side by
// side are parted by a divide, a ridge; two ridges drawn side by side have a
// trough between them, a valley. Real land has these lines (Colorado's
// tributaries are parted by long spurs), and a drawing read as land has them
// too. Given only the drawn lines, the synthesis filled the land between two
// tributaries with the exemplars' knobs, and a valley network read as one
// trunk in a field of hills. The target shapes the implied lines; patches are
// placed on the drawn ones only.
#pragma once

#include "FeatureGraph.h"
#include "StrokeSpacing.h"

namespace tsynth
{

struct ImpliedLineOptions
{
  // An implied line shorter than this (cells) is left out: the bisector of a
  // junction's narrow angle, a few cells long, is no landform of its own.
  double minLength = 20.0;
  // Only where the two strokes are at most this far from the line (cells):
  // land farther from any stroke is free, and the fill serves it.
  double maxDistance = 80.0;
  // ... and at least this far (cells): closer, the two strokes are one
  // landform's two sides (a drawn line's own width, a junction).
  double minDistance = 4.0;
  // Chains are given control points at this radius (cells), as drawn ones are.
  double controlRadius = 40.0;
  // Also the troughs between two drawn ridges. Two ridges may have a saddle,
  // a basin or a plateau between them, but without a low between them they
  // read as one broad rise: block letters drawn as ridges on Colorado were
  // lost in its knobs (legible share of their ridges 0.37, Tasse's code 0.28
  // but drawn bolder; with the troughs 0.56, and a spiral ridge's turns
  // stand apart). The landform field shapes them as valleys without an
  // outlet: they cut no gorge, carry no flow and warn of no loop.
  bool troughs = true;
};

// The implied lines of a drawn graph on its own grid (graph.width x
// graph.height cells): ridges on the medial axis between two valleys, and
// (options.troughs) valleys on the medial axis between two ridges;
// nowhere between a ridge and a valley, which one slope joins. `spacing` is the strokeSpacing() of
// all the drawn lines on that grid, in cells. Elevations are NaN.
FeatureGraph impliedLines(const FeatureGraph& drawn,
  const StrokeSpacing& spacing,
  const ImpliedLineOptions& options = {});

} // namespace tsynth
