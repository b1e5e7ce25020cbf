// Fuzz target: the .vtp poly-line sketch reader (readPolyDataFile, as `tsynth
// synth --sketch LINES.vtp` and the ParaView filters read it) and what the
// set-up makes of the lines: the sketch in metres, the output grid, the feature
// graph of the lines in cells and, on grids of up to kMaxTargetCells, the
// synthesis target. The generator lines of `tsynth distance` too.
#include "Core/Error.h"
#include "DistanceInputs.h"
#include "FeatureGraphConversion.h"
#include "FuzzExemplar.h"
#include "FuzzSupport.h"
#include "Synthesis/Setup.h"

#include <vtkNew.h>
#include <vtkObject.h>
#include <vtkPolyData.h>

namespace
{

// Targets are rasters of the output grid: only small ones keep a run fast.
constexpr std::size_t kMaxTargetCells = 256 * 256;

void quietVtk()
{
  static const bool once = []
  {
    vtkObject::GlobalWarningDisplayOff();
    return true;
  }();
  (void)once;
}

void interpretSketch(vtkPolyData* data)
{
  const tsynth::PolylineSketch sketch = tsynth::polyDataToPolylineSketch(data);
  const tsynth::OutputGrid grid = tsynth::outputGrid(tsynth::polylineExtent(sketch),
    {},
    tsynth::fuzz::kExemplarCell,
    tsynth::fuzz::kExemplarCell,
    tsynth::fuzz::kFuzzPatch);
  const tsynth::AnalysedSketch analysed =
    tsynth::analyseSketch(sketch, grid, tsynth::fuzz::kFuzzPatch);
  if (static_cast<std::size_t>(grid.width) * static_cast<std::size_t>(grid.height) >
    kMaxTargetCells)
  {
    return;
  }
  tsynth::makeTarget(analysed.graph,
    analysed.width,
    analysed.height,
    nullptr,
    grid.width,
    grid.height,
    grid.cellX,
    grid.cellY,
    tsynth::fuzz::exemplarStatisticsForFuzzing(),
    tsynth::fuzz::kFuzzPatch,
    tsynth::SketchHeights::None);
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  quietVtk();
  const std::string path = tsynth::fuzz::writeScratch("lines.vtp", data, size);
  vtkNew<vtkPolyData> lines;
  try
  {
    tsynth::readPolyDataFile(path, lines);
  }
  catch (const tsynth::Error&)
  {
    return 0; // not a readable .vtp, told as it should be
  }
  try
  {
    interpretSketch(lines);
  }
  catch (const tsynth::Error&)
  {
  }
  try
  {
    tsynth::polyDataToGeneratorLines(lines, tsynth::fuzz::kExemplarCell);
  }
  catch (const tsynth::Error&)
  {
  }
  return 0;
}
