#include "PipelineRequests.h"

#include <vtkDataObject.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkPolyData.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkTable.h>

#include <algorithm>
#include <map>
#include <mutex>

namespace tsynth
{

namespace
{

// The newest modification of `filter` (its settings and connections) or of the algorithms that
// feed it. Not of their data: ParaView's representations re-run a reader for each of their
// requests, which renews its output's time while nothing the user set has changed.
vtkMTimeType newestChange(vtkAlgorithm* filter)
{
  vtkMTimeType newest = filter->GetMTime();
  for (int port = 0; port < filter->GetNumberOfInputPorts(); ++port)
  {
    for (int c = 0; c < filter->GetNumberOfInputConnections(port); ++c)
    {
      if (vtkAlgorithm* producer = filter->GetInputAlgorithm(port, c))
      {
        newest = std::max(newest, producer->GetMTime());
      }
    }
  }
  return newest;
}

struct Refusal
{
  std::string message;
  vtkMTimeType at = 0;
};

} // namespace

void reportRefusal(vtkAlgorithm* filter, const std::string& message)
{
  // Per filter, its last refusal. Modification times only grow, so a filter made later at the
  // address of a deleted one never matches the old entry's time.
  static std::mutex mutex;
  static std::map<const vtkAlgorithm*, Refusal> last;
  const vtkMTimeType now = newestChange(filter);
  {
    const std::lock_guard<std::mutex> lock(mutex);
    Refusal& said = last[filter];
    if (said.message == message && said.at == now)
    {
      return;
    }
    said = { message, now };
  }
  vtkErrorWithObjectMacro(filter, << message);
}

void requestWholeExtents(vtkInformationVector** inputVector, int ports)
{
  for (int port = 0; port < ports; ++port)
  {
    for (int c = 0; c < inputVector[port]->GetNumberOfInformationObjects(); ++c)
    {
      vtkInformation* in = inputVector[port]->GetInformationObject(c);
      // The whole input on every rank of a parallel engine too, not its piece.
      in->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), 0);
      in->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), 1);
      if (in->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
      {
        int extent[6];
        in->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent);
        in->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), extent, 6);
      }
    }
  }
}

bool imageProducerFailed(vtkInformationVector* port)
{
  for (int c = 0; c < port->GetNumberOfInformationObjects(); ++c)
  {
    vtkInformation* in = port->GetInformationObject(c);
    vtkDataObject* data = in->Get(vtkDataObject::DATA_OBJECT());
    if (vtkPolyData::SafeDownCast(data) != nullptr || vtkTable::SafeDownCast(data) != nullptr)
    {
      continue; // no extent to announce
    }
    if (!in->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
    {
      return true;
    }
    int e[6];
    in->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), e);
    const bool empty = e[1] < e[0] || e[3] < e[2] || e[5] < e[4];
    if (empty && !in->Has(vtkDataObject::SPACING()))
    {
      return true;
    }
  }
  return false;
}

bool anyImageProducerFailed(vtkInformationVector** inputVector, int ports)
{
  for (int p = 0; p < ports; ++p)
  {
    if (imageProducerFailed(inputVector[p]))
    {
      return true;
    }
  }
  return false;
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
