#include "vtkTerrainSynthesis.h"

#include "CandidatePoolTable.h"

#include "FeatureGraphConversion.h"
#include "MatchingInputs.h"
#include "ParallelPieces.h"
#include "PipelineRequests.h"
#include "PropertyEnums.h"
#include "SketchInputs.h"
#include "TerrainImageConversion.h"

#include "Core/ContentHash.h"
#include "Core/Error.h"
#include "Core/Memory.h"
#include "Synthesis/PatchColours.h"
#include "Synthesis/Preview.h"
#include "Synthesis/Regions.h"
#include "Synthesis/SeamLines.h"
#include "Synthesis/Setup.h"
#include "Synthesis/SynthesisFigures.h"
#include "Synthesis/SynthesisRequest.h"
#include "Synthesis/Synthesiser.h"
#include "Synthesis/TileRecord.h"

#include <vtkAlgorithmOutput.h>
#include <vtkCellArray.h>
#include <vtkDataObject.h>
#include <vtkDoubleArray.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSignedCharArray.h>
#include <vtkSmartPointer.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkStringArray.h>
#include <vtkTable.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <iterator>
#include <memory>
#include <new>
#include <thread>

vtkStandardNewMacro(vtkTerrainSynthesis);

// The enumerations scripts set (vtkTerrainSynthesis.NEW) number the kernels' words alike.
static_assert(vtkTerrainSynthesis::CPU == static_cast<int>(tsynth::Backend::Cpu));
static_assert(vtkTerrainSynthesis::NEW == static_cast<int>(tsynth::MergeMode::New));
static_assert(vtkTerrainSynthesis::CONCENTRIC == static_cast<int>(tsynth::FillOrder::Concentric));
static_assert(
  vtkTerrainSynthesis::DRAIN_BY_HYBRID == static_cast<int>(tsynth::PitRemovalMethod::Hybrid) + 1);

namespace
{
constexpr int kExemplarHeights = 0; // SetInputArrayToProcess index of the exemplars' heights
// The optional input ports: style regions, and the Candidate Builder's pool.
constexpr int kRegionsPort = 2;
constexpr int kPoolPort = 3;
// The output ports: the terrain, and what shows how it was made.
constexpr int kTerrainPort = 0;
constexpr int kPlacementsPort = 1;
constexpr int kSketchFeaturesPort = 2;
constexpr int kSeamsPort = 3;
constexpr int kReportPort = 4;
constexpr int kConstructionPort = 5;
constexpr int kImpliedLinesPort = 6;
constexpr int kOutputPorts = 7;
} // namespace

vtkTerrainSynthesis::vtkTerrainSynthesis()
{
  this->SetInputArrayToProcess(
    kExemplarHeights, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, tsynth::kElevationArray);
  const auto initial = [](const char* property)
  { return tsynth::synthesisOption(property).defaultValue; };
  this->PatchSize = static_cast<int>(initial("PatchSize"));
  this->Backend = static_cast<int>(initial("Backend"));
  this->MergeMode = static_cast<int>(initial("MergeMode"));
  this->FillOrder = static_cast<int>(initial("FillOrder"));
  this->Drainage = static_cast<int>(initial("Drainage"));
  this->VerticalOffset = initial("VerticalOffset") != 0.0;
  this->Repetition = initial("Repetition");
  this->TileSize = static_cast<int>(initial("TileSize"));
  this->PlacementLimit = static_cast<int>(initial("PlacementLimit"));
  this->OutputSize[0] = this->OutputSize[1] = static_cast<int>(initial("OutputSize"));
  this->CellSize = initial("CellSize");
  this->Seed = static_cast<vtkIdType>(initial("Seed"));
  this->MemoryBudget = initial("MemoryBudget");
  this->LandformRelief = initial("LandformRelief");
  this->UseExemplarCache = initial("UseExemplarCache") != 0.0;
  this->SetNumberOfInputPorts(4);
  this->SetNumberOfOutputPorts(kOutputPorts);
}

int vtkTerrainSynthesis::FillInputPortInformation(int port, vtkInformation* info)
{
  // The exemplars and the sketch are optional to the executive only: RequestData names the
  // one missing in one sentence, where VTK's own check repeats a generic one per request.
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  if (port == 0)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
    info->Set(vtkAlgorithm::INPUT_IS_REPEATABLE(), 1);
    return 1;
  }
  if (port == kRegionsPort)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
    return 1;
  }
  if (port == kPoolPort)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkTable");
    return 1;
  }
  info->Remove(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE());
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

int vtkTerrainSynthesis::FillOutputPortInformation(int port, vtkInformation* info)
{
  const bool image = port == kTerrainPort || port == kConstructionPort;
  const bool lines = port == kSketchFeaturesPort || port == kSeamsPort || port == kImpliedLinesPort;
  info->Set(vtkDataObject::DATA_TYPE_NAME(),
    image     ? "vtkImageData"
      : lines ? "vtkPolyData"
              : "vtkTable");
  return 1;
}

