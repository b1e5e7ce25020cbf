// Pipeline requests shared by the filters whose inputs differ in size.
#pragma once

#include "Core/Cancellation.h"

#include <vtkAlgorithm.h>

class vtkInformation;
class vtkInformationVector;

namespace tsynth
{

// Asks every connection of the first `ports` input ports for its whole extent.
void requestWholeExtents(vtkInformationVector** inputVector, int ports);

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

} // namespace tsynth
