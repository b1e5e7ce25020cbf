#include "vtkTerrainSynthesis.h"

#include "FeatureGraphConversion.h"
#include "MatchingInputs.h"
#include "PipelineRequests.h"
#include "TerrainImageConversion.h"

#include "Core/Error.h"
#include "Features/Ppa.h"
#include "Features/Sketch.h"
#include "Synthesis/Regions.h"
#include "Synthesis/Synthesizer.h"

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
#include <vtkPolyData.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkTable.h>
#include <vtkUnsignedCharArray.h>

#include <cmath>

vtkStandardNewMacro(vtkTerrainSynthesis);

vtkTerrainSynthesis::vtkTerrainSynthesis()
{
  this->SetNumberOfInputPorts(3);
  this->SetNumberOfOutputPorts(2);
}

int vtkTerrainSynthesis::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == 0)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
    info->Set(vtkAlgorithm::INPUT_IS_REPEATABLE(), 1);
    return 1;
  }
  if (port == 2)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
    return 1;
  }
  info->Remove(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE());
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

int vtkTerrainSynthesis::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkImageData" : "vtkTable");
  return 1;
}

vtkImageData* vtkTerrainSynthesis::GetTerrain()
{
  return vtkImageData::SafeDownCast(this->GetOutputDataObject(0));
}

vtkTable* vtkTerrainSynthesis::GetPlacements()
{
  return vtkTable::SafeDownCast(this->GetOutputDataObject(1));
}

vtkTypeBool vtkTerrainSynthesis::ProcessRequest(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_INFORMATION()))
  {
    return this->RequestInformation(inputVector, outputVector);
  }
  if (request->Has(vtkStreamingDemandDrivenPipeline::REQUEST_UPDATE_EXTENT()))
  {
    // Every input is needed whole, whatever their sizes.
    tsynth::requestWholeExtents(inputVector, 3);
    return 1;
  }
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_DATA()))
  {
    return this->RequestData(inputVector, outputVector);
  }
  return this->Superclass::ProcessRequest(request, inputVector, outputVector);
}

int vtkTerrainSynthesis::RequestInformation(vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  // Size: OutputSize, else the sketch image's pixels; cells: CellSize, else the
  // first exemplar's spacing.
  int w = this->OutputSize[0];
  int h = this->OutputSize[1];
  vtkInformation* sketch = inputVector[1]->GetInformationObject(0);
  if ((w <= 0 || h <= 0) && sketch != nullptr &&
    sketch->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    int e[6];
    sketch->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), e);
    w = e[1] - e[0] + 1;
    h = e[3] - e[2] + 1;
  }
  if (w <= 0 || h <= 0)
  {
    vtkErrorMacro("Set OutputSize: poly-line sketches have no pixel size of their own.");
    return 0;
  }
  double spacing[3] = { this->CellSize, this->CellSize, 1.0 };
  vtkInformation* exemplar = inputVector[0]->GetInformationObject(0);
  if (this->CellSize <= 0.0 && exemplar != nullptr && exemplar->Has(vtkDataObject::SPACING()))
  {
    exemplar->Get(vtkDataObject::SPACING(), spacing);
  }
  if (!(spacing[0] > 0.0))
  {
    spacing[0] = spacing[1] = 1.0;
  }
  const int extent[6] = { 0, w - 1, 0, h - 1, 0, 0 };
  const double origin[3] = { 0.0, 0.0, 0.0 };
  vtkInformation* out = outputVector->GetInformationObject(0);
  out->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  out->Set(vtkDataObject::SPACING(), spacing[0], spacing[1], 1.0);
  out->Set(vtkDataObject::ORIGIN(), origin, 3);
  return 1;
}

