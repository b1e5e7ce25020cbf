#include "OptimisationGuide.h"

#include "../Core/Error.h"
#include "TerrainOptimisation.h"

#include <limits>
#include <string>

namespace tsynth
{

OptimisationGuide buildOptimisationGuide(const Heightfield& source,
  const SketchInput& sketch,
  const GridRequest& grid,
  const OptimisationOptions& run,
  const SetupOptionNames& names)
{
  checkOptimisationSource(source); // before the guide's work on a source that cannot serve
  const OutputGrid wanted =
    outputGrid(sketchExtent(sketch), grid, source.cellX, source.cellY, 1, names);
  if (wanted.width < kGuideLandformScale || wanted.height < kGuideLandformScale)
  {
    throw Error("The guide gives an output of " + std::to_string(wanted.width) + " x " +
      std::to_string(wanted.height) + " cells, smaller than the " +
      std::to_string(kGuideLandformScale) + " cells its landforms are built at; give a larger " +
      names.size + ".");
  }
  // Before the guide's work: the optimisation's estimate counts the guide too.
  checkOptimisationMemory(wanted.width, wanted.height, source.size(), run);
  SetupInputs in;
  in.exemplars.push_back(source);
  in.sketch = sketch;
  in.grid = grid;
  in.patchSize = kGuideLandformScale;
  in.seed = run.seed;
  in.names = names;
  in.memoryBudget = std::numeric_limits<double>::max(); // checked above, as an optimisation
  SynthesisSetup setup = prepareSynthesis(std::move(in));
  OptimisationGuide guide;
  guide.field = std::move(setup.target.field);
  guide.confidence = std::move(setup.target.weight);
  guide.kind = setup.sketchKind;
  guide.warnings = std::move(setup.warnings);
  guide.warnings.insert(
    guide.warnings.end(), setup.target.warnings.begin(), setup.target.warnings.end());
  return guide;
}

} // namespace tsynth
