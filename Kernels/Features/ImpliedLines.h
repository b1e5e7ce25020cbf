// The lines a drawing implies without drawing them: two valleys drawn side by
// side are parted by a divide, a ridge; two ridges drawn side by side have a
// trough between them, a valley. Real land has these lines (Colorado's
// tributaries are parted by long spurs), and a drawing read as land has them
// too. Given only the drawn lines, the synthesis filled the land between two
// tributaries with the exemplars' knobs, and a valley network read as one
// trunk in a field of hills. Feature patches placed on the implied lines carry
// the exemplars' own spurs there.
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
  // Also the troughs between two drawn ridges. Off by default: water must
  // part between two valleys, so a divide is always there, but two ridges
  // may have a saddle, a basin or a plateau between them, and a trough there
  // would need an outlet the drawing does not give. (The landform field
  // takes implied lines as ridges only: an implied valley would still cut
  // gorges and warn of loops as a drawn one does.)
  bool troughs = false;
};

// The implied lines of a drawn graph on its own grid (graph.width x
// graph.height cells): ridges on the medial axis between two valleys, and
// with options.troughs valleys on the medial axis between two ridges;
// nowhere between a ridge and a valley, which one slope joins. `spacing` is the strokeSpacing() of
// all the drawn lines on that grid, in cells. Elevations are NaN.
FeatureGraph impliedLines(const FeatureGraph& drawn,
  const StrokeSpacing& spacing,
  const ImpliedLineOptions& options = {});

} // namespace tsynth
