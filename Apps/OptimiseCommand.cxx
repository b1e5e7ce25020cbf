// tsynth optimise: terrain optimisation (Scott & Dodgson 2021) from a source
// DEM and a guide.
#include "Commands.h"

#include "CliSupport.h"
#include "CommandLine.h"
#include "TerrainFileIO.h"

#include "Core/Error.h"
#include "Core/FileRoles.h"
#include "Hydrology/PitRemoval.h"
#include "Optimisation/OptimisationGuide.h"
#include "Optimisation/TerrainOptimisation.h"

#include <chrono>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace tsynth::cli
{
namespace
{

const char* const kOptimiseHelp =
  R"(Usage: tsynth optimise --exemplar DEM --guide GUIDE -o OUT [options]

Terrain optimisation (Scott & Dodgson, "Example-based terrain synthesis with pit removal",
2021): the output is rebuilt entirely from small patches of the source DEM so that it looks
like the source and follows the guide. From the coarsest level of a pyramid to the finest,
each cell takes the source patch that best matches its neighbourhood (PatchMatch) and
becomes the average of the overlapping patches, blended with the guide with a weight that
halves level by level; pits are removed after each step on every level but the finest.

The guide is a DEM, a grey sketch (brighter is higher), a stroke map (red ridges, blue
valleys) or poly-lines (.vtp), read as tsynth synth reads its --sketch: DEMs and grey maps
are brought onto the source's heights, strokes become its landforms.

  --exemplar DEM         the source DEM: every height of the output comes from it
  --guide GUIDE          what the terrain should follow
  -o, --output OUT       .tif (GeoTIFF float32), .png (16-bit + sidecar) or .vti
  --size WxH             output size in cells (default: the guide's pixels)
  --patch N              patch size in cells, odd, %RANGE:PatchSize% (default %DEFAULT:PatchSize%)
  --levels L             pyramid levels above the output, %RANGE:Levels% (default: as many
                         as the source allows)
  --alpha A              guide weight at the coarsest level, %RANGE:Alpha% (default %DEFAULT:Alpha%)
  --iterations N         E/M iterations per level, %RANGE:IterationsPerLevel% (default %DEFAULT:IterationsPerLevel%, the paper's)
  --search-iterations N  PatchMatch passes per M-step, %RANGE:SearchIterations% (default %DEFAULT:SearchIterations%)
  --rotations            also use the source's patches turned by 90, 180 and 270 degrees
  --reflections          also use them mirrored
  --pits M               pit removal on the coarser levels: %WORDS:PitRemoval%
                         (default %DEFAULT:PitRemoval%, the paper's)
  --drain                also make the output itself drain (beyond the paper, which leaves
                         the finest level alone): the --pits method on blocks from the coarsest
                         level's scale down to 2 cells, the last few-cell pits filled
  --seed N               another seed gives another terrain; the same seed the same terrain
  --max-memory GB        refuse a run estimated to need more, before any work (default: 80%
                         of the machine's memory)
  --no-progress          no progress bar on the terminal
)";

struct OptimiseArguments
{
  std::string source;
  std::string guide;
  std::string output;
  GridRequest grid;
  OptimisationOptions options;
  bool progress = true;
};

void takeOptimisationOptions(CommandLine& cl, OptimisationOptions& o)
{
  const std::vector<OptionRow>& rows = optimisationOptionRows();
  if (const auto patch = takeRowNumber(cl, optionRow(rows, "PatchSize")))
  {
    o.patchSize = static_cast<int>(*patch); // odd checked by the kernel, with its sentence
  }
  if (const auto levels = takeRowNumber(cl, optionRow(rows, "Levels")))
  {
    o.levels = static_cast<int>(*levels);
  }
  if (const auto alpha = takeRowNumber(cl, optionRow(rows, "Alpha")))
  {
    o.alpha = *alpha;
  }
  if (const auto mu = takeRowNumber(cl, optionRow(rows, "IterationsPerLevel")))
  {
    o.iterationsPerLevel = static_cast<int>(*mu);
  }
  if (const auto pm = takeRowNumber(cl, optionRow(rows, "SearchIterations")))
  {
    o.patchMatchIterations = static_cast<int>(*pm);
  }
  o.rotations = cl.takeFlag("--rotations");
  o.drainOutput = cl.takeFlag("--drain");
  o.reflections = cl.takeFlag("--reflections");
  if (const auto pits = takeRowChoice(cl, optionRow(rows, "PitRemoval")))
  {
    const std::optional<PitRemovalMethod> method = offOrMethod(*pits);
    o.removePits = method.has_value();
    o.pitRemoval.method = method.value_or(o.pitRemoval.method);
  }
  if (const auto seed = cl.take("--seed"))
  {
    o.seed = parseSeed(*seed);
  }
  o.memoryBudget = takeMemoryBudget(cl);
  o.memoryOption = kMemoryOption;
  o.sizeOption = "--size";
}

OptimiseArguments parseOptimiseArguments(std::vector<std::string> args)
{
  CommandLine cl(std::move(args));
  OptimiseArguments a;
  a.source = cl.take("--exemplar").value_or("");
  a.guide = cl.take("--guide").value_or("");
  a.output = cl.take("--output", "-o").value_or("");
  if (const auto size = cl.take("--size"))
  {
    a.grid = parseSize(*size, a.grid);
  }
  takeOptimisationOptions(cl, a.options);
  a.progress = !cl.takeFlag("--no-progress");
  if (!cl.positionals().empty())
  {
    throw UsageError("Unexpected argument \"" + cl.positionals().front() + "\".");
  }
  if (a.source.empty() || a.guide.empty())
  {
    throw UsageError("tsynth optimise needs a source --exemplar DEM and a --guide.");
  }
  if (a.output.empty() || (!isVtiPath(a.output) && !isHeightfieldWriteExtension(a.output)))
  {
    throw UsageError("tsynth optimise needs an output file: -o OUT.tif|.png|.vti.");
  }
  FileRoles files;
  files.input(a.source, "--exemplar");
  files.input(a.guide, "--guide");
  files.output(a.output, "-o");
  files.check();
  return a;
}

// Reads the source and the guide, builds the guide field and optimises, with
// progress; throws Cancelled as soon as Ctrl-C is seen.
OptimisationResult optimiseFromFiles(OptimiseArguments& a, const InterruptGuard& interrupt)
{
  const Heightfield source = readDem(a.source, {});
  std::vector<std::string> warnings;
  const SketchInput sketch = readSketchInput(a.guide, warnings);
  printWarnings(warnings);
  interrupt.check();
  SetupOptionNames names;
  names.size = "--size";
  names.patch = "the guide's landform scale";
  const OptimisationGuide guide = buildOptimisationGuide(source, sketch, a.grid, a.options, names);
  printWarnings(guide.warnings);
  interrupt.check();
  std::cout << "Optimising " << guide.field.width << " x " << guide.field.height
            << " cells (guide: " << guide.kind << ")" << std::endl;
  ProgressBar bar(a.progress);
  a.options.progress = [&](double f, const std::string& stage) { bar(f, stage); };
  a.options.guideConfidence = guide.confidence;
  const auto t0 = std::chrono::steady_clock::now();
  OptimisationResult r = optimiseTerrain(source, guide.field, a.options);
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::cout << "Optimised in " << std::fixed << std::setprecision(2) << seconds << " s.\n"
            << std::defaultfloat;
  return r;
}

void printLevels(const OptimisationResult& r)
{
  std::cout << "Level  size         energy (m^2 per patch, each iteration)   pits    s\n";
  for (const OptimisationLevel& l : r.levels)
  {
    std::ostringstream sizes;
    sizes << l.width << " x " << l.height;
    std::ostringstream energies;
    energies << std::setprecision(4);
    for (double e : l.energy)
    {
      energies << e << " ";
    }
    std::cout << std::left << std::setw(7) << l.level << std::setw(13) << sizes.str()
              << std::setw(41) << energies.str() << std::setw(8) << l.pitsAfter << std::fixed
              << std::setprecision(2) << l.seconds << "\n"
              << std::defaultfloat;
  }
}

} // namespace

int runOptimise(std::vector<std::string> args)
{
  if (wantsHelp(args))
  {
    std::cout << withOptionRows(kOptimiseHelp, optimisationOptionRows()) << kReadOptionsHelp;
    return 0;
  }
  OptimiseArguments a = parseOptimiseArguments(std::move(args));
  const InterruptGuard interrupt; // from here on Ctrl-C stops the run cleanly
  try
  {
    const OptimisationResult r = optimiseFromFiles(a, interrupt);
    writeTerrainFile(a.output, r.terrain);
    printLevels(r);
    std::cout << "Wrote " << a.output << "\n";
    return 0;
  }
  catch (const Cancelled&)
  {
    std::cerr << "\ntsynth: stopped; nothing was written.\n";
    return interruptedExit();
  }
}

} // namespace tsynth::cli
