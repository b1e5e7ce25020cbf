#include "vtkTerrainFeatureExtractor.h"
#include "PipelineRequests.h"

#include "FeatureGraphConversion.h"
#include "TerrainImageConversion.h"

#include "Core/Error.h"
#include "Features/Ppa.h"

#include <vtkDataObject.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>

#include <new>

vtkStandardNewMacro(vtkTerrainFeatureExtractor);

static_assert(
  vtkTerrainFeatureExtractor::RIDGES == static_cast<int>(tsynth::FeatureSelection::Ridges) &&
    vtkTerrainFeatureExtractor::VALLEYS == static_cast<int>(tsynth::FeatureSelection::Valleys) &&
    vtkTerrainFeatureExtractor::RIDGES_AND_VALLEYS ==
      static_cast<int>(tsynth::FeatureSelection::Both),
  "the Features property takes tsynth::FeatureSelection's values");

vtkTerrainFeatureExtractor::vtkTerrainFeatureExtractor()
{
  this->SetNumberOfOutputPorts(2);
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, tsynth::kElevationArray);
  // The defaults of the options table (tsynth::ppaOptionRows).
  const auto initial = [](const char* property)
  { return tsynth::optionRow(tsynth::ppaOptionRows(), property).defaultValue; };
  this->Features = static_cast<int>(initial("Features"));
  this->HalfProfileLength = static_cast<int>(initial("HalfProfileLength"));
  this->MinimumDip = initial("MinimumDip");
  this->RelativeDip = initial("RelativeDip");
  this->Significance = initial("Significance");
  this->SignificanceNoise = initial("SignificanceNoise");
  this->SignificanceRadius = static_cast<int>(initial("SignificanceRadius"));
  this->PresmoothSigma = initial("PresmoothSigma");
  this->EndReductions = static_cast<int>(initial("EndReductions"));
  this->MinimumBranchLength = static_cast<int>(initial("MinimumBranchLength"));
  this->MinimumTreeSize = static_cast<int>(initial("MinimumTreeSize"));
  this->SmoothingPasses = static_cast<int>(initial("SmoothingPasses"));
  this->ControlRadius = initial("ControlRadius");
}

int vtkTerrainFeatureExtractor::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

int vtkTerrainFeatureExtractor::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0], 0);
  vtkPolyData* tree = vtkPolyData::GetData(outputVector, 0);
  vtkPolyData* controls = vtkPolyData::GetData(outputVector, 1);
  return tsynth::runFilterRequest(
    this,
    "Out of memory: give a smaller input.",
    [&]
    {
      tree->Initialize();
      controls->Initialize(); // aborted: empty outputs
    },
    [&]
    {
      const tsynth::Heightfield hf =
        tsynth::imageToHeightfield(input, this->GetInputArrayToProcess(0, inputVector));
      tsynth::requireValidHeights(hf);
      tsynth::PpaOptions o;
      o.halfProfileLength = this->HalfProfileLength;
      o.minDip = this->MinimumDip;
      o.relativeDip = this->RelativeDip;
      o.significance = this->Significance;
      o.significanceNoise = this->SignificanceNoise;
      o.significanceRadius = this->SignificanceRadius;
      o.presmoothSigma = this->PresmoothSigma;
      o.endReductions = this->EndReductions;
      o.minBranchLength = this->MinimumBranchLength;
      o.minTreeSize = this->MinimumTreeSize;
      o.smoothingPasses = this->SmoothingPasses;
      o.controlRadius = this->ControlRadius;

      const auto selection = tsynth::choiceOf<tsynth::FeatureSelection>(
        tsynth::optionRow(tsynth::ppaOptionRows(), "Features").choices, this->Features, "Features");
      tsynth::FeatureExtraction lines = tsynth::extractSelectedFeatures(
        hf, selection, o, [this](double f, const std::string&) { this->UpdateProgress(0.9 * f); });
      for (const auto& w : lines.warnings)
      {
        vtkWarningMacro(<< w);
      }
      tsynth::FeatureGraph& graph = lines.graph;
      this->UpdateProgress(0.9);
      // Points sit on the input's grid: its origin plus the extent's offset.
      double ox = 0.0;
      double oy = 0.0;
      tsynth::gridOrigin(input, ox, oy);
      tsynth::featureGraphToPolyData(graph, tree, ox, oy);
      tsynth::controlPointsToPolyData(graph, controls, ox, oy);
    });
}

void vtkTerrainFeatureExtractor::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Features: " << this->Features << "\n";
  os << indent << "HalfProfileLength: " << this->HalfProfileLength << "\n";
  os << indent << "MinimumDip: " << this->MinimumDip << "\n";
  os << indent << "RelativeDip: " << this->RelativeDip << "\n";
  os << indent << "Significance: " << this->Significance << "\n";
  os << indent << "SignificanceNoise: " << this->SignificanceNoise << "\n";
  os << indent << "SignificanceRadius: " << this->SignificanceRadius << "\n";
  os << indent << "PresmoothSigma: " << this->PresmoothSigma << "\n";
  os << indent << "EndReductions: " << this->EndReductions << "\n";
  os << indent << "MinimumBranchLength: " << this->MinimumBranchLength << "\n";
  os << indent << "MinimumTreeSize: " << this->MinimumTreeSize << "\n";
  os << indent << "SmoothingPasses: " << this->SmoothingPasses << "\n";
  os << indent << "ControlRadius: " << this->ControlRadius << "\n";
}
