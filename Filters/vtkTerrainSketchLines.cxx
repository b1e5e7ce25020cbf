#include "vtkTerrainSketchLines.h"

#include "PipelineRequests.h"

#include "Core/Error.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkFloatArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <cmath>
#include <limits>

vtkStandardNewMacro(vtkTerrainSketchLines);

// The property's values are the kernel's (the wrappers cannot parse a cast in the header).
static_assert(vtkTerrainSketchLines::NO_ELEVATION == static_cast<int>(tsynth::LineElevation::None));
static_assert(
  vtkTerrainSketchLines::ELEVATION_FROM_Z == static_cast<int>(tsynth::LineElevation::FromZ));
static_assert(
  vtkTerrainSketchLines::CONSTANT_ELEVATION == static_cast<int>(tsynth::LineElevation::Constant));
static_assert(vtkTerrainSketchLines::RIDGE == static_cast<int>(tsynth::FeatureType::Ridge));
static_assert(vtkTerrainSketchLines::VALLEY == static_cast<int>(tsynth::FeatureType::Valley));

vtkTerrainSketchLines::vtkTerrainSketchLines()
{
  const auto byDefault = [](const char* property)
  { return tsynth::optionRow(tsynth::sketchLineOptionRows(), property).defaultValue; };
  this->FeatureType = static_cast<int>(byDefault("FeatureType"));
  this->ElevationMode = static_cast<int>(byDefault("ElevationMode"));
  this->Elevation = byDefault("Elevation");
}

int vtkTerrainSketchLines::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  if (input == nullptr || output == nullptr)
  {
    tsynth::reportRefusal(this, "Sketch Lines needs poly-lines on its input.");
    return 0;
  }
  try
  {
    const auto& rows = tsynth::sketchLineOptionRows();
    tsynth::optionRow(rows, "FeatureType").choices.wordOf(this->FeatureType, "Feature type");
    tsynth::optionRow(rows, "ElevationMode").choices.wordOf(this->ElevationMode, "Elevation mode");
  }
  catch (const tsynth::Error& e)
  {
    tsynth::reportRefusal(this, e.what());
    return 0;
  }
  if (input->GetNumberOfLines() == 0)
  {
    tsynth::reportRefusal(
      this, "The input has no lines: draw a Poly Line or Spline source and apply this to it.");
    return 0;
  }
  // Lines only: points and polygons of the input are not a sketch.
  output->SetPoints(input->GetPoints());
  output->SetLines(input->GetLines());
  vtkNew<vtkIntArray> type;
  type->SetName("FeatureType");
  type->SetNumberOfTuples(input->GetNumberOfLines());
  type->FillValue(this->FeatureType);
  // The active cell scalars, so ParaView colours the lines by it when they are shown: with the
  // plugin's FeatureType colour map, ridges red and valleys blue.
  output->GetCellData()->SetScalars(type);

  const vtkIdType n = input->GetNumberOfPoints();
  vtkNew<vtkFloatArray> elevation;
  elevation->SetName("Elevation");
  elevation->SetNumberOfTuples(n);
  elevation->Fill(std::numeric_limits<float>::quiet_NaN());
  if (this->ElevationMode == CONSTANT_ELEVATION)
  {
    elevation->Fill(static_cast<float>(this->Elevation));
  }
  else if (this->ElevationMode == ELEVATION_FROM_Z)
  {
    // Heights from z, and the lines laid flat on the raster plane.
    vtkNew<vtkPoints> flat;
    flat->SetNumberOfPoints(n);
    for (vtkIdType k = 0; k < n; ++k)
    {
      double p[3];
      input->GetPoint(k, p);
      elevation->SetValue(k, static_cast<float>(p[2]));
      flat->SetPoint(k, p[0], p[1], 0.0);
    }
    output->SetPoints(flat);
  }
  output->GetPointData()->AddArray(elevation);
  return 1;
}

void vtkTerrainSketchLines::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FeatureType: " << this->FeatureType
     << (this->FeatureType == RIDGE       ? " (ridge)"
            : this->FeatureType == VALLEY ? " (valley)"
                                          : "")
     << "\n";
  os << indent << "ElevationMode: " << this->ElevationMode << "\n";
  os << indent << "Elevation: " << this->Elevation << "\n";
}
