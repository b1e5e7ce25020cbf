// Pipeline requests shared by the filters whose inputs differ in size.
#pragma once

#include "Core/Cancellation.h"

#include <vtkAlgorithm.h>
#include <vtkSetGet.h>

#include <exception>
#include <new>
#include <string>

class vtkInformation;
class vtkInformationVector;

namespace tsynth
{

// Asks every connection of the first `ports` input ports for its whole extent,
// as one piece (on every rank of a parallel engine).
void requestWholeExtents(vtkInformationVector** inputVector, int ports);

// Whether a producer on one of the port's connections failed to announce its image (a reader
// whose file is missing: its RequestInformation failed and said why): no whole extent, or (past
// ParaView's vtkPVPostFilter) an empty one without a spacing, which every image that was
// announced has. A filter's RequestInformation then fails without a sentence of its own, which
// would name a consequence (no cell size, an empty sketch) and not the cause. Poly data and
// tables announce no extent and never count as failed here.
bool imageProducerFailed(vtkInformationVector* port);

// Whether the image producer on any of the first `ports` input ports failed (see above).
bool anyImageProducerFailed(vtkInformationVector** inputVector, int ports);

// Gives the output the grid (whole extent, spacing, origin) of one input.
void copyGrid(vtkInformation* from, vtkInformation* to);

// Held for the length of a filter's RequestData: ParaView's abort (CheckAbort) stops the
// kernels the filter runs at their next poll with tsynth::Cancelled, which the filter turns
// into an empty output.
class AbortScope : public CancellationScope
{
public:
  explicit AbortScope(vtkAlgorithm* filter)
    : CancellationScope([filter] { return filter->CheckAbort(); })
  {
  }
};

// Reports `message` as `filter`'s error, unless the filter reported the same sentence last time
// and neither it nor its inputs changed since: ParaView updates a filter twice on Apply (the
// pipeline, then its representation), and a refusal is said once, not once per update.
void reportRefusal(vtkAlgorithm* filter, const std::string& message);

// A filter's RequestData body run the one way every filter runs it: under an
// AbortScope, with tsynth::Cancelled (ParaView's abort) turned into empty outputs
// (clearOutputs) and a request that succeeds, running out of memory into the error
// `outOfMemory` (one sentence naming what to make smaller), and any other failure
// into its own sentence (each said once: reportRefusal); both fail the request.
// Returns what RequestData returns.
template<class ClearOutputs, class Body>
int runFilterRequest(vtkAlgorithm* filter,
  const char* outOfMemory,
  const ClearOutputs& clearOutputs,
  const Body& body)
{
  try
  {
    const AbortScope abortScope(filter);
    body();
    return 1;
  }
  catch (const Cancelled&)
  {
    clearOutputs();
    return 1;
  }
  catch (const std::bad_alloc&)
  {
    reportRefusal(filter, outOfMemory);
    return 0;
  }
  catch (const std::exception& e)
  {
    reportRefusal(filter, e.what());
    return 0;
  }
}

} // namespace tsynth
