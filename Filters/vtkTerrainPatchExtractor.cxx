#include "vtkTerrainPatchExtractor.h"

#include "MatchingInputs.h"
#include "PipelineRequests.h"
#include "TerrainImageConversion.h"

#include "Core/Error.h"
#include "Features/ChainPointGrid.h"
#include "Features/Ppa.h"
#include "Matching/LandformTerm.h"
#include "Synthesis/ExemplarCache.h"
#include "Synthesis/PatchExtraction.h"

#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkTable.h>
#include <vtkUnsignedCharArray.h>

#include <cmath>
#include <string>

vtkStandardNewMacro(vtkTerrainPatchExtractor);

namespace
{

constexpr int kTerrainPort = 0;
constexpr int kExemplarPort = 1;
constexpr int kMatchesPort = 2;
// Cell sizes closer than this share of each other are the same grid.
constexpr double kSameCellSize = 1e-6;

// A value of the matches table: column `name`, row `row`, or its field data
// array `name`, component `component`. Throws naming what is missing.
double matchValue(vtkTable* matches, const char* name, vtkIdType row)
{
  vtkAbstractArray* column = matches->GetColumnByName(name);
  if (column == nullptr || vtkDataArray::SafeDownCast(column) == nullptr)
  {
    throw tsynth::Error(std::string("The matches have no column ") + name +
      ": connect the Terrain Patch Matcher's first output.");
  }
  return vtkDataArray::SafeDownCast(column)->GetComponent(row, 0);
}

int fieldValue(vtkTable* matches, const char* name, int component)
{
  auto* a = vtkDataArray::SafeDownCast(matches->GetFieldData()->GetAbstractArray(name));
  if (a == nullptr || a->GetNumberOfValues() <= component)
  {
    throw tsynth::Error(std::string("The matches have no field data ") + name +
      ": connect the Terrain Patch Matcher's first output.");
  }
  return static_cast<int>(a->GetComponent(component, 0));
}

// The match of the given row as the kernels take it.
tsynth::PatchCandidate matchOfRow(vtkTable* matches, vtkIdType row, std::size_t exemplars)
{
  tsynth::PatchCandidate c;
  c.exemplar = static_cast<int>(matchValue(matches, "Exemplar", row));
  c.variant = static_cast<int>(matchValue(matches, "Variant", row));
  c.centreX = matchValue(matches, "CellX", row);
  c.centreY = matchValue(matches, "CellY", row);
  c.feature = matchValue(matches, "Feature", row) != 0.0;
  if (c.exemplar < 0 || static_cast<std::size_t>(c.exemplar) >= exemplars)
  {
    throw tsynth::Error("The match names exemplar " + std::to_string(c.exemplar) + ", but " +
      std::to_string(exemplars) +
      " are connected: connect the exemplars the matcher was given, in its order.");
  }
  if (c.variant < 0 || c.variant >= tsynth::kVariantCount)
  {
    throw tsynth::Error("The match names variant " + std::to_string(c.variant) +
      ", not one of the 10: connect the Terrain Patch Matcher's first output.");
  }
  return c;
}

// The ridge (+1) or valley (-1) a feature match brings, from the matches'
// FeatureType column; 0 for a fill match or a table without the column.
int featureTypeOf(vtkTable* matches, vtkIdType row)
{
  auto* column = vtkDataArray::SafeDownCast(matches->GetColumnByName("FeatureType"));
  return column != nullptr ? static_cast<int>(column->GetComponent(row, 0)) : 0;
}

// The cells a feature match owns whatever the seam, as the synthesis gives
// them: the disc and the drawn lines near its centre (featureCore), and a strip
// along its own ridge or valley (`type`), read from its exemplar with the
// synthesis' PPA settings.
std::vector<std::uint8_t> featureMatchCore(const tsynth::Heightfield& exemplar,
  const tsynth::PatchCandidate& match,
  int type,
  const std::vector<std::uint8_t>& line,
  const tsynth::Heightfield& terrain,
  int x0,
  int y0,
  int patchSize)
{
  std::vector<std::uint8_t> core =
    tsynth::featureCore(line, terrain.width, terrain.height, x0, y0, patchSize);
  if (type != 0)
  {
    const tsynth::ChainPointGrid lines(
      tsynth::ridgesAndValleys(exemplar, tsynth::exemplarPpaOptions()),
      tsynth::kLineOffsetReachInPatches * patchSize);
    const tsynth::FeatureType t =
      type > 0 ? tsynth::FeatureType::Ridge : tsynth::FeatureType::Valley;
    tsynth::addOwnLineStrip(core, tsynth::ownLineOffsets(lines, t, match, patchSize), patchSize);
  }
  return core;
}

// What the synthesis fits a patch's shift to besides the filled cells: its
// target through the landform term's low-pass and the confidence in it, from
// the terrain's "Target" and "TargetConfidence" point arrays (the Terrain
// Synthesis filter's construction output has both); none without Target.
struct OffsetTarget
{
  tsynth::Heightfield low;
  std::vector<float> confidence;
};

OffsetTarget offsetTargetOf(vtkImageData* terrain, int patchSize)
{
  OffsetTarget t;
  vtkDataArray* target = terrain->GetPointData()->GetArray("Target");
  if (target == nullptr)
  {
    return t;
  }
  t.low = tsynth::landformImage(tsynth::imageToHeightfield(terrain, target), patchSize);
  t.confidence.assign(t.low.size(), 1.0f);
  if (vtkDataArray* weight = terrain->GetPointData()->GetArray("TargetConfidence"))
  {
    for (std::size_t k = 0; k < t.confidence.size(); ++k)
    {
      t.confidence[k] = static_cast<float>(weight->GetComponent(static_cast<vtkIdType>(k), 0));
    }
  }
  return t;
}

void addField(vtkImageData* image, const char* name, double value)
{
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->InsertNextValue(value);
  image->GetFieldData()->AddArray(a);
}

} // namespace

