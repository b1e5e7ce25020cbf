// Exemplars and their feature graphs gathered from a filter's input ports, for
// the candidate builder and the patch matcher.
#pragma once

#include "Core/Heightfield.h"
#include "Features/FeatureGraph.h"

#include <functional>
#include <string>
#include <utility>
#include <vector>

class vtkDataArray;
class vtkInformation;
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

// The height array a filter chose for its e-th exemplar connection (the filter's
// GetInputArrayToProcess(idx, e, inputVector)). Empty, or nullptr from it (the exemplar lacks
// the chosen array): "Elevation" or the active scalars, as imageToHeightfield reads any
// heightfield. ParaView leaves a placeholder name in the selection when a script creates the
// filter before its inputs have run, so a missing name must not fail the request.
using ExemplarHeights = std::function<vtkDataArray*(int connection)>;

// The exemplar heights named by a filter's input-array selection (GetInputArrayInformation of
// its SetInputArrayToProcess index for the exemplars), looked up by name in each connection of
// `images`: the selection's port and connection are not used, since one name serves every
// exemplar.
ExemplarHeights exemplarHeightsNamed(vtkInformation* chosen, vtkInformationVector* images);

// Heights and origins of the images of `images` (one or more connections), no
// graphs. Throws tsynth::Error when there is no exemplar.
ExemplarInputs gatherExemplarImages(vtkInformationVector* images,
  const ExemplarHeights& heights = {});

// Images from `images` (one or more connections); graphs from `trees` when it
// has one per image, else ridges and valleys extracted as the synthesis finds
// them (exemplarPpaOptions), so that the pool is the synthesis' own.
// Throws tsynth::Error when there is no exemplar or the counts disagree.
ExemplarInputs gatherExemplars(vtkInformationVector* images,
  vtkInformationVector* trees,
  const ExemplarHeights& heights = {});

} // namespace tsynth
