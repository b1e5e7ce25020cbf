// Poisson solvers for seam removal (Perez et al. 2003; Zhou et al. 2007;
// Tasse's thesis). Both discretise with the 5-point stencil on cells of size
// cellX x cellY: (Lu)_p = sum_q w_pq (u_q - u_p), w = 1/cellX^2 along x,
// 1/cellY^2 along y.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

namespace tsynth
{

// Dirichlet problem on a full rectangle by a discrete sine transform (FFTW's
// RODFT00 diagonalises the 5-point Laplacian with zero boundary). Plans are
// made once per size, shared by all instances (guarded by a mutex) and run with
// FFTW's new-array interface, which is thread-safe. Fast when interior sizes
// N have N + 1 with small prime factors (N = 95: 0.3 ms; N = 96: 1.9 ms).
class DstPoissonSolver
{
public:
  // plannerEffort: false = FFTW_ESTIMATE (no planning cost), true = FFTW_MEASURE
  // (slow first plan of each size, faster solves).
  explicit DstPoissonSolver(bool measurePlans = true);
  ~DstPoissonSolver();
  DstPoissonSolver(const DstPoissonSolver&) = delete;
  DstPoissonSolver& operator=(const DstPoissonSolver&) = delete;

  // u is width x height (row-major, row 0 south); its border cells hold the
  // Dirichlet values and are not changed. laplacian (same layout, only the
  // interior is read) is the target of L u. Fills the interior of u.
  void solve(int width, int height, double cellX, double cellY, const double* laplacian, double* u);

  // The core: solves -L x = b on an nx x ny grid with zero boundary; b is
  // overwritten with x.
  void solveZeroBoundary(int nx, int ny, double cellX, double cellY, double* b);

private:
  struct Buffer;
  bool measure_;
  std::unique_ptr<Buffer> buffer_;
};

struct PoissonOptions
{
  double tolerance = 1e-10; // stop when |residual| <= tolerance * |initial residual|
  int maxIterations = 100;  // preconditioned CG iterations
  // Red-black Gauss-Seidel sweeps before and after each coarse solve (at least 1).
  int smoothingSweeps = 2;
  // Also stop when the estimated error of u, in the units of u, is at most this
  // (0 = off). The estimate is the largest entry of the multigrid-preconditioned
  // residual, which approximates the error itself (one V-cycle approximates the
  // inverse). For blending, a fraction of the height range far below DEM
  // precision; it makes the solve independent of how large the start's misfit is.
  double errorTolerance = 0.0;
};

struct PoissonStatistics
{
  int iterations = 0;
  double initialResidual = 0.0; // 2-norm
  double finalResidual = 0.0;
  std::size_t unknowns = 0;
  std::size_t pinnedUnknowns = 0; // in components with no Dirichlet neighbour (kept as given)
};

// Poisson on an arbitrary mask of unknown cells: conjugate gradient (double)
// preconditioned by one multigrid V-cycle (Galerkin aggregation of 2x2 cells,
// symmetric red-black Gauss-Seidel, in single precision on a red-black split
// layout so the smoother vectorises). Cells outside the mask with a finite value
// are Dirichlet values; edges to cells without one (nodata, unfilled) are left
// out (natural Neumann boundary). Connected parts of the mask with no Dirichlet
// neighbour have no unique solution and keep their starting values. Holds its
// hierarchy between calls; one instance per thread.
class MaskedPoissonSolver
{
public:
  MaskedPoissonSolver();
  ~MaskedPoissonSolver();
  MaskedPoissonSolver(const MaskedPoissonSolver&) = delete;
  MaskedPoissonSolver& operator=(const MaskedPoissonSolver&) = delete;

  // Gradient-domain form: minimises sum over edges of w (u_q - u_p - g_pq)^2,
  // with gx[k] the wanted u(i+1,j) - u(i,j) and gy[k] the wanted u(i,j+1) -
  // u(i,j) (differences, not slopes; null = 0; NaN drops the edge). u holds
  // Dirichlet values outside the mask and the starting guess inside; the
  // interior is overwritten. The solve is for the correction to the start, so a
  // start that already fits the guidance is returned bit for bit.
  PoissonStatistics solveGuided(int width,
    int height,
    double cellX,
    double cellY,
    const std::uint8_t* unknown,
    const double* gx,
    const double* gy,
    double* u,
    const PoissonOptions& options = {});

  // Laplacian form: L u = laplacian on the mask (laplacian has the grid layout).
  PoissonStatistics solveLaplacian(int width,
    int height,
    double cellX,
    double cellY,
    const std::uint8_t* unknown,
    const double* laplacian,
    double* u,
    const PoissonOptions& options = {});

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

} // namespace tsynth
