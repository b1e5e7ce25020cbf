#include "PipelineRequests.h"

#include <vtkDataObject.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkStreamingDemandDrivenPipeline.h>

namespace tsynth
{

void requestWholeExtents(vtkInformationVector** inputVector, int ports)
{
  for (int port = 0; port < ports; ++port)
  {
    for (int c = 0; c < inputVector[port]->GetNumberOfInformationObjects(); ++c)
    {
      vtkInformation* in = inputVector[port]->GetInformationObject(c);
      if (in->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
      {
        int extent[6];
        in->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent);
        in->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), extent, 6);
      }
    }
  }
}

void copyGrid(vtkInformation* from, vtkInformation* to)
{
  if (from == nullptr || !from->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    return;
  }
  to->CopyEntry(from, vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT());
  to->CopyEntry(from, vtkDataObject::SPACING());
  to->CopyEntry(from, vtkDataObject::ORIGIN());
}

} // namespace tsynth
