// Pipeline requests shared by the filters whose inputs differ in size.
#pragma once

class vtkInformation;
class vtkInformationVector;

namespace tsynth
{

// Asks every connection of the first `ports` input ports for its whole extent.
void requestWholeExtents(vtkInformationVector** inputVector, int ports);

// Gives the output the grid (whole extent, spacing, origin) of one input.
void copyGrid(vtkInformation* from, vtkInformation* to);

} // namespace tsynth
