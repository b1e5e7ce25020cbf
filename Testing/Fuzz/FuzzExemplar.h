// The exemplar statistics the target-building fuzz targets build their targets
// with: measured once on a small synthetic terrain, so the landforms have real
// cross-sections without any file.
#pragma once

#include "Features/Ppa.h"
#include "Synthesis/Target.h"

#include <cmath>

namespace tsynth::fuzz
{

// Side (cells) and cell size (metres) of the synthetic exemplar: big enough for
// PPA to find ridges and valleys a patch long.
constexpr int kExemplarSide = 96;
constexpr double kExemplarCell = 30.0;
// Patch of the targets: the smallest the synthesis takes, so small grids pass.
constexpr int kFuzzPatch = 16;

inline const ExemplarStatistics& exemplarStatisticsForFuzzing()
{
  static const ExemplarStatistics stats = []
  {
    Heightfield hf(kExemplarSide, kExemplarSide);
    hf.cellX = hf.cellY = kExemplarCell;
    for (int j = 0; j < hf.height; ++j)
    {
      for (int i = 0; i < hf.width; ++i)
      {
        // Diagonal ridges and valleys 24 cells apart, rising to the north-east.
        hf.at(i, j) = static_cast<float>(200.0 * std::sin(0.26 * (i + 0.5 * j)) + 2.0 * (i + j));
      }
    }
    PpaOptions o;
    o.significance = 0.0;
    FeatureGraph g = extractFeatures(hf, FeatureType::Ridge, o).graph;
    appendGraph(g, extractFeatures(hf, FeatureType::Valley, o).graph);
    return exemplarStatistics({ &hf }, { &g }, kFuzzPatch);
  }();
  return stats;
}

} // namespace tsynth::fuzz
