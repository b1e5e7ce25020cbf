// Exemplars and their feature graphs gathered from a filter's input ports, for
// the candidate builder and the patch matcher.
#pragma once

#include "Core/Heightfield.h"
#include "Features/FeatureGraph.h"

#include <string>
#include <vector>

class vtkInformationVector;

namespace tsynth
{

struct ExemplarInputs
{
  std::vector<Heightfield> heights;
  std::vector<FeatureGraph> graphs;
  std::vector<double> originX, originY; // world position of cell (0, 0) of each exemplar
  std::vector<std::string> warnings;

  std::vector<const Heightfield*> heightPointers() const;
  std::vector<const FeatureGraph*> graphPointers() const;
};

// Heights and origins of the images of `images` (one or more connections), no
// graphs. Throws tsynth::Error when there is no exemplar.
ExemplarInputs gatherExemplarImages(vtkInformationVector* images);

// Images from `images` (one or more connections); graphs from `trees` when it
// has one per image, else ridges and valleys extracted with default settings.
// Throws tsynth::Error when there is no exemplar or the counts disagree.
ExemplarInputs gatherExemplars(vtkInformationVector* images, vtkInformationVector* trees);

} // namespace tsynth
