#include "vtkTerrainDistanceSynthesis.h"

#include "DistanceInputs.h"
#include "PipelineRequests.h"
#include "TerrainImageConversion.h"

#include "Core/Error.h"
#include "Core/Memory.h"
#include "Distance/CostScaling.h"
#include "Distance/DistanceSynthesis.h"

#include <vtkDataArray.h>
#include <vtkDataObject.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkTable.h>

#include <cctype>
#include <new>

vtkStandardNewMacro(vtkTerrainDistanceSynthesis);

namespace
{

constexpr int kGeneratorsPort = 0;
constexpr int kProfilesPort = 1;

std::string lowerCase(std::string s)
{
  for (char& c : s)
  {
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return s;
}

// A numeric column by name, whatever its case (ParaView's CSV reader keeps the header's).
vtkDataArray* column(vtkTable* table, const char* name)
{
  for (vtkIdType c = 0; c < table->GetNumberOfColumns(); ++c)
  {
    const char* columnName = table->GetColumnName(c);
    if (columnName != nullptr && lowerCase(columnName) == name)
    {
      return vtkDataArray::SafeDownCast(table->GetColumn(c));
    }
  }
  return nullptr;
}

// Rows of a profile table: Distance, Height and optionally Profile columns.
std::vector<tsynth::MonotoneProfile> profilesFromTable(vtkTable* table)
{
  vtkDataArray* distance = column(table, "distance");
  vtkDataArray* height = column(table, "height");
  vtkDataArray* id = column(table, "profile");
  if (distance == nullptr || height == nullptr)
  {
    throw tsynth::Error("The profile table needs numeric Distance and Height columns.");
  }
  std::vector<tsynth::ProfileRow> rows;
  for (vtkIdType r = 0; r < table->GetNumberOfRows(); ++r)
  {
    tsynth::ProfileRow row;
    row.distance = distance->GetComponent(r, 0);
    row.height = height->GetComponent(r, 0);
    row.profile = id != nullptr ? static_cast<int>(id->GetComponent(r, 0)) : 0;
    row.line = static_cast<int>(r);
    rows.push_back(row);
  }
  return tsynth::profilesFromRows(rows, "the profile table (row numbers from 0)");
}

} // namespace

vtkTerrainDistanceSynthesis::vtkTerrainDistanceSynthesis()
{
  this->SetNumberOfInputPorts(2);
  const tsynth::DistanceOptions d;
  this->CellSize = d.cellSize;
  this->HeightScale = d.heightScale;
  this->Seed = static_cast<vtkIdType>(d.seed);
  this->MeanWeight = d.meanWeight;
  this->Roughness = d.roughness;
  this->Sqrt2Diagonals = d.sqrt2Diagonals;
  this->SeaLevelScale = d.seaLevelScale;
  this->BlendBias = d.blendBias;
  this->SeaLevelEpsilon = d.seaLevelEpsilon;
  this->ApproximateFraction = d.approximateFraction;
  this->MinScaling = d.minScaling;
  this->ProfileScale = d.profileScale;
  this->ProfileBins = d.profileBins;
  this->FbmH = d.fbm.h;
  this->FbmLacunarity = d.fbm.lacunarity;
  this->FbmOctaves = d.fbm.octaves;
  this->FbmDomain = d.fbm.domain;
  this->FbmScale = d.fbm.scale;
  this->FbmRange[0] = d.fbm.low;
  this->FbmRange[1] = d.fbm.high;
  this->RidgeCount = d.ridgeCount;
  this->RidgeFraction = d.ridgeFraction;
  this->RidgeCost = d.ridgeCost == tsynth::RidgeCost::ScaledRise ? SCALED_RISE : SCALED_COST;
  this->ApproximateOnly = d.approximateOnly;
}

int vtkTerrainDistanceSynthesis::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == kProfilesPort)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkTable");
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
    return 1;
  }
  info->Remove(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE());
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

int vtkTerrainDistanceSynthesis::RequestInformation(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkInformation* out = outputVector->GetInformationObject(0);
  vtkInformation* in = inputVector[kGeneratorsPort]->GetInformationObject(0);
  int extent[6] = { 0, this->OutputSize[0] - 1, 0, this->OutputSize[1] - 1, 0, 0 };
  if (in != nullptr && in->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    in->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent); // a stroke map
    extent[4] = 0;
    extent[5] = 0;
  }
  const double origin[3] = { 0.0, 0.0, 0.0 };
  out->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  out->Set(vtkDataObject::SPACING(), this->CellSize, this->CellSize, 1.0);
  out->Set(vtkDataObject::ORIGIN(), origin, 3);
  return 1;
}

int vtkTerrainDistanceSynthesis::RequestUpdateExtent(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector*)
{
  tsynth::requestWholeExtents(inputVector, 1); // the stroke map is needed whole
  return 1;
}