vtkImageData* vtkTerrainSynthesis::GetTerrain()
{
  return vtkImageData::SafeDownCast(this->GetOutputDataObject(0));
}

vtkTable* vtkTerrainSynthesis::GetPlacements()
{
  return vtkTable::SafeDownCast(this->GetOutputDataObject(kPlacementsPort));
}

vtkPolyData* vtkTerrainSynthesis::GetSketchFeatures()
{
  return vtkPolyData::SafeDownCast(this->GetOutputDataObject(kSketchFeaturesPort));
}

vtkPolyData* vtkTerrainSynthesis::GetSeams()
{
  return vtkPolyData::SafeDownCast(this->GetOutputDataObject(kSeamsPort));
}

vtkTable* vtkTerrainSynthesis::GetReport()
{
  return vtkTable::SafeDownCast(this->GetOutputDataObject(kReportPort));
}

vtkImageData* vtkTerrainSynthesis::GetConstruction()
{
  return vtkImageData::SafeDownCast(this->GetOutputDataObject(kConstructionPort));
}

vtkPolyData* vtkTerrainSynthesis::GetImpliedLines()
{
  return vtkPolyData::SafeDownCast(this->GetOutputDataObject(kImpliedLinesPort));
}

int vtkTerrainSynthesis::RequestUpdateExtent(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector*)
{
  // Every image input (the ports before the pool, a table) is needed whole, whatever its size.
  tsynth::requestWholeExtents(inputVector, kPoolPort);
  return 1;
}

