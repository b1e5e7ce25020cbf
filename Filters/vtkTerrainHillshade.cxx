#include "vtkTerrainHillshade.h"

#include "PipelineRequests.h"
#include "TerrainImageConversion.h"

#include "Analysis/Hillshade.h"
#include "Core/Error.h"

#include <vtkDataArray.h>
#include <vtkDataObject.h>
#include <vtkDataSetAttributes.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>

#include <new>

vtkStandardNewMacro(vtkTerrainHillshade);

vtkTerrainHillshade::vtkTerrainHillshade()
{
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, tsynth::kElevationArray);
  // The defaults of the options table (tsynth::hillshadeOptionRows).
  const auto initial = [](const char* property)
  { return tsynth::optionRow(tsynth::hillshadeOptionRows(), property).defaultValue; };
  this->Altitude = initial("Altitude");
  this->Azimuth = initial("Azimuth");
  this->Multidirectional = initial("Multidirectional") != 0.0;
  this->ZFactor = initial("ZFactor");
}

int vtkTerrainHillshade::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0], 0);
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  if (input == nullptr || output == nullptr)
  {
    tsynth::reportRefusal(this, "Hillshade needs an image input.");
    return 0;
  }
  vtkDataArray* heights = this->GetInputArrayToProcess(0, inputVector);
  return tsynth::runFilterRequest(
    this,
    "Out of memory: give a smaller input.",
    [&] { output->Initialize(); },
    [&]
    {
      const tsynth::Heightfield hf = tsynth::imageToHeightfield(input, heights);
      tsynth::requireValidHeights(hf);
      this->UpdateProgress(0.1);
      tsynth::HillshadeOptions options;
      options.altitudeDeg = this->Altitude;
      options.azimuthDeg = this->Azimuth;
      options.multidirectional = this->Multidirectional;
      options.zFactor = this->ZFactor;
      const tsynth::ShadedRelief relief = tsynth::computeHillshade(hf, options);
      this->UpdateProgress(0.9);

      tsynth::copyAsPointGrid(input, hf, output);
      tsynth::addPointArray(output, "Slope", relief.slopeDeg.data());
      tsynth::addPointArray(output, "Hillshade", relief.shade.data());
      output->GetPointData()->SetActiveScalars("Hillshade");
    });
}

void vtkTerrainHillshade::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Altitude: " << this->Altitude << "\n";
  os << indent << "Azimuth: " << this->Azimuth << "\n";
  os << indent << "Multidirectional: " << this->Multidirectional << "\n";
  os << indent << "ZFactor: " << this->ZFactor << "\n";
}