int vtkTerrainDistanceSynthesis::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkDataObject* generators = vtkDataObject::GetData(inputVector[kGeneratorsPort], 0);
  vtkTable* table = vtkTable::GetData(inputVector[kProfilesPort], 0);
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  if (generators == nullptr || output == nullptr)
  {
    tsynth::reportRefusal(this, "Connect a stroke map or generator poly-lines.");
    return 0;
  }
  return tsynth::runFilterRequest(
    this,
    "Out of memory: use a smaller stroke map or OutputSize.",
    [&] { output->Initialize(); },
    [&]
    {
      tsynth::DistanceSources sources;
      if (table != nullptr && !this->ProfileFileName.empty())
      {
        throw tsynth::Error(
          "Give the profiles as a table on input 1 or as ProfileFileName, not both.");
      }
      if (table != nullptr)
      {
        sources.profiles = profilesFromTable(table);
      }
      else if (!this->ProfileFileName.empty())
      {
        sources.profiles = tsynth::readProfiles(this->ProfileFileName);
      }
      sources.assignment = this->ProfileAssignment == BY_FEATURE
        ? tsynth::ProfileAssignment::ByFeature
        : tsynth::ProfileAssignment::ByColour;
      sources.regionProfile = this->RegionProfile < 0 ? tsynth::kNoProfile : this->RegionProfile;
      tsynth::ColourImage strokes;
      std::vector<tsynth::GeneratorLine> lines;
      if (auto* image = vtkImageData::SafeDownCast(generators))
      {
        strokes = tsynth::imageToColourImage(image);
        sources.strokes = &strokes;
      }
      else if (auto* poly = vtkPolyData::SafeDownCast(generators))
      {
        lines = tsynth::polyDataToGeneratorLines(poly, this->CellSize);
        sources.lines = &lines;
        sources.width = this->OutputSize[0];
        sources.height = this->OutputSize[1];
      }
      std::vector<std::string> warnings;
      const tsynth::DistanceInputs inputs = tsynth::assembleDistanceInputs(sources, warnings);
      tsynth::DistanceOptions o;
      o.cellSize = this->CellSize;
      o.heightScale = this->HeightScale;
      o.seed = static_cast<std::uint64_t>(this->Seed);
      o.meanWeight = this->MeanWeight;
      o.roughness = this->Roughness;
      o.sqrt2Diagonals = this->Sqrt2Diagonals;
      o.seaLevelScale = this->SeaLevelScale;
      o.blendBias = this->BlendBias;
      o.seaLevelEpsilon = this->SeaLevelEpsilon;
      o.approximateFraction = this->ApproximateFraction;
      o.minScaling = this->MinScaling;
      o.profileScale = this->ProfileScale;
      o.profileBins = this->ProfileBins;
      o.fbm.h = this->FbmH;
      o.fbm.lacunarity = this->FbmLacunarity;
      o.fbm.octaves = this->FbmOctaves;
      o.fbm.domain = this->FbmDomain;
      o.fbm.scale = this->FbmScale;
      o.fbm.low = this->FbmRange[0];
      o.fbm.high = this->FbmRange[1];
      o.ridgeCount = this->RidgeCount;
      o.ridgeFraction = this->RidgeFraction;
      o.ridgeCost = this->RidgeCost == SCALED_COST ? tsynth::RidgeCost::ScaledCost
                                                   : tsynth::RidgeCost::ScaledRise;
      o.approximateOnly = this->ApproximateOnly;
      o.memoryBudget = this->MemoryBudget * tsynth::kBytesPerGB;
      o.memoryOption = "MemoryBudget";
      o.sizeOption = sources.strokes != nullptr ? "stroke map" : "OutputSize";
      o.progress = [this](double f, const std::string&) { this->UpdateProgress(f); };
      const tsynth::DistanceTerrain t = tsynth::synthesiseByDistance(inputs, o);
      warnings.insert(warnings.end(), t.warnings.begin(), t.warnings.end());
      for (const std::string& w : warnings)
      {
        vtkWarningMacro(<< w);
      }
      tsynth::heightfieldToImage(t.heights, output);
    });
}

void vtkTerrainDistanceSynthesis::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "OutputSize: " << this->OutputSize[0] << " " << this->OutputSize[1] << "\n";
  os << indent << "CellSize: " << this->CellSize << "\n";
  os << indent << "HeightScale: " << this->HeightScale << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "MeanWeight: " << this->MeanWeight << "\n";
  os << indent << "Roughness: " << this->Roughness << "\n";
  os << indent << "Sqrt2Diagonals: " << this->Sqrt2Diagonals << "\n";
  os << indent << "SeaLevelScale: " << this->SeaLevelScale << "\n";
  os << indent << "BlendBias: " << this->BlendBias << "\n";
  os << indent << "SeaLevelEpsilon: " << this->SeaLevelEpsilon << "\n";
  os << indent << "ApproximateFraction: " << this->ApproximateFraction << "\n";
  os << indent << "MinScaling: " << this->MinScaling << "\n";
  os << indent << "ProfileFileName: " << this->ProfileFileName << "\n";
  os << indent << "ProfileScale: " << this->ProfileScale << "\n";
  os << indent << "ProfileBins: " << this->ProfileBins << "\n";
  os << indent << "ProfileAssignment: " << this->ProfileAssignment << "\n";
  os << indent << "RegionProfile: " << this->RegionProfile << "\n";
  os << indent << "Fbm: H " << this->FbmH << ", lacunarity " << this->FbmLacunarity << ", octaves "
     << this->FbmOctaves << ", domain " << this->FbmDomain << ", scale " << this->FbmScale
     << ", range " << this->FbmRange[0] << " " << this->FbmRange[1] << "\n";
  os << indent << "Ridges: " << this->RidgeCount << ", fraction " << this->RidgeFraction
     << ", cost " << this->RidgeCost << "\n";
  os << indent << "ApproximateOnly: " << this->ApproximateOnly << "\n";
  os << indent << "MemoryBudget: " << this->MemoryBudget << " GB\n";
}