namespace
{

// Share of the progress bar taken by the set-up (features of sketch and exemplars).
constexpr double kSetupProgress = 0.05;
constexpr double kSynthesisProgress = 0.9;

tsynth::SetupOptionNames propertyNames()
{
  tsynth::SetupOptionNames names;
  names.size = "OutputSize";
  names.cell = "CellSize";
  names.patch = "Patch Size";
  names.memory = "MemoryBudget";
  return names;
}

// Throws tsynth::Error naming the input a user has not connected yet.
void requireInputs(vtkInformationVector** inputVector)
{
  if (inputVector[0]->GetNumberOfInformationObjects() == 0)
  {
    throw tsynth::Error("No exemplar is connected: give Exemplars one or more DEMs (open them "
                        "with the Terrain Reader).");
  }
  if (inputVector[1]->GetNumberOfInformationObjects() == 0)
  {
    throw tsynth::Error("No sketch is connected: give Sketch a stroke map, a grey map, "
                        "poly-lines (Terrain Sketch Lines) or a DEM target.");
  }
}

void addDiagnosticArrays(const tsynth::SynthesisResult& r, vtkImageData* output)
{
  const vtkIdType n = static_cast<vtkIdType>(r.terrain.size());
  vtkNew<vtkIntArray> patchId;
  patchId->SetName("PatchId");
  patchId->SetNumberOfTuples(n);
  std::copy(r.patchId.begin(), r.patchId.end(), patchId->GetPointer(0));
  output->GetPointData()->AddArray(patchId);
  vtkNew<vtkIntArray> order;
  order->DeepCopy(patchId);
  order->SetName("PlacementOrder");
  output->GetPointData()->AddArray(order);
  vtkNew<vtkUnsignedCharArray> seam;
  seam->SetName("SeamMask");
  seam->SetNumberOfTuples(n);
  std::copy(r.seam.begin(), r.seam.end(), seam->GetPointer(0));
  output->GetPointData()->AddArray(seam);
  tsynth::addPointArray(output, "MatchCost", r.matchCost.data());
  const std::vector<std::int8_t> colours =
    tsynth::patchColours(r.patchId, r.terrain.width, r.terrain.height);
  vtkNew<vtkSignedCharArray> colour;
  colour->SetName("PatchColour");
  colour->SetNumberOfTuples(n);
  std::copy(colours.begin(), colours.end(), colour->GetPointer(0));
  output->GetPointData()->AddArray(colour);
}

// One row per placement; source positions in metres in each exemplar's own frame.
void fillPlacementTable(const tsynth::SynthesisResult& r,
  const tsynth::SynthesisSetup& setup,
  const tsynth::ExemplarInputs& ex,
  vtkTable* table)
{
  const char* intNames[] = { "Order", "Feature", "Exemplar", "Variant", "Column", "Row" };
  const char* realNames[] = { "SourceX", "SourceY", "MatchCost", "SeamCost", "Offset" };
  std::vector<vtkNew<vtkIntArray>> ints(std::size(intNames));
  std::vector<vtkNew<vtkDoubleArray>> reals(std::size(realNames));
  for (std::size_t c = 0; c < ints.size(); ++c)
  {
    ints[c]->SetName(intNames[c]);
  }
  for (std::size_t c = 0; c < reals.size(); ++c)
  {
    reals[c]->SetName(realNames[c]);
  }
  for (const tsynth::Placement& p : r.placements)
  {
    const auto e = static_cast<std::size_t>(p.exemplar);
    ints[0]->InsertNextValue(p.order);
    ints[1]->InsertNextValue(p.feature ? 1 : 0);
    ints[2]->InsertNextValue(p.exemplar);
    ints[3]->InsertNextValue(p.variant);
    ints[4]->InsertNextValue(p.x0);
    ints[5]->InsertNextValue(p.y0);
    reals[0]->InsertNextValue(ex.originX[e] + p.sourceX * setup.exemplars[e].cellX);
    reals[1]->InsertNextValue(ex.originY[e] + p.sourceY * setup.exemplars[e].cellY);
    reals[2]->InsertNextValue(p.matchCost);
    reals[3]->InsertNextValue(p.seamCost);
    reals[4]->InsertNextValue(p.offset);
  }
  for (auto& a : ints)
  {
    table->AddColumn(a);
  }
  for (auto& a : reals)
  {
    table->AddColumn(a);
  }
}

// The output grid the properties ask for (zeros: from the inputs).
tsynth::GridRequest gridRequest(vtkTerrainSynthesis* filter)
{
  tsynth::GridRequest request;
  const int* size = filter->GetOutputSize();
  if (size[0] > 0 || size[1] > 0)
  {
    request.width = size[0];
    request.height = size[1];
  }
  request.cellX = filter->GetCellSize();
  request.cellY = filter->GetCellSize();
  return request;
}

// The request the properties make: every option of the synthesis, read once.
tsynth::SynthesisRequest synthesisRequest(vtkTerrainSynthesis* filter)
{
  tsynth::SynthesisRequest r;
  tsynth::SynthesisOptions& o = r.options;
  o.patchSize = filter->GetPatchSize();
  o.backend = tsynth::backendFromProperty(filter->GetBackend());
  o.merge = tsynth::mergeModeFromProperty(filter->GetMergeMode());
  o.fill = tsynth::fillOrderFromProperty(filter->GetFillOrder());
  o.drainage = tsynth::drainageFromProperty(filter->GetDrainage());
  o.verticalOffset = filter->GetVerticalOffset();
  o.repetitionPenalty = filter->GetRepetition();
  o.tileSize = filter->GetTileSize();
  o.placementLimit = tsynth::placementLimitOf(filter->GetPlacementLimit());
  o.seed = static_cast<std::uint64_t>(filter->GetSeed());
  o.progress = [filter](double f, const std::string&)
  { filter->UpdateProgress(kSetupProgress + kSynthesisProgress * f); };
  r.grid = gridRequest(filter);
  r.landformRelief = filter->GetLandformRelief();
  r.memoryBudgetGB = filter->GetMemoryBudget();
  r.useExemplarCache = filter->GetUseExemplarCache();
  r.cacheDirectory = filter->GetExemplarCacheDirectory();
  return r;
}

// The seams as poly-lines along the borders between patches (tsynth::seamLines), in metres on
// the terrain's grid at z = 0, with an Elevation point array (the mean height of the cells
// around each corner) so that Warp By Scalar lifts them onto the warped terrain.
void seamsToPolyData(const tsynth::SynthesisResult& r, vtkPolyData* out)
{
  const tsynth::Heightfield& t = r.terrain;
  const std::vector<tsynth::SeamLine> lines = tsynth::seamLines(r.patchId, t.width, t.height);
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> cells;
  vtkNew<vtkFloatArray> elevation;
  elevation->SetName(tsynth::kElevationArray);
  auto cornerHeight = [&t](int i, int j)
  {
    double sum = 0.0;
    int n = 0;
    for (int y = j - 1; y <= j; ++y)
    {
      for (int x = i - 1; x <= i; ++x)
      {
        if (x >= 0 && y >= 0 && x < t.width && y < t.height && t.isValid(x, y))
        {
          sum += t.at(x, y);
          ++n;
        }
      }
    }
    return n > 0 ? sum / n : 0.0;
  };
  constexpr double kCornerOffset = 0.5; // corner (i, j) is half a cell below-left of cell (i, j)
  for (const tsynth::SeamLine& line : lines)
  {
    cells->InsertNextCell(static_cast<vtkIdType>(line.size()));
    for (const tsynth::CellCorner& c : line)
    {
      cells->InsertCellPoint(points->InsertNextPoint(
        (c.i - kCornerOffset) * t.cellX, (c.j - kCornerOffset) * t.cellY, 0.0));
      elevation->InsertNextValue(static_cast<float>(cornerHeight(c.i, c.j)));
    }
  }
  out->SetPoints(points);
  out->SetLines(cells);
  out->GetPointData()->AddArray(elevation);
}

// The synthesis report as a table: a Figure name (tsynth::figureRows) and its Value per row.
void fillReport(const tsynth::SynthesisFigures& figures, vtkTable* table)
{
  vtkNew<vtkStringArray> names;
  names->SetName("Figure");
  vtkNew<vtkDoubleArray> values;
  values->SetName("Value");
  for (const tsynth::FigureRow& row : tsynth::figureRows(figures))
  {
    names->InsertNextValue(row.name);
    values->InsertNextValue(row.value);
  }
  table->AddColumn(names);
  table->AddColumn(values);
}

// The construction image: the target field the synthesis followed (Target, metres), its
// confidence (TargetConfidence, 0-1) and the terrain as the patches made it, before the final
// corrections (Patches, metres), on the terrain's grid: `tsynth synth --debug-dir`'s
// target.tif, target-confidence.tif and patches.tif.
void fillConstruction(const tsynth::SynthesisSetup& setup,
  const tsynth::SynthesisResult& r,
  vtkImageData* out)
{
  tsynth::heightfieldToImage(r.patches, out);
  out->GetPointData()->GetArray(tsynth::kElevationArray)->SetName("Patches");
  vtkNew<vtkImageData> target;
  tsynth::heightfieldToImage(setup.target.field, target);
  vtkDataArray* field = target->GetPointData()->GetArray(tsynth::kElevationArray);
  field->SetName("Target");
  out->GetPointData()->AddArray(field);
  tsynth::addPointArray(out, "TargetConfidence", setup.target.weight.data());
  out->GetPointData()->SetActiveScalars("Target");
}

// Nothing announced on the image outputs: not the exemplar's grid the pipeline copied in by
// default.
void clearAnnouncedGrid(vtkInformationVector* outputVector)
{
  for (int port : { kTerrainPort, kConstructionPort })
  {
    vtkInformation* out = outputVector->GetInformationObject(port);
    out->Remove(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT());
    out->Remove(vtkDataObject::SPACING());
    out->Remove(vtkDataObject::ORIGIN());
  }
}

} // namespace

