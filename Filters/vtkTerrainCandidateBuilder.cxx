#include "vtkTerrainCandidateBuilder.h"
#include "PipelineRequests.h"

#include "MatchingInputs.h"
#include "TerrainImageConversion.h"

#include "Core/Constants.h"
#include "Core/Error.h"
#include "Matching/CandidatePool.h"

#include <vtkDataObject.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkTable.h>

#include <new>

#include <cmath>

vtkStandardNewMacro(vtkTerrainCandidateBuilder);

namespace
{
constexpr int kExemplarHeights = 0; // SetInputArrayToProcess index of the exemplars' heights
} // namespace

vtkTerrainCandidateBuilder::vtkTerrainCandidateBuilder()
{
  this->SetNumberOfInputPorts(2);
  this->SetInputArrayToProcess(
    kExemplarHeights, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, tsynth::kElevationArray);
}

int vtkTerrainCandidateBuilder::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_IS_REPEATABLE(), 1);
  if (port == 0)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
    return 1;
  }
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

int vtkTerrainCandidateBuilder::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkTable* table = vtkTable::GetData(outputVector, 0);
  return tsynth::runFilterRequest(
    this,
    "Out of memory: give a smaller input.",
    [&]
    {
      table->Initialize(); // aborted: empty outputs
    },
    [&]
    {
      tsynth::checkPatchSizeInRange(this->PatchSize, "Patch Size");
      const tsynth::ExemplarInputs in = tsynth::gatherExemplars(inputVector[0],
        inputVector[1],
        tsynth::exemplarHeightsNamed(
          this->GetInputArrayInformation(kExemplarHeights), inputVector[0]));
      this->UpdateProgress(0.3);
      tsynth::PoolOptions o;
      o.patchSize = this->PatchSize;
      const tsynth::CandidatePool pool =
        tsynth::buildCandidatePool(in.heightPointers(), in.graphPointers(), o);
      for (const auto& w : pool.warnings)
      {
        vtkWarningMacro(<< w);
      }
      this->UpdateProgress(0.9);
      auto intColumn = [&](const char* name, const std::vector<int>& values)
      {
        vtkNew<vtkIntArray> a;
        a->SetName(name);
        a->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
        std::copy(values.begin(), values.end(), a->GetPointer(0));
        table->AddColumn(a);
      };
      intColumn("Exemplar", pool.exemplar);
      intColumn("Site", pool.site);
      intColumn("Variant", pool.variant);
      intColumn("Kind", pool.kind);
      intColumn("FeatureType", pool.type);
      intColumn("Arms", pool.arms);
      const vtkIdType n = static_cast<vtkIdType>(pool.size());
      vtkNew<vtkDoubleArray> x;
      vtkNew<vtkDoubleArray> y;
      x->SetName("X");
      y->SetName("Y");
      x->SetNumberOfTuples(n);
      y->SetNumberOfTuples(n);
      for (vtkIdType c = 0; c < n; ++c)
      {
        const auto e = static_cast<std::size_t>(pool.exemplar[static_cast<std::size_t>(c)]);
        x->SetValue(
          c, in.originX[e] + pool.centreX[static_cast<std::size_t>(c)] * in.heights[e].cellX);
        y->SetValue(
          c, in.originY[e] + pool.centreY[static_cast<std::size_t>(c)] * in.heights[e].cellY);
      }
      table->AddColumn(x);
      table->AddColumn(y);
      for (int a = 0; a < tsynth::kMaxArms; ++a)
      {
        vtkNew<vtkFloatArray> angle;
        angle->SetName(("Angle" + std::to_string(a)).c_str());
        angle->SetNumberOfTuples(n);
        for (vtkIdType c = 0; c < n; ++c)
        {
          const bool used = a < pool.arms[static_cast<std::size_t>(c)];
          angle->SetValue(c,
            used ? static_cast<float>(pool.angles[static_cast<std::size_t>(c) * tsynth::kMaxArms +
                                        static_cast<std::size_t>(a)] *
                     180.0 / tsynth::kPi)
                 : std::nanf(""));
        }
        table->AddColumn(angle);
      }
      for (int l = 0; l < tsynth::kNoiseLevels; ++l)
      {
        vtkNew<vtkFloatArray> noise;
        noise->SetName(("Noise" + std::to_string(l)).c_str());
        noise->SetNumberOfTuples(n);
        for (vtkIdType c = 0; c < n; ++c)
        {
          noise->SetValue(c,
            pool.noise[static_cast<std::size_t>(c) * tsynth::kNoiseLevels +
              static_cast<std::size_t>(l)]);
        }
        table->AddColumn(noise);
      }
      vtkNew<vtkDoubleArray> patch;
      patch->SetName("PatchSize");
      patch->InsertNextValue(pool.patchSize);
      table->GetFieldData()->AddArray(patch);
      vtkNew<vtkDoubleArray> scale;
      scale->SetName("HeightScale");
      scale->InsertNextValue(pool.heightScale);
      table->GetFieldData()->AddArray(scale);
    });
}

void vtkTerrainCandidateBuilder::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "PatchSize: " << this->PatchSize << "\n";
}