int vtkTerrainSynthesis::RequestData(vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  vtkTable* table = vtkTable::GetData(outputVector, 1);
  vtkDataObject* sketchData = vtkDataObject::GetData(inputVector[1], 0);
  try
  {
    const tsynth::ExemplarInputs ex = tsynth::gatherExemplars(inputVector[0], nullptr);
    const double cellX = this->CellSize > 0.0 ? this->CellSize : ex.heights.front().cellX;
    const double cellY = this->CellSize > 0.0 ? this->CellSize : ex.heights.front().cellY;
    this->UpdateProgress(0.05);

    // The sketch's graph in its own pixels, and its heights when it has them.
    tsynth::FeatureGraph graph;
    tsynth::Heightfield heights;
    bool hasHeights = false;
    tsynth::SketchHeights heightKind = tsynth::SketchHeights::None;
    int sw = 0;
    int sh = 0;
    if (auto* image = vtkImageData::SafeDownCast(sketchData))
    {
      vtkDataArray* scalars = image->GetPointData()->GetScalars();
      if (scalars != nullptr && scalars->GetDataType() != VTK_UNSIGNED_CHAR &&
        scalars->GetNumberOfComponents() == 1)
      {
        heights = tsynth::imageToHeightfield(image); // a DEM as the target
        graph = tsynth::extractFeatures(heights, tsynth::FeatureType::Ridge, {}).graph;
        tsynth::appendGraph(
          graph, tsynth::extractFeatures(heights, tsynth::FeatureType::Valley, {}).graph);
        hasHeights = true;
        heightKind = tsynth::SketchHeights::Dem;
        sw = heights.width;
        sh = heights.height;
      }
      else
      {
        const tsynth::ColourImage pixels = tsynth::imageToColourImage(image);
        tsynth::SketchOptions so;
        so.patchSize = this->PatchSize;
        so.controlRadius = 0.5 * this->PatchSize;
        tsynth::SketchFeatures s = tsynth::sketchFeatures(pixels, so);
        for (const auto& w : s.warnings)
        {
          vtkWarningMacro(<< w);
        }
        graph = std::move(s.graph);
        if (s.kind == tsynth::SketchKind::Grey)
        {
          heights = tsynth::greyField(pixels);
          hasHeights = true;
          heightKind = tsynth::SketchHeights::Grey;
        }
        sw = pixels.width;
        sh = pixels.height;
      }
    }
    else if (auto* lines = vtkPolyData::SafeDownCast(sketchData))
    {
      std::string warning;
      const auto polylines = tsynth::polyDataToPolylines(lines, cellX, cellY, 0.0, 0.0, &warning);
      if (!warning.empty())
      {
        vtkWarningMacro(<< warning);
      }
      sw = this->OutputSize[0];
      sh = this->OutputSize[1];
      graph = tsynth::polylineFeatures(polylines, sw, sh, cellX, cellY, 1.0, 0.5 * this->PatchSize);
    }
    else
    {
      throw tsynth::Error("The sketch must be an image or poly-lines.");
    }
    const int w = this->OutputSize[0] > 0 ? this->OutputSize[0] : sw;
    const int h = this->OutputSize[1] > 0 ? this->OutputSize[1] : sh;

    const tsynth::ExemplarStatistics stats =
      tsynth::exemplarStatistics(ex.heightPointers(), ex.graphPointers(), this->PatchSize);
    const tsynth::SynthesisTarget target = tsynth::makeTarget(graph,
      sw,
      sh,
      hasHeights ? &heights : nullptr,
      w,
      h,
      cellX,
      cellY,
      stats,
      this->PatchSize,
      heightKind);
    tsynth::SynthesisOptions o;
    o.patchSize = this->PatchSize;
    o.backend = this->Backend == 1
      ? tsynth::Backend::OpenCL
      : (this->Backend == 2 ? tsynth::Backend::Cpu : tsynth::Backend::Auto);
    o.merge = this->MergeMode == 0 ? tsynth::MergeMode::Cut
      : this->MergeMode == 1       ? tsynth::MergeMode::Poisson
      : this->MergeMode == 2       ? tsynth::MergeMode::Shepard
                                   : tsynth::MergeMode::New;
    o.fill = this->FillOrder == 1 ? tsynth::FillOrder::Concentric : tsynth::FillOrder::BestFirst;
    o.progress = [this](double f, const std::string&) { this->UpdateProgress(0.05 + 0.9 * f); };
    if (inputVector[2]->GetNumberOfInformationObjects() > 0)
    {
      const tsynth::Heightfield labels =
        tsynth::imageToHeightfield(vtkImageData::GetData(inputVector[2], 0));
      tsynth::assignRegions(o, labels, this->RegionMaps, w, h, ex.heights.size());
    }
    const tsynth::SynthesisResult r =
      tsynth::synthesize(target, ex.heightPointers(), ex.graphPointers(), o);
    this->BackendUsed = r.backend;
    for (const auto& warning : r.warnings)
    {
      vtkWarningMacro(<< warning);
    }

    tsynth::heightfieldToImage(r.terrain, output);
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

    const char* intNames[] = { "Order", "Feature", "Exemplar", "Variant", "Column", "Row" };
    const char* realNames[] = { "SourceX", "SourceY", "MatchCost", "SeamCost", "Offset" };
    std::vector<vtkNew<vtkIntArray>> ints(6);
    std::vector<vtkNew<vtkDoubleArray>> reals(5);
    for (std::size_t c = 0; c < 6; ++c)
    {
      ints[c]->SetName(intNames[c]);
    }
    for (std::size_t c = 0; c < 5; ++c)
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
      reals[0]->InsertNextValue(ex.originX[e] + p.sourceX * ex.heights[e].cellX);
      reals[1]->InsertNextValue(ex.originY[e] + p.sourceY * ex.heights[e].cellY);
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
  catch (const tsynth::Error& e)
  {
    vtkErrorMacro(<< e.what());
    return 0;
  }
  return 1;
}

void vtkTerrainSynthesis::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "PatchSize: " << this->PatchSize << "\n";
  os << indent << "Backend: " << this->Backend << "\n";
  os << indent << "MergeMode: " << this->MergeMode << "\n";
  os << indent << "FillOrder: " << this->FillOrder << "\n";
  os << indent << "OutputSize: " << this->OutputSize[0] << " x " << this->OutputSize[1] << "\n";
  os << indent << "CellSize: " << this->CellSize << "\n";
}