int vtkTerrainSynthesis::RequestInformation(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkInformation* sketch = inputVector[1]->GetInformationObject(0);
  vtkInformation* exemplar = inputVector[0]->GetInformationObject(0);
  if (sketch == nullptr || exemplar == nullptr)
  {
    return 1; // nothing to announce; RequestData says which input is missing
  }
  if (tsynth::anyImageProducerFailed(inputVector, this->GetNumberOfInputPorts()))
  {
    clearAnnouncedGrid(outputVector);
    return 0; // the reader that failed said why
  }
  try
  {
    if (this->PatchSize != tsynth::kAutomaticPatch)
    {
      tsynth::checkPatchSize(this->PatchSize, propertyNames().patch);
    }
    // The grid RequestData's set-up will produce, by the same kernel function.
    const tsynth::SketchExtent extent = tsynth::announcedSketchExtent(this, 1, inputVector[1]);
    // The patch sizes only the poly-lines' grid (half a patch past their
    // reach), and poly-lines are no DEM target: an automatic patch is theirs.
    const int patch = tsynth::patchSizeFor(this->PatchSize, tsynth::PolylineSketch{});
    double spacing[3] = { 0.0, 0.0, 0.0 };
    if (exemplar->Has(vtkDataObject::SPACING()))
    {
      exemplar->Get(vtkDataObject::SPACING(), spacing);
    }
    const tsynth::OutputGrid grid =
      tsynth::outputGrid(extent, gridRequest(this), spacing[0], spacing[1], patch, propertyNames());
    const int wholeExtent[6] = { 0, grid.width - 1, 0, grid.height - 1, 0, 0 };
    const double origin[3] = { 0.0, 0.0, 0.0 };
    const int noExtent[6] = { 0, -1, 0, -1, 0, -1 };
    for (int port : { kTerrainPort, kConstructionPort })
    {
      const bool made = port == kTerrainPort || this->DebugOutputs;
      vtkInformation* out = outputVector->GetInformationObject(port);
      out->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), made ? wholeExtent : noExtent, 6);
      // Each rank of a parallel engine may ask for its piece only (ParallelPieces.h).
      out->Set(vtkAlgorithm::CAN_PRODUCE_SUB_EXTENT(), 1);
      out->Set(vtkDataObject::SPACING(), grid.cellX, grid.cellY, 1.0);
      out->Set(vtkDataObject::ORIGIN(), origin, 3);
    }
  }
  catch (const std::exception& e)
  {
    clearAnnouncedGrid(outputVector);
    tsynth::reportRefusal(this, e.what()); // once, not again in RequestData or the next update
    return 0;
  }
  return 1;
}

