// The sketch (or guide) port shared by the synthesis and optimisation filters:
// what the set-up takes from it, and the extent RequestInformation announces.
#pragma once

#include "Synthesis/Setup.h"

#include <string>
#include <vector>

class vtkAlgorithm;
class vtkDataObject;
class vtkInformationVector;

namespace tsynth
{

// The sketch as the set-up takes it: a DEM (one non-8-bit band), a sketch image
// or poly-lines in metres. Throws tsynth::Error for anything else.
SketchInput sketchInput(vtkDataObject* data, std::vector<std::string>& warnings);

// The sketch extent on `filter`'s input `port` for RequestInformation: a raster's
// whole extent, or the poly-lines' (a poly-data producer announces none, so it
// is brought up to date first); empty when nothing is known yet.
SketchExtent announcedSketchExtent(vtkAlgorithm* filter, int port, vtkInformationVector* portInfo);

} // namespace tsynth
