// Gradient-domain editing of a heightfield, the two operations of the Terrain
// Poisson Solver filter (Pérez, Gangnet & Blake 2003, "Poisson Image Editing"):
// seamless cloning of a source into a destination, and integration of a slope
// field inside a mask. Both keep the destination outside the mask and solve
// inside it with the masked multigrid-preconditioned CG solver (Poisson.h).
// In ParaView: vtkTerrainPoissonSolver (Terrain Poisson Solver), in Filters/.
#pragma once

#include "../Core/Heightfield.h"
#include "../Core/OptionTable.h"
#include "Poisson.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace tsynth
{

// The two edits, in the Terrain Poisson Solver's Mode order.
enum class PoissonEditMode
{
  SeamlessClone, // the source's slopes inside the mask
  GuidanceField  // a given slope field inside the mask
};
inline constexpr const char* kPoissonEditModeWords[] = { "clone", "guidance" };

// The relative residual an edit stops at by default: the solver's own
// (PoissonOptions::tolerance, 1e-10). Multigrid-preconditioned CG gains about
// two orders of magnitude per iteration, so it costs two iterations more than
// 1e-8 (measured: 14 against 12 on a 648^2 clone) and leaves no question of
// which of two defaults applies.
constexpr double kMinEditTolerance = 1e-14; // near double precision's reach on a solve
constexpr double kMaxEditTolerance = 0.1;   // coarser stops leave visible steps

// The edits' options as a table: the Terrain Poisson Solver's Mode and Tolerance.
const std::vector<OptionRow>& poissonEditOptionRows();

// CG with the multigrid preconditioner converges in tens of iterations on any
// mask; this bounds a solve that cannot (the statistics say how far it got).
constexpr int kPoissonEditMaxIterations = 200;

struct PoissonEditResult
{
  Heightfield terrain; // the destination with the masked cells solved
  PoissonStatistics statistics;
  std::size_t solvedCells = 0; // 0: the mask was empty and nothing changed
};

// Inside `mask` (one byte per cell; null: the source's valid cells) the
// heights whose differences along every edge are the source's, meeting the
// destination on the mask's border. Throws tsynth::Error if the source is not
// on the destination's grid or the mask has the wrong size.
PoissonEditResult seamlessClone(const Heightfield& destination,
  const Heightfield& source,
  const std::vector<std::uint8_t>* mask,
  double tolerance);

// Inside `mask` the heights whose slopes are (slopeX, slopeY) (dz/dx and dz/dy
// per cell, metres per metre; an edge takes the mean of its two ends), meeting
// the destination on the mask's border. Throws tsynth::Error for arrays of the
// wrong size.
PoissonEditResult integrateSlopes(const Heightfield& destination,
  const std::vector<double>& slopeX,
  const std::vector<double>& slopeY,
  const std::vector<std::uint8_t>& mask,
  double tolerance);

} // namespace tsynth