namespace
{

// The set-up's inputs from the filter's inputs and its request, whose automatic
// patch size is fixed for the sketch found; the exemplars' origins and warnings
// stay in `ex` for the placement table.
tsynth::SetupInputs setupInputs(vtkTerrainSynthesis* filter,
  tsynth::SynthesisRequest& request,
  vtkInformationVector** inputVector,
  tsynth::ExemplarInputs& ex)
{
  requireInputs(inputVector);
  ex = tsynth::gatherExemplarImages(inputVector[0],
    tsynth::exemplarHeightsNamed(
      filter->GetInputArrayInformation(kExemplarHeights), inputVector[0]));
  tsynth::SketchInput sketch =
    tsynth::sketchInput(vtkDataObject::GetData(inputVector[1], 0), ex.warnings);
  tsynth::resolvePatchSize(request, sketch, propertyNames());
  // The placement table needs only ex's origins.
  tsynth::SetupInputs in =
    tsynth::setupInputs(request, std::move(ex.heights), {}, std::move(sketch), propertyNames());
  if (vtkTable* pool = vtkTable::GetData(inputVector[kPoolPort], 0))
  {
    in.pool = std::make_shared<const tsynth::CandidatePool>(tsynth::poolFromTable(pool));
  }
  return in;
}

// The request's options, with the style regions (port 2) laid on the terrain's grid.
tsynth::SynthesisOptions optionsOnGrid(const tsynth::SynthesisRequest& request,
  vtkInformationVector** inputVector,
  const std::vector<std::string>& regionMaps,
  const tsynth::OutputGrid& grid,
  std::size_t exemplars)
{
  tsynth::SynthesisOptions o = request.options;
  if (inputVector[kRegionsPort]->GetNumberOfInformationObjects() > 0)
  {
    const tsynth::Heightfield labels =
      tsynth::imageToHeightfield(vtkImageData::GetData(inputVector[kRegionsPort], 0));
    tsynth::assignRegions(o, labels, regionMaps, grid.width, grid.height, exemplars);
  }
  return o;
}

} // namespace

// The whole synthesis run on a thread of its own while the preview is shown. It touches no
// VTK object: it works on copies of the inputs, and its result is taken on the pipeline's
// thread once `finished` says so.
class vtkTerrainSynthesis::vtkRefinement
{
public:
  std::thread worker;
  std::atomic<bool> stop{ false };
  std::atomic<bool> finished{ false };
  bool announced = false; // GetNeedsUpdate() said so
  std::uint64_t key = 0;  // tsynth::synthesisRequestKey of the request it answers
  // Shown until it is done: the preview's heights on the terrain's grid, and the lines it
  // followed (in metres, as the whole synthesis gives them).
  tsynth::Heightfield preview;
  tsynth::FeatureGraph sketchLines;
  tsynth::FeatureGraph impliedLines;
  tsynth::ExemplarInputs exemplars;
  tsynth::SynthesisSetup setup;
  tsynth::SynthesisResult result;
  std::string error; // why it failed ("": it did not)
  // The filter's last tile record, which the synthesis takes tiles from if it serves.
  std::shared_ptr<const tsynth::PlacementRecord> lastRecord;

  void start(tsynth::SetupInputs in, tsynth::SynthesisOptions o)
  {
    o.progress = nullptr; // UpdateProgress is the pipeline thread's
    this->worker = std::thread(
      [this, in = std::move(in), o = std::move(o)]() mutable
      {
        try
        {
          const tsynth::CancellationScope scope([this] { return this->stop.load(); });
          this->setup = tsynth::prepareSynthesis(std::move(in));
          tsynth::useRecordIfItServes(
            o, std::move(this->lastRecord), this->setup.target, this->setup.exemplarPointers());
          this->result = tsynth::synthesise(this->setup, o);
        }
        catch (const tsynth::Cancelled&)
        {
          this->error = "stopped";
        }
        catch (const std::bad_alloc&)
        {
          this->error = kOutOfMemory;
        }
        catch (const std::exception& e)
        {
          this->error = e.what();
        }
        this->finished.store(true);
      });
  }

  void join()
  {
    if (this->worker.joinable())
    {
      this->worker.join();
    }
  }

  ~vtkRefinement()
  {
    this->stop.store(true);
    this->join();
  }

  static constexpr const char* kOutOfMemory =
    "The synthesis ran out of memory; give a smaller OutputSize or a larger "
    "CellSize, or fewer or smaller exemplars.";
};

vtkTerrainSynthesis::~vtkTerrainSynthesis()
{
  this->StopRefinement();
  this->ForgetWholeOutputs();
}

