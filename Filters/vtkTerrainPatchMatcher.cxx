#include "vtkTerrainPatchMatcher.h"

#include "CandidatePoolTable.h"
#include "MatchingInputs.h"
#include "PipelineRequests.h"
#include "PropertyEnums.h"
#include "TerrainImageConversion.h"

#include "Core/Error.h"
#include "Matching/PatchMatcher.h"
#include "Matching/SiteMatch.h"

#include <vtkDataObject.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkTable.h>

#include <cmath>
#include <limits>
#include <memory>

vtkStandardNewMacro(vtkTerrainPatchMatcher);

namespace
{
constexpr int kExemplarHeights = 1; // SetInputArrayToProcess index of the exemplars' heights
constexpr int kPoolPort = 3;        // the Candidate Builder's table

// Per target cell, 1 where the chosen known-cells array is non-zero (every
// cell without one).
std::vector<std::uint8_t> knownCells(vtkImageData* target, const char* arrayName, std::size_t cells)
{
  std::vector<std::uint8_t> known(cells, 1);
  if (vtkDataArray* k =
        tsynth::chosenPointArray(target, arrayName, vtkTerrainPatchMatcher::kDefaultKnownArray))
  {
    for (std::size_t c = 0; c < known.size(); ++c)
    {
      known[c] = k->GetComponent(static_cast<vtkIdType>(c), 0) != 0.0 ? 1 : 0;
    }
  }
  return known;
}

// The ranked matches, one row each (their place in world coordinates and in
// their exemplar's cells), and as field data the window they fill.
void writeMatchTable(vtkTable* table,
  const tsynth::SiteMatchResult& match,
  const tsynth::PatchMatcher& matcher,
  const tsynth::ExemplarInputs& in,
  int patchSize)
{
  const std::vector<tsynth::PatchCandidate>& found = match.candidates;
  vtkNew<vtkIntArray> rank, exemplar, variantColumn, feature, featureType;
  vtkNew<vtkDoubleArray> x, y, cellX, cellY;
  vtkNew<vtkFloatArray> cost;
  rank->SetName("Rank");
  exemplar->SetName("Exemplar");
  variantColumn->SetName("Variant");
  feature->SetName("Feature");
  featureType->SetName("FeatureType");
  x->SetName("X");
  y->SetName("Y");
  cellX->SetName("CellX");
  cellY->SetName("CellY");
  cost->SetName("Cost");
  for (std::size_t r = 0; r < found.size(); ++r)
  {
    const tsynth::PatchCandidate& m = found[r];
    const auto e = static_cast<std::size_t>(m.exemplar);
    rank->InsertNextValue(static_cast<int>(r));
    exemplar->InsertNextValue(m.exemplar);
    variantColumn->InsertNextValue(m.variant);
    feature->InsertNextValue(m.feature ? 1 : 0);
    // The ridge or valley a feature match brings (+1, -1; 0 for a fill match).
    const bool inPool = m.feature && m.poolIndex < matcher.pool().size();
    featureType->InsertNextValue(inPool ? matcher.pool().type[m.poolIndex] : 0);
    x->InsertNextValue(in.originX[e] + m.centreX * in.heights[e].cellX);
    y->InsertNextValue(in.originY[e] + m.centreY * in.heights[e].cellY);
    cellX->InsertNextValue(m.centreX);
    cellY->InsertNextValue(m.centreY);
    cost->InsertNextValue(m.cost);
  }
  table->AddColumn(rank);
  table->AddColumn(exemplar);
  table->AddColumn(variantColumn);
  table->AddColumn(x);
  table->AddColumn(y);
  table->AddColumn(cost);
  table->AddColumn(feature);
  table->AddColumn(featureType);
  table->AddColumn(cellX);
  table->AddColumn(cellY);
  // Where the patch goes: the lower-left target cell of the window matched.
  vtkNew<vtkIntArray> window;
  window->SetName("PatchCell");
  window->InsertNextValue(tsynth::windowCorner(match.centreX, patchSize));
  window->InsertNextValue(tsynth::windowCorner(match.centreY, patchSize));
  table->GetFieldData()->AddArray(window);
  vtkNew<vtkIntArray> patch;
  patch->SetName("PatchSize");
  patch->InsertNextValue(patchSize);
  table->GetFieldData()->AddArray(patch);
}

// The cost map over the first exemplar: the lowest cost of a candidate
// centred on each cell.
void writeCostMap(vtkImageData* map,
  const tsynth::SiteMatchResult& match,
  const tsynth::ExemplarInputs& in)
{
  const tsynth::Heightfield& first = in.heights.front();
  map->SetExtent(0, first.width - 1, 0, first.height - 1, 0, 0);
  map->SetSpacing(first.cellX, first.cellY, 1.0);
  map->SetOrigin(in.originX.front(), in.originY.front(), 0.0);
  vtkNew<vtkFloatArray> costMap;
  costMap->SetName("MatchCost");
  costMap->SetNumberOfTuples(static_cast<vtkIdType>(match.costMap.size()));
  std::copy(match.costMap.begin(), match.costMap.end(), costMap->GetPointer(0));
  map->GetPointData()->SetScalars(costMap);
}
} // namespace