vtkTerrainPatchExtractor::vtkTerrainPatchExtractor()
{
  this->SetNumberOfInputPorts(3);
  // The defaults of the options table (tsynth::patchExtractionOptionRows).
  const auto byDefault = [](const char* property)
  { return tsynth::optionRow(tsynth::patchExtractionOptionRows(), property).defaultValue; };
  this->Rank = static_cast<int>(byDefault("Rank"));
  this->VerticalOffset = byDefault("VerticalOffset") != 0.0;
  this->SetInputArrayToProcess(
    0, kTerrainPort, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, tsynth::kElevationArray);
}

int vtkTerrainPatchExtractor::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(
    vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), port == kMatchesPort ? "vtkTable" : "vtkImageData");
  if (port == kExemplarPort)
  {
    info->Set(vtkAlgorithm::INPUT_IS_REPEATABLE(), 1);
  }
  return 1;
}

int vtkTerrainPatchExtractor::RequestInformation(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  // The patch lies on the terrain's cells; its size and place come with the
  // matches (their PatchSize and PatchCell), known when they have run.
  vtkInformation* terrain = inputVector[kTerrainPort]->GetInformationObject(0);
  vtkInformation* out = outputVector->GetInformationObject(0);
  if (terrain->Has(vtkDataObject::SPACING()))
  {
    out->Set(vtkDataObject::SPACING(), terrain->Get(vtkDataObject::SPACING()), 3);
  }
  return 1;
}

int vtkTerrainPatchExtractor::RequestUpdateExtent(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector*)
{
  tsynth::requestWholeExtents(inputVector, this->GetNumberOfInputPorts());
  return 1;
}