void vtkTerrainSynthesis::StopRefinement()
{
  delete this->Refinement; // stops and joins it
  this->Refinement = nullptr;
}

void vtkTerrainSynthesis::WaitForRefinement()
{
  if (this->Refinement != nullptr)
  {
    this->Refinement->join();
  }
}

bool vtkTerrainSynthesis::GetNeedsUpdate()
{
  vtkRefinement* r = this->Refinement;
  if (r == nullptr || r->announced || !r->finished.load())
  {
    return false;
  }
  r->announced = true;
  this->Modified(); // the next update shows it
  return true;
}

namespace
{

// Every output of a finished synthesis.
void writeOutputs(vtkTerrainSynthesis* filter,
  const tsynth::SynthesisSetup& setup,
  const tsynth::SynthesisResult& r,
  const tsynth::ExemplarInputs& ex,
  vtkInformationVector* outputVector)
{
  for (const auto& warning : r.warnings)
  {
    vtkWarningWithObjectMacro(filter, << warning);
  }
  vtkImageData* output = vtkImageData::GetData(outputVector, kTerrainPort);
  tsynth::heightfieldToImage(r.terrain, output);
  addDiagnosticArrays(r, output);
  fillPlacementTable(r, setup, ex, vtkTable::GetData(outputVector, kPlacementsPort));
  tsynth::featureGraphToPolyData(
    setup.target.graph, vtkPolyData::GetData(outputVector, kSketchFeaturesPort));
  tsynth::featureGraphToPolyData(
    setup.target.implied, vtkPolyData::GetData(outputVector, kImpliedLinesPort));
  seamsToPolyData(r, vtkPolyData::GetData(outputVector, kSeamsPort));
  // The figures measure a finished terrain, not one stopped after some placements.
  if (filter->GetDebugOutputs() && filter->GetPlacementLimit() == tsynth::kAllPlacementsNumber)
  {
    fillReport(tsynth::measureSynthesis(setup, r, setup.patchSize),
      vtkTable::GetData(outputVector, kReportPort));
    fillConstruction(setup, r, vtkImageData::GetData(outputVector, kConstructionPort));
  }
}

// On ParaView's parallel engine each rank's outputs hold its piece: the
// images their extent, the tables and lines the first piece alone. True if any
// output now holds less than the whole.
bool keepRequestedPieces(vtkInformationVector* outputVector)
{
  bool cut = false;
  for (int port = 0; port < kOutputPorts; ++port)
  {
    vtkInformation* out = outputVector->GetInformationObject(port);
    if (auto* image = vtkImageData::GetData(outputVector, port))
    {
      cut = tsynth::keepRequestedExtent(out, image) || cut;
    }
    else if (!tsynth::holdsFirstPiece(out))
    {
      vtkDataObject::GetData(outputVector, port)->Initialize();
      cut = true;
    }
  }
  return cut;
}

void clearOutputs(vtkInformationVector* outputVector)
{
  for (int port = 0; port < kOutputPorts; ++port)
  {
    vtkDataObject::GetData(outputVector, port)->Initialize();
  }
}

} // namespace

// The whole outputs of the last synthesis (shallow copies taken before they were cut to this
// rank's piece) and the key of what made them (wholeOutputsKey).
class vtkTerrainSynthesis::vtkWholeOutputs
{
public:
  std::uint64_t key = 0;
  std::array<vtkSmartPointer<vtkDataObject>, kOutputPorts> outputs;
};

void vtkTerrainSynthesis::ForgetWholeOutputs()
{
  delete this->WholeOutputs;
  this->WholeOutputs = nullptr;
}

namespace
{

// What decides every output of a synthesis: what decides its terrain (the kernel's key), the
// exemplars' origins (the placement table's source positions) and whether the debug outputs
// are filled.
std::uint64_t wholeOutputsKey(const tsynth::SetupInputs& in,
  const tsynth::SynthesisOptions& o,
  const tsynth::ExemplarInputs& ex,
  bool debugOutputs)
{
  tsynth::ContentHasher h;
  h.value(tsynth::synthesisRequestKey(in, o));
  h.values(ex.originX);
  h.values(ex.originY);
  h.value(debugOutputs);
  return h.digest();
}

std::unique_ptr<vtkTerrainSynthesis::vtkWholeOutputs> copyWholeOutputs(std::uint64_t key,
  vtkInformationVector* outputVector)
{
  auto whole = std::make_unique<vtkTerrainSynthesis::vtkWholeOutputs>();
  whole->key = key;
  for (int port = 0; port < kOutputPorts; ++port)
  {
    vtkDataObject* output = vtkDataObject::GetData(outputVector, port);
    whole->outputs[static_cast<std::size_t>(port)].TakeReference(output->NewInstance());
    whole->outputs[static_cast<std::size_t>(port)]->ShallowCopy(output);
  }
  return whole;
}

void restoreWholeOutputs(const vtkTerrainSynthesis::vtkWholeOutputs& whole,
  vtkInformationVector* outputVector)
{
  for (int port = 0; port < kOutputPorts; ++port)
  {
    vtkDataObject::GetData(outputVector, port)
      ->ShallowCopy(whole.outputs[static_cast<std::size_t>(port)]);
  }
}

} // namespace