vtkTerrainPatchMatcher::vtkTerrainPatchMatcher()
{
  this->SetNumberOfInputPorts(4);
  this->SetNumberOfOutputPorts(2);
  this->SetInputArrayToProcess(
    kExemplarHeights, 1, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, tsynth::kElevationArray);
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, tsynth::kElevationArray);
  this->SetKnownArray(kDefaultKnownArray);
  // The defaults of the options table (tsynth::matcherOptionRows): the synthesis' own.
  const auto initial = [](const char* property)
  { return tsynth::optionRow(tsynth::matcherOptionRows(), property).defaultValue; };
  this->Backend = static_cast<int>(initial("Backend"));
  this->PatchSize = static_cast<int>(initial("PatchSize"));
  this->K = static_cast<int>(initial("K"));
  this->FeatureWeight = initial("FeatureWeight");
  this->AngleWeight = initial("AngleWeight");
  this->NoiseWeight = initial("NoiseWeight");
  this->OverlapWeight = initial("OverlapWeight");
  this->VerticalOffset = initial("VerticalOffset") != 0.0;
}

vtkTerrainPatchMatcher::~vtkTerrainPatchMatcher()
{
  this->SetKnownArray(nullptr);
}

int vtkTerrainPatchMatcher::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == 0)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
    return 1;
  }
  if (port == kPoolPort)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkTable");
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
    return 1;
  }
  info->Set(vtkAlgorithm::INPUT_IS_REPEATABLE(), 1);
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), port == 1 ? "vtkImageData" : "vtkPolyData");
  if (port == 2)
  {
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  }
  return 1;
}

int vtkTerrainPatchMatcher::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkTable" : "vtkImageData");
  return 1;
}

vtkTable* vtkTerrainPatchMatcher::GetMatches()
{
  return vtkTable::SafeDownCast(this->GetOutputDataObject(0));
}

vtkImageData* vtkTerrainPatchMatcher::GetCostMap()
{
  return vtkImageData::SafeDownCast(this->GetOutputDataObject(1));
}

int vtkTerrainPatchMatcher::RequestInformation(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  // The cost map lies on the first exemplar's grid.
  tsynth::copyGrid(inputVector[1]->GetInformationObject(0), outputVector->GetInformationObject(1));
  return 1;
}

int vtkTerrainPatchMatcher::RequestUpdateExtent(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector*)
{
  // Every input is needed whole, whatever their sizes.
  tsynth::requestWholeExtents(inputVector, this->GetNumberOfInputPorts());
  return 1;
}

int vtkTerrainPatchMatcher::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkImageData* targetImage = vtkImageData::GetData(inputVector[0], 0);
  vtkTable* table = vtkTable::GetData(outputVector, 0);
  vtkImageData* map = vtkImageData::GetData(outputVector, 1);
  return tsynth::runFilterRequest(
    this,
    "Out of memory: give a smaller input.",
    [&]
    {
      table->Initialize();
      map->Initialize();
    },
    [&]
    {
      tsynth::checkPatchSizeInRange(this->PatchSize, "Patch Size");
      const tsynth::Heightfield target =
        tsynth::imageToHeightfield(targetImage, this->GetInputArrayToProcess(0, inputVector));
      const std::vector<std::uint8_t> known =
        knownCells(targetImage, this->KnownArray, target.size());
      vtkTable* poolTable = vtkTable::GetData(inputVector[kPoolPort], 0);
      const tsynth::ExemplarHeights heights = tsynth::exemplarHeightsNamed(
        this->GetInputArrayInformation(kExemplarHeights), inputVector[1]);
      // A given pool holds what the feature trees would be read for.
      const tsynth::ExemplarInputs in = poolTable != nullptr
        ? tsynth::gatherExemplarImages(inputVector[1], heights)
        : tsynth::gatherExemplars(inputVector[1], inputVector[2], heights);
      this->UpdateProgress(0.2);
      tsynth::MatcherOptions o;
      o.patchSize = this->PatchSize;
      o.k = static_cast<std::size_t>(this->K);
      o.backend = tsynth::backendFromProperty(this->Backend);
      o.weights.feature = this->FeatureWeight;
      o.weights.angle = this->AngleWeight;
      o.weights.noise = this->NoiseWeight;
      o.weights.overlap = this->OverlapWeight;
      o.weights.verticalOffset = this->VerticalOffset;
      if (poolTable != nullptr)
      {
        auto pool = std::make_shared<const tsynth::CandidatePool>(tsynth::poolFromTable(poolTable));
        tsynth::checkGivenPool(*pool, in.heightPointers(), this->PatchSize);
        o.pool = std::move(pool);
      }
      tsynth::PatchMatcher matcher(in.heightPointers(), in.graphPointers(), o);
      this->BackendUsed = matcher.backendName();
      this->UpdateProgress(0.6);

      double tx = 0.0;
      double ty = 0.0;
      tsynth::gridOrigin(targetImage, tx, ty);
      const tsynth::SiteMatchResult match = tsynth::matchAtSite(matcher,
        target,
        known,
        (this->Site[0] - tx) / target.cellX,
        (this->Site[1] - ty) / target.cellY,
        this->Mode == FEATURE,
        this->PatchSize);
      for (const auto& w : match.warnings)
      {
        vtkWarningMacro(<< w);
      }
      writeMatchTable(table, match, matcher, in, this->PatchSize);
      writeCostMap(map, match, in);
    });
}

void vtkTerrainPatchMatcher::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Mode: " << this->Mode << "\n";
  os << indent << "Backend: " << this->Backend << "\n";
  os << indent << "PatchSize: " << this->PatchSize << "\n";
  os << indent << "K: " << this->K << "\n";
  os << indent << "Site: " << this->Site[0] << ", " << this->Site[1] << "\n";
  os << indent << "Weights: " << this->FeatureWeight << ", " << this->AngleWeight << ", "
     << this->NoiseWeight << ", " << this->OverlapWeight << "\n";
  os << indent << "VerticalOffset: " << this->VerticalOffset << "\n";
  os << indent << "KnownArray: " << (this->KnownArray ? this->KnownArray : "(none)") << "\n";
}