int vtkTerrainPatchExtractor::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkImageData* terrainImage = vtkImageData::GetData(inputVector[kTerrainPort], 0);
  vtkTable* matches = vtkTable::GetData(inputVector[kMatchesPort], 0);
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  return tsynth::runFilterRequest(
    this,
    "Out of memory: give a smaller input.",
    [&] { output->Initialize(); },
    [&]
    {
      const tsynth::Heightfield terrain =
        tsynth::imageToHeightfield(terrainImage, this->GetInputArrayToProcess(0, inputVector));
      const tsynth::ExemplarInputs in = tsynth::gatherExemplarImages(inputVector[kExemplarPort]);
      if (this->Rank >= matches->GetNumberOfRows())
      {
        throw tsynth::Error("Rank " + std::to_string(this->Rank) + " asks for a match past the " +
          std::to_string(matches->GetNumberOfRows()) + " the matcher found: give a smaller rank.");
      }
      const tsynth::PatchCandidate match = matchOfRow(matches, this->Rank, in.heights.size());
      const tsynth::Heightfield& exemplar = in.heights[static_cast<std::size_t>(match.exemplar)];
      if (std::abs(exemplar.cellX - terrain.cellX) > kSameCellSize * terrain.cellX ||
        std::abs(exemplar.cellY - terrain.cellY) > kSameCellSize * terrain.cellY)
      {
        throw tsynth::Error("Exemplar " + std::to_string(match.exemplar) +
          " has other cells than the terrain: resample it to the terrain's cell size.");
      }
      const int patchSize = fieldValue(matches, "PatchSize", 0);
      const int x0 = fieldValue(matches, "PatchCell", 0);
      const int y0 = fieldValue(matches, "PatchCell", 1);
      tsynth::checkPatchSizeInRange(patchSize, "The matches' PatchSize");
      this->UpdateProgress(0.3);

      tsynth::Heightfield patch = tsynth::extractPatch(exemplar, match, patchSize);
      patch.cellX = terrain.cellX;
      patch.cellY = terrain.cellY;
      const std::vector<std::uint8_t> filled = tsynth::filledCells(terrainImage, terrain);
      const std::vector<std::uint8_t> line = tsynth::pointFlags(terrainImage, "Line", 0);
      if (!match.feature)
      {
        // As the synthesis tries a fill patch: the lines laid stay as they are.
        tsynth::protectKeptCells(patch,
          x0,
          y0,
          { line,
            tsynth::pointFlags(terrainImage, "Frozen", 0),
            filled,
            terrain.width,
            terrain.height });
      }
      const OffsetTarget target = offsetTargetOf(terrainImage, patchSize);
      const float offset = this->VerticalOffset
        ? tsynth::fitPatchOffset(patch, x0, y0, { terrain, filled, target.low, target.confidence })
        : 0.0f;
      for (float& z : patch.z)
      {
        z += offset;
      }
      const std::vector<std::uint8_t> core = match.feature
        ? featureMatchCore(
            exemplar, match, featureTypeOf(matches, this->Rank), line, terrain, x0, y0, patchSize)
        : std::vector<std::uint8_t>(patch.size(), 0);
      this->UpdateProgress(0.8);

      tsynth::heightfieldToImage(patch, output);
      double tx = 0.0;
      double ty = 0.0;
      tsynth::gridOrigin(terrainImage, tx, ty);
      output->SetOrigin(tx + x0 * terrain.cellX, ty + y0 * terrain.cellY, 0.0);
      vtkNew<vtkUnsignedCharArray> coreArray;
      coreArray->SetName("Core");
      coreArray->SetNumberOfTuples(static_cast<vtkIdType>(core.size()));
      std::copy(core.begin(), core.end(), coreArray->GetPointer(0));
      output->GetPointData()->AddArray(coreArray);
      addField(output, "VerticalOffset", offset);
      addField(output, "Exemplar", match.exemplar);
      addField(output, "Variant", match.variant);
      addField(output, "Rank", this->Rank);
    });
}

void vtkTerrainPatchExtractor::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Rank: " << this->Rank << "\n";
  os << indent << "VerticalOffset: " << this->VerticalOffset << "\n";
}