int vtkTerrainSynthesis::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  if (tsynth::anyImageProducerFailed(inputVector, this->GetNumberOfInputPorts()))
  {
    // ParaView asks for the data even after RequestInformation failed; nothing to add to what
    // the reader said.
    this->StopRefinement();
    this->ForgetWholeOutputs();
    clearOutputs(outputVector);
    this->OutputLevel = "none";
    return 0;
  }
  return tsynth::runFilterRequest(
    this,
    vtkRefinement::kOutOfMemory,
    [&]
    {
      clearOutputs(outputVector); // aborted: empty outputs
      this->OutputLevel = "none";
    },
    [&]
    {
      if (this->PreviewFirst && this->PlacementLimit == tsynth::kAllPlacementsNumber)
      {
        this->ForgetWholeOutputs();
        this->PreviewOrRefined(inputVector, outputVector);
        return;
      }
      this->StopRefinement();
      this->SynthesiseOrCut(inputVector, outputVector);
      this->OutputLevel =
        this->PlacementLimit == tsynth::kAllPlacementsNumber ? "final" : "placements";
    });
}

void vtkTerrainSynthesis::SynthesiseOrCut(vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  tsynth::SynthesisRequest request = this->RequestWithRecord();
  tsynth::ExemplarInputs ex;
  tsynth::SetupInputs in = setupInputs(this, request, inputVector, ex);
  tsynth::SynthesisOptions o = optionsOnGrid(
    request, inputVector, this->RegionMaps, tsynth::plannedGrid(in), in.exemplars.size());
  const std::uint64_t key = wholeOutputsKey(in, o, ex, this->DebugOutputs);
  if (this->WholeOutputs != nullptr && this->WholeOutputs->key == key)
  {
    restoreWholeOutputs(*this->WholeOutputs, outputVector);
    keepRequestedPieces(outputVector);
    return;
  }
  this->ForgetWholeOutputs(); // its memory goes to the new synthesis
  for (const auto& w : ex.warnings)
  {
    vtkWarningMacro(<< w);
  }
  const tsynth::SynthesisSetup setup = tsynth::prepareSynthesis(std::move(in));
  for (const auto& w : setup.warnings)
  {
    vtkWarningMacro(<< w);
  }
  this->UpdateProgress(kSetupProgress);
  tsynth::shareTilesAmongRanks(o);
  tsynth::useRecordIfItServes(o, this->TileRecord, setup.target, setup.exemplarPointers());
  this->TileRecord = nullptr; // its memory goes to the new one
  const tsynth::SynthesisResult r = tsynth::synthesise(setup, o);
  tsynth::reportRankWork(o, r);
  this->KeepRecord(r);
  this->BackendUsed = r.backend;
  writeOutputs(this, setup, r, ex, outputVector);
  auto whole = copyWholeOutputs(key, outputVector);
  if (keepRequestedPieces(outputVector))
  {
    this->WholeOutputs = whole.release(); // for the next extent of this synthesis
  }
}

namespace
{

// The preview in place of the whole synthesis: its heights, and the lines it followed so that
// their representation keeps its colours; the other outputs empty.
void showPreview(const vtkTerrainSynthesis::vtkRefinement& r, vtkInformationVector* outputVector)
{
  clearOutputs(outputVector);
  tsynth::heightfieldToImage(r.preview, vtkImageData::GetData(outputVector, kTerrainPort));
  tsynth::featureGraphToPolyData(
    r.sketchLines, vtkPolyData::GetData(outputVector, kSketchFeaturesPort));
  tsynth::featureGraphToPolyData(
    r.impliedLines, vtkPolyData::GetData(outputVector, kImpliedLinesPort));
}

} // namespace

void vtkTerrainSynthesis::PreviewOrRefined(vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  tsynth::SynthesisRequest request = this->RequestWithRecord();
  tsynth::ExemplarInputs ex;
  tsynth::SetupInputs in = setupInputs(this, request, inputVector, ex);
  const tsynth::PreviewPlan plan = tsynth::planPreview(in);
  tsynth::SynthesisOptions o =
    optionsOnGrid(request, inputVector, this->RegionMaps, plan.full, in.exemplars.size());
  const std::uint64_t key = tsynth::synthesisRequestKey(in, o);
  if (vtkRefinement* r = this->Refinement; r != nullptr && r->key == key)
  {
    if (!r->finished.load())
    {
      showPreview(*r, outputVector); // asked again while it runs
      this->OutputLevel = "preview";
      return;
    }
    r->join();
    if (!r->error.empty())
    {
      throw tsynth::Error(r->error);
    }
    this->KeepRecord(r->result);
    this->BackendUsed = r->result.backend;
    writeOutputs(this, r->setup, r->result, r->exemplars, outputVector);
    this->OutputLevel = "final";
    return;
  }
  this->StopRefinement(); // it answers another request
  if (!plan.available())
  {
    vtkWarningMacro(<< "No preview for a Patch Size of " << in.patchSize
                    << " (its coarser level would be under " << tsynth::kMinSynthesisPatch
                    << " cells): the whole synthesis is done at once.");
    const tsynth::SynthesisSetup setup = tsynth::prepareSynthesis(std::move(in));
    tsynth::useRecordIfItServes(o, this->TileRecord, setup.target, setup.exemplarPointers());
    const tsynth::SynthesisResult r = tsynth::synthesise(setup, o);
    this->KeepRecord(r);
    this->BackendUsed = r.backend;
    writeOutputs(this, setup, r, ex, outputVector);
    this->OutputLevel = "final";
    return;
  }
  tsynth::SynthesisOptions quiet = o;
  quiet.progress = nullptr; // a fraction of a second
  auto r = std::make_unique<vtkRefinement>();
  r->key = key;
  tsynth::Preview preview = tsynth::synthesisePreview(in, quiet);
  r->preview = std::move(preview.onFullGrid);
  r->sketchLines = std::move(preview.setup.target.graph);
  r->impliedLines = std::move(preview.setup.target.implied);
  showPreview(*r, outputVector);
  this->OutputLevel = "preview";
  r->exemplars = std::move(ex);
  r->lastRecord = this->TileRecord;
  r->start(std::move(in), std::move(o));
  this->Refinement = r.release();
}

tsynth::SynthesisRequest vtkTerrainSynthesis::RequestWithRecord()
{
  tsynth::SynthesisRequest request = synthesisRequest(this);
  // What the memory estimate counts; useRecordIfItServes decides once the target is made.
  request.options.keepRecord = this->TileSize > 0;
  request.options.previous = this->TileRecord;
  return request;
}

void vtkTerrainSynthesis::KeepRecord(const tsynth::SynthesisResult& r)
{
  this->TileRecord = r.record;
  this->TilesTakenOver = static_cast<vtkIdType>(r.tilesTakenOver);
}

void vtkTerrainSynthesis::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "PatchSize: " << this->PatchSize << "\n";
  os << indent << "Backend: " << this->Backend << "\n";
  os << indent << "MergeMode: " << this->MergeMode << "\n";
  os << indent << "FillOrder: " << this->FillOrder << "\n";
  os << indent << "Drainage: " << this->Drainage << "\n";
  os << indent << "VerticalOffset: " << this->VerticalOffset << "\n";
  os << indent << "Repetition: " << this->Repetition << "\n";
  os << indent << "TileSize: " << this->TileSize << "\n";
  os << indent << "PlacementLimit: " << this->PlacementLimit << "\n";
  os << indent << "OutputSize: " << this->OutputSize[0] << " x " << this->OutputSize[1] << "\n";
  os << indent << "CellSize: " << this->CellSize << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "MemoryBudget: " << this->MemoryBudget << " GB\n";
  os << indent << "LandformRelief: " << this->LandformRelief << "\n";
  os << indent << "UseExemplarCache: " << this->UseExemplarCache << "\n";
  os << indent << "ExemplarCacheDirectory: " << this->ExemplarCacheDirectory << "\n";
  os << indent << "WholeOutputsKept: " << (this->WholeOutputs != nullptr ? "yes" : "no") << "\n";
  os << indent << "DebugOutputs: " << (this->DebugOutputs ? "on" : "off") << "\n";
  os << indent << "PreviewFirst: " << (this->PreviewFirst ? "on" : "off") << "\n";
  os << indent << "OutputLevel: " << this->OutputLevel << "\n";
  os << indent << "Refinement: "
     << (this->Refinement == nullptr     ? "none"
            : this->Refinement->finished ? "finished"
                                         : "under way")
     << "\n";
  os << indent << "RegionMaps: " << this->RegionMaps.size() << "\n";
  os << indent << "BackendUsed: " << (this->BackendUsed.empty() ? "(none yet)" : this->BackendUsed)
     << "\n";
  os << indent << "TileRecord: " << (this->TileRecord != nullptr ? "kept" : "(none)") << "\n";
  os << indent << "TilesTakenOver: " << this->TilesTakenOver << "\n";
}
