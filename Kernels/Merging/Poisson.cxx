#include "Poisson.h"

#include "../Core/Error.h"

#include <Eigen/Dense>
#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <tuple>

namespace tsynth
{

// ---------------------------------------------------------------------------
// DST-I solver

namespace
{

std::mutex& planMutex()
{
  static std::mutex m;
  return m;
}

// Plans live for the whole process: sizes are few, planning is the expensive part.
fftw_plan dstPlan(int nx, int ny, bool measure)
{
  static std::map<std::tuple<int, int, bool>, fftw_plan> plans;
  std::lock_guard<std::mutex> lock(planMutex());
  const auto key = std::make_tuple(nx, ny, measure);
  auto it = plans.find(key);
  if (it != plans.end())
  {
    return it->second;
  }
  double* scratch = fftw_alloc_real(static_cast<std::size_t>(nx) * ny);
  fftw_plan plan = fftw_plan_r2r_2d(
    ny, nx, scratch, scratch, FFTW_RODFT00, FFTW_RODFT00, measure ? FFTW_MEASURE : FFTW_ESTIMATE);
  fftw_free(scratch);
  if (!plan)
  {
    throw Error("FFTW could not plan a sine transform of " + std::to_string(nx) + " x " +
      std::to_string(ny) + " values.");
  }
  plans.emplace(key, plan);
  return plan;
}

} // namespace

struct DstPoissonSolver::Buffer
{
  double* data = nullptr;
  std::size_t capacity = 0;
  std::vector<double> lambdaX, lambdaY;
  int nx = -1, ny = -1;
  double cellX = 0.0, cellY = 0.0;
  ~Buffer() { fftw_free(data); }
};

DstPoissonSolver::DstPoissonSolver(bool measurePlans)
  : measure_(measurePlans)
  , buffer_(std::make_unique<Buffer>())
{
}

DstPoissonSolver::~DstPoissonSolver() = default;

void DstPoissonSolver::solveZeroBoundary(int nx, int ny, double cellX, double cellY, double* b)
{
  if (nx <= 0 || ny <= 0)
  {
    return;
  }
  const std::size_t n = static_cast<std::size_t>(nx) * ny;
  Buffer& buf = *buffer_;
  if (buf.capacity < n)
  {
    fftw_free(buf.data);
    buf.data = fftw_alloc_real(n);
    buf.capacity = n;
  }
  if (buf.nx != nx || buf.ny != ny || buf.cellX != cellX || buf.cellY != cellY)
  {
    // Eigenvalues of -L for the sine modes.
    const double pi = 3.14159265358979323846;
    buf.lambdaX.resize(nx);
    buf.lambdaY.resize(ny);
    for (int k = 0; k < nx; ++k)
    {
      buf.lambdaX[k] = (2.0 - 2.0 * std::cos(pi * (k + 1) / (nx + 1))) / (cellX * cellX);
    }
    for (int k = 0; k < ny; ++k)
    {
      buf.lambdaY[k] = (2.0 - 2.0 * std::cos(pi * (k + 1) / (ny + 1))) / (cellY * cellY);
    }
    buf.nx = nx;
    buf.ny = ny;
    buf.cellX = cellX;
    buf.cellY = cellY;
  }
  fftw_plan plan = dstPlan(nx, ny, measure_);
  std::copy(b, b + n, buf.data);
  fftw_execute_r2r(plan, buf.data, buf.data);
  // RODFT00 is its own inverse up to 2(n+1) per dimension.
  const double norm = 1.0 / (4.0 * (nx + 1) * (ny + 1));
  for (int j = 0; j < ny; ++j)
  {
    double* row = buf.data + static_cast<std::size_t>(j) * nx;
    const double ly = buf.lambdaY[j];
    for (int i = 0; i < nx; ++i)
    {
      row[i] *= norm / (buf.lambdaX[i] + ly);
    }
  }
  fftw_execute_r2r(plan, buf.data, buf.data);
  std::copy(buf.data, buf.data + n, b);
}

void DstPoissonSolver::solve(int width,
  int height,
  double cellX,
  double cellY,
  const double* laplacian,
  double* u)
{
  const int nx = width - 2;
  const int ny = height - 2;
  if (nx <= 0 || ny <= 0)
  {
    return;
  }
  const double wx = 1.0 / (cellX * cellX);
  const double wy = 1.0 / (cellY * cellY);
  std::vector<double> b(static_cast<std::size_t>(nx) * ny);
  for (int j = 1; j <= ny; ++j)
  {
    for (int i = 1; i <= nx; ++i)
    {
      const std::size_t k = static_cast<std::size_t>(j) * width + i;
      // -L u = -laplacian, with the known boundary values moved to the right.
      double v = -laplacian[k];
      if (i == 1)
      {
        v += wx * u[k - 1];
      }
      if (i == nx)
      {
        v += wx * u[k + 1];
      }
      if (j == 1)
      {
        v += wy * u[k - width];
      }
      if (j == ny)
      {
        v += wy * u[k + width];
      }
      b[static_cast<std::size_t>(j - 1) * nx + (i - 1)] = v;
    }
  }
  solveZeroBoundary(nx, ny, cellX, cellY, b.data());
  for (int j = 1; j <= ny; ++j)
  {
    std::copy(b.begin() + static_cast<std::ptrdiff_t>(j - 1) * nx,
      b.begin() + static_cast<std::ptrdiff_t>(j) * nx,
      u + static_cast<std::size_t>(j) * width + 1);
  }
}

// ---------------------------------------------------------------------------
// Multigrid-preconditioned CG on a mask

namespace
{

// One level of the hierarchy, on a grid padded by a one-cell frame so stencils
// need no bounds tests. Vectors are zero outside the unknowns.
struct Level
{
  int w = 0, h = 0; // unpadded size
  int stride = 0;
  std::vector<std::uint8_t> unknown;
  std::vector<double> wE, wN;  // coupling to the +x / +y unknown neighbour
  std::vector<double> diag;    // includes edges to Dirichlet cells
  std::vector<double> invDiag; // 1 / diag on unknowns, 0 elsewhere
  std::vector<double> x, b, r;
  // Per row j, the unknowns lie in columns [rowBegin[j], rowEnd[j]) (empty if
  // equal): the loops skip the rest of the row. Vectors stay 0 outside.
  std::vector<int> rowBegin, rowEnd;
  std::size_t count = 0;
  // Coarsest level: dense Cholesky over its unknowns.
  std::vector<int> denseIndex;
  Eigen::LLT<Eigen::MatrixXd> dense;
  Eigen::VectorXd denseRhs;

  std::size_t pad(int i, int j) const
  {
    return static_cast<std::size_t>(j + 1) * stride + static_cast<std::size_t>(i + 1);
  }
  void allocate(int width, int height)
  {
    w = width;
    h = height;
    stride = w + 2;
    const std::size_t n = static_cast<std::size_t>(stride) * (h + 2);
    unknown.assign(n, 0);
    wE.assign(n, 0.0);
    wN.assign(n, 0.0);
    diag.assign(n, 0.0);
    x.assign(n, 0.0);
    b.assign(n, 0.0);
    r.assign(n, 0.0);
    count = 0;
  }
  // After unknown and diag are final: inverse diagonal, row extents, count.
  void finish()
  {
    invDiag.assign(unknown.size(), 0.0);
    rowBegin.assign(static_cast<std::size_t>(h), 0);
    rowEnd.assign(static_cast<std::size_t>(h), 0);
    count = 0;
    for (int j = 0; j < h; ++j)
    {
      int first = w, last = -1;
      for (int i = 0; i < w; ++i)
      {
        const std::size_t k = pad(i, j);
        if (!unknown[k])
          continue;
        invDiag[k] = 1.0 / diag[k];
        first = std::min(first, i);
        last = i;
        ++count;
      }
      rowBegin[j] = last >= 0 ? first : 0;
      rowEnd[j] = last + 1;
    }
  }
};

// Threads only pay off on large grids; every loop below writes disjoint cells,
// so results do not depend on the thread count.
constexpr long ParallelCells = 32768;

void applyOperator(const Level& L, const double* v, double* y)
{
  const std::size_t s = L.stride;
  const double* const diag = L.diag.data();
  const double* const wE = L.wE.data();
  const double* const wN = L.wN.data();
#pragma omp parallel for schedule(static) if (static_cast <long>(L.w) * L.h > ParallelCells)
  for (int j = 0; j < L.h; ++j)
  {
    const std::size_t row = L.pad(0, j);
    // Off the unknowns the diagonal and every coupling are 0 (and v is 0), so
    // y is 0 there without a test, and the loop vectorises.
    for (std::size_t k = row + L.rowBegin[j]; k < row + static_cast<std::size_t>(L.rowEnd[j]); ++k)
    {
      y[k] = diag[k] * v[k] -
        (wE[k] * v[k + 1] + wE[k - 1] * v[k - 1] + wN[k] * v[k + s] + wN[k - s] * v[k - s]);
    }
  }
}

// Gauss-Seidel update of the cells of one colour in row j (red-black order).
inline void smoothRow(Level& L, int j, int colour)
{
  const std::size_t s = L.stride;
  const std::size_t row = L.pad(0, j);
  const int begin = L.rowBegin[j] + ((L.rowBegin[j] + j + colour) & 1);
  double* const x = L.x.data();
  const double* const b = L.b.data();
  const double* const wE = L.wE.data();
  const double* const wN = L.wN.data();
  const double* const invDiag = L.invDiag.data();
  for (int i = begin; i < L.rowEnd[j]; i += 2)
  {
    const std::size_t k = row + static_cast<std::size_t>(i);
    // invDiag is 0 off the unknowns, where x stays 0.
    x[k] =
      (b[k] + wE[k] * x[k + 1] + wE[k - 1] * x[k - 1] + wN[k] * x[k + s] + wN[k - s] * x[k - s]) *
      invDiag[k];
  }
}

// One symmetric red-black Gauss-Seidel sweep: colour first, then the other.
// On small grids the two half sweeps run as one pass over the rows, the other
// colour one row behind (its cells then see every update they would see after
// a full first half sweep), so each row is loaded once: same result, half the
// memory traffic. Large grids run each half sweep in parallel instead.
void sweep(Level& L, int first)
{
  if (static_cast<long>(L.w) * L.h > ParallelCells)
  {
    for (int colour : { first, first ^ 1 })
    {
#pragma omp parallel for schedule(static)
      for (int j = 0; j < L.h; ++j)
        smoothRow(L, j, colour);
    }
    return;
  }
  for (int j = 0; j < L.h; ++j)
  {
    smoothRow(L, j, first);
    if (j > 0)
      smoothRow(L, j - 1, first ^ 1);
  }
  if (L.h > 0)
    smoothRow(L, L.h - 1, first ^ 1);
}

double dot(const std::vector<double>& a, const std::vector<double>& b)
{
  double s = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k)
  {
    s += a[k] * b[k];
  }
  return s;
}

} // namespace

struct MaskedPoissonSolver::Impl
{
  std::vector<Level> levels;
  std::vector<double> delta, res, dir, q, z;
  std::vector<int> stack;
  std::vector<int> component;

  void buildCoarse(const Level& fine, Level& coarse)
  {
    coarse.allocate((fine.w + 1) / 2, (fine.h + 1) / 2);
    for (int j = 0; j < fine.h; ++j)
    {
      for (int i = 0; i < fine.w; ++i)
      {
        const std::size_t k = fine.pad(i, j);
        if (!fine.unknown[k])
        {
          continue;
        }
        const std::size_t c = coarse.pad(i / 2, j / 2);
        coarse.unknown[c] = 1;
        // Galerkin P^T A P with piecewise-constant P: edges inside the block
        // cancel, edges leaving it stay. Halved below (see there).
        double external = fine.diag[k];
        if (fine.wE[k] > 0.0 && (i + 1) / 2 == i / 2)
          external -= fine.wE[k];
        else if (fine.wE[k] > 0.0)
          coarse.wE[c] += fine.wE[k];
        if (fine.wE[k - 1] > 0.0 && (i - 1) / 2 == i / 2 && i > 0)
          external -= fine.wE[k - 1];
        if (fine.wN[k] > 0.0 && (j + 1) / 2 == j / 2)
          external -= fine.wN[k];
        else if (fine.wN[k] > 0.0)
          coarse.wN[c] += fine.wN[k];
        if (fine.wN[k - fine.stride] > 0.0 && (j - 1) / 2 == j / 2 && j > 0)
          external -= fine.wN[k - fine.stride];
        coarse.diag[c] += external;
      }
    }
    // Aggregation makes the coarse operator twice as stiff as a rediscretised
    // one; halving it restores the size of the coarse correction.
    for (std::size_t c = 0; c < coarse.unknown.size(); ++c)
    {
      coarse.wE[c] *= 0.5;
      coarse.wN[c] *= 0.5;
      coarse.diag[c] *= 0.5;
    }
    coarse.finish();
  }

  void buildDense(Level& L)
  {
    L.denseIndex.assign(L.unknown.size(), -1);
    int n = 0;
    for (std::size_t k = 0; k < L.unknown.size(); ++k)
    {
      if (L.unknown[k])
      {
        L.denseIndex[k] = n++;
      }
    }
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
    for (std::size_t k = 0; k < L.unknown.size(); ++k)
    {
      const int a = L.denseIndex[k];
      if (a < 0)
      {
        continue;
      }
      A(a, a) = L.diag[k];
      if (L.wE[k] > 0.0)
      {
        const int e = L.denseIndex[k + 1];
        A(a, e) = A(e, a) = -L.wE[k];
      }
      if (L.wN[k] > 0.0)
      {
        const int e = L.denseIndex[k + L.stride];
        A(a, e) = A(e, a) = -L.wN[k];
      }
    }
    L.dense.compute(A);
  }

  void vcycle(std::size_t l, int sweeps)
  {
    Level& L = levels[l];
    std::fill(L.x.begin(), L.x.end(), 0.0);
    if (l + 1 == levels.size())
    {
      Eigen::VectorXd& rhs = L.denseRhs;
      rhs.resize(static_cast<Eigen::Index>(L.count));
      for (std::size_t k = 0; k < L.unknown.size(); ++k)
        if (L.denseIndex[k] >= 0)
          rhs[L.denseIndex[k]] = L.b[k];
      L.dense.solveInPlace(rhs);
      for (std::size_t k = 0; k < L.unknown.size(); ++k)
        if (L.denseIndex[k] >= 0)
          L.x[k] = rhs[L.denseIndex[k]];
      return;
    }
    for (int s = 0; s < sweeps; ++s)
      sweep(L, 0);
    applyOperator(L, L.x.data(), L.r.data());
    Level& C = levels[l + 1];
    std::fill(C.b.begin(), C.b.end(), 0.0);
    // Restriction by coarse row, so threads never share an output cell.
#pragma omp parallel for schedule(static) if (static_cast <long>(L.w) * L.h > ParallelCells)
    for (int cj = 0; cj < C.h; ++cj)
    {
      for (int j = 2 * cj; j < std::min(2 * cj + 2, L.h); ++j)
      {
        for (int i = L.rowBegin[j]; i < L.rowEnd[j]; ++i)
        {
          const std::size_t k = L.pad(i, j);
          if (L.unknown[k])
          {
            C.b[C.pad(i / 2, cj)] += L.b[k] - L.r[k];
          }
        }
      }
    }
    vcycle(l + 1, sweeps);
#pragma omp parallel for schedule(static) if (static_cast <long>(L.w) * L.h > ParallelCells)
    for (int j = 0; j < L.h; ++j)
    {
      for (int i = L.rowBegin[j]; i < L.rowEnd[j]; ++i)
      {
        const std::size_t k = L.pad(i, j);
        if (L.unknown[k])
        {
          L.x[k] += C.x[C.pad(i / 2, j / 2)];
        }
      }
    }
    // Reverse colour order so the V-cycle is a symmetric preconditioner.
    for (int s = 0; s < sweeps; ++s)
      sweep(L, 1);
  }

  // Finest level from the problem; returns false if nothing to solve.
  // edgeOk(k, d): whether the fine edge from cell k in direction d (0 +x, 1 +y) exists.
  template<typename EdgeOk>
  void buildFine(int width,
    int height,
    double cellX,
    double cellY,
    const std::uint8_t* unknownIn,
    const double* u,
    EdgeOk edgeOk,
    PoissonStatistics& stats)
  {
    levels.reserve(40); // never reallocated: callers hold references to level 0
    levels.resize(1);
    Level& F = levels[0];
    F.allocate(width, height);
    const double wx = 1.0 / (cellX * cellX);
    const double wy = 1.0 / (cellY * cellY);
    auto present = [&](int i, int j)
    {
      if (i < 0 || j < 0 || i >= width || j >= height)
        return false;
      const std::size_t g = static_cast<std::size_t>(j) * width + i;
      return unknownIn[g] != 0 || std::isfinite(u[g]);
    };
    for (int j = 0; j < height; ++j)
    {
      for (int i = 0; i < width; ++i)
      {
        F.unknown[F.pad(i, j)] = unknownIn[static_cast<std::size_t>(j) * width + i] != 0;
      }
    }
    // Edge weights: an edge counts if it touches an unknown, both ends have a
    // value or are unknown, and its guidance is defined.
    for (int j = 0; j < height; ++j)
    {
      for (int i = 0; i < width; ++i)
      {
        const std::size_t k = F.pad(i, j);
        const std::size_t g = static_cast<std::size_t>(j) * width + i;
        if (i + 1 < width && (F.unknown[k] || F.unknown[k + 1]) && present(i, j) &&
          present(i + 1, j) && edgeOk(g, 0))
        {
          if (F.unknown[k] && F.unknown[k + 1])
            F.wE[k] = wx;
          F.diag[k] += F.unknown[k] ? wx : 0.0;
          F.diag[k + 1] += F.unknown[k + 1] ? wx : 0.0;
        }
        if (j + 1 < height && (F.unknown[k] || F.unknown[k + F.stride]) && present(i, j) &&
          present(i, j + 1) && edgeOk(g, 1))
        {
          if (F.unknown[k] && F.unknown[k + F.stride])
            F.wN[k] = wy;
          F.diag[k] += F.unknown[k] ? wy : 0.0;
          F.diag[k + F.stride] += F.unknown[k + F.stride] ? wy : 0.0;
        }
      }
    }
    // Components of unknowns with no Dirichlet edge (diag > couplings nowhere)
    // are singular: pin them (drop them from the unknowns).
    component.assign(F.unknown.size(), -1);
    const std::size_t s = F.stride;
    std::vector<std::size_t> members;
    for (std::size_t seed = 0; seed < F.unknown.size(); ++seed)
    {
      if (!F.unknown[seed] || component[seed] >= 0)
        continue;
      members.clear();
      bool anchored = false;
      stack.assign(1, static_cast<int>(seed));
      component[seed] = 1;
      while (!stack.empty())
      {
        const std::size_t k = static_cast<std::size_t>(stack.back());
        stack.pop_back();
        members.push_back(k);
        const double coupling = F.wE[k] + F.wE[k - 1] + F.wN[k] + F.wN[k - s];
        anchored = anchored || F.diag[k] > coupling * (1.0 + 1e-12);
        const std::size_t nb[4] = { k + 1, k - 1, k + s, k - s };
        const double wt[4] = { F.wE[k], F.wE[k - 1], F.wN[k], F.wN[k - s] };
        for (int d = 0; d < 4; ++d)
        {
          if (wt[d] > 0.0 && component[nb[d]] < 0)
          {
            component[nb[d]] = 1;
            stack.push_back(static_cast<int>(nb[d]));
          }
        }
      }
      if (!anchored)
      {
        stats.pinnedUnknowns += members.size();
        for (std::size_t k : members)
        {
          F.unknown[k] = 0;
          F.diag[k] = 0.0;
          F.wE[k] = F.wN[k] = 0.0;
          F.wE[k - 1] = 0.0; // neighbours in the same component only
          F.wN[k - s] = 0.0;
        }
      }
    }
    F.finish();
    stats.unknowns = F.count;
  }

  void buildHierarchy()
  {
    constexpr std::size_t denseLimit = 64;
    while (levels.back().count > denseLimit && (levels.back().w > 1 || levels.back().h > 1))
    {
      Level coarse;
      buildCoarse(levels.back(), coarse);
      levels.push_back(std::move(coarse));
    }
    buildDense(levels.back());
  }

  // Solves A delta = res (res holds the initial residual on the padded grid).
  // Vectors are 0 off the unknowns, so whole-array loops give the same sums.
  void pcg(const PoissonOptions& options, PoissonStatistics& stats)
  {
    Level& F = levels[0];
    const std::size_t n = F.unknown.size();
    delta.assign(n, 0.0);
    dir.assign(n, 0.0);
    q.assign(n, 0.0);
    z.assign(n, 0.0);
    const double r0 = std::sqrt(dot(res, res));
    stats.initialResidual = r0;
    stats.finalResidual = r0;
    if (r0 == 0.0 || F.count == 0)
    {
      return;
    }
    // z = V-cycle(res): the V-cycle reads its right-hand side from F.b and
    // leaves its result in F.x; swapping buffers avoids two copies.
    auto precondition = [&]()
    {
      F.b.swap(res);
      vcycle(0, options.smoothingSweeps);
      F.b.swap(res);
      z.swap(F.x);
    };
    // rz = res . z, and whether the estimated error max |z| is small enough.
    auto examine = [&](double& rz)
    {
      double s = 0.0, e = 0.0;
      for (std::size_t k = 0; k < n; ++k)
      {
        s += res[k] * z[k];
        e = std::max(e, std::abs(z[k]));
      }
      rz = s;
      return options.errorTolerance > 0.0 && e <= options.errorTolerance;
    };
    precondition();
    double rz = 0.0;
    if (examine(rz))
    {
      return;
    }
    dir = z;
    for (int it = 1; it <= options.maxIterations; ++it)
    {
      applyOperator(F, dir.data(), q.data());
      const double alpha = rz / dot(dir, q);
      double rr = 0.0;
      for (std::size_t k = 0; k < n; ++k)
      {
        delta[k] += alpha * dir[k];
        res[k] -= alpha * q[k];
        rr += res[k] * res[k];
      }
      const double rn = std::sqrt(rr);
      stats.iterations = it;
      stats.finalResidual = rn;
      if (rn <= options.tolerance * r0)
      {
        break;
      }
      precondition();
      double rzNew = 0.0;
      if (examine(rzNew))
      {
        break;
      }
      const double beta = rzNew / rz;
      rz = rzNew;
      for (std::size_t k = 0; k < n; ++k)
      {
        dir[k] = z[k] + beta * dir[k];
      }
    }
  }
};

MaskedPoissonSolver::MaskedPoissonSolver()
  : impl_(std::make_unique<Impl>())
{
}

MaskedPoissonSolver::~MaskedPoissonSolver() = default;

PoissonStatistics MaskedPoissonSolver::solveGuided(int width,
  int height,
  double cellX,
  double cellY,
  const std::uint8_t* unknown,
  const double* gx,
  const double* gy,
  double* u,
  const PoissonOptions& options)
{
  PoissonStatistics stats;
  if (width <= 0 || height <= 0)
  {
    return stats;
  }
  Impl& m = *impl_;
  auto edgeOk = [&](std::size_t g, int d)
  {
    const double* field = d == 0 ? gx : gy;
    return !field || !std::isnan(field[g]);
  };
  m.buildFine(width, height, cellX, cellY, unknown, u, edgeOk, stats);
  Level& F = m.levels[0];
  // Residual of the starting guess: r_p = sum_q w (g_pq - (u_q - u_p)) with
  // g_pq the wanted u_q - u_p. It is exactly 0 where u already fits.
  const double wx = 1.0 / (cellX * cellX);
  const double wy = 1.0 / (cellY * cellY);
  m.res.assign(F.unknown.size(), 0.0);
  for (int j = 0; j < height; ++j)
  {
    for (int i = 0; i < width; ++i)
    {
      const std::size_t k = F.pad(i, j);
      if (!F.unknown[k])
        continue;
      const std::size_t g = static_cast<std::size_t>(j) * width + i;
      double r = 0.0;
      auto edge = [&](std::size_t gq, double wanted, bool exists)
      {
        if (exists && (unknown[gq] || std::isfinite(u[gq])) && !std::isnan(wanted))
          r += (wanted - (u[gq] - u[g]));
      };
      if (i + 1 < width)
        edge(g + 1, gx ? gx[g] : 0.0, true);
      if (i > 0)
        edge(g - 1, gx ? -gx[g - 1] : 0.0, true);
      const double rx = r;
      r = 0.0;
      if (j + 1 < height)
        edge(g + width, gy ? gy[g] : 0.0, true);
      if (j > 0)
        edge(g - width, gy ? -gy[g - width] : 0.0, true);
      // A delta = -(residual of the normal equations) with A = -L.
      m.res[k] = -(wx * rx + wy * r);
    }
  }
  m.buildHierarchy();
  m.pcg(options, stats);
  for (int j = 0; j < height; ++j)
  {
    for (int i = 0; i < width; ++i)
    {
      const std::size_t k = F.pad(i, j);
      if (F.unknown[k])
      {
        u[static_cast<std::size_t>(j) * width + i] += m.delta[k];
      }
    }
  }
  return stats;
}

PoissonStatistics MaskedPoissonSolver::solveLaplacian(int width,
  int height,
  double cellX,
  double cellY,
  const std::uint8_t* unknown,
  const double* laplacian,
  double* u,
  const PoissonOptions& options)
{
  PoissonStatistics stats;
  if (width <= 0 || height <= 0)
  {
    return stats;
  }
  Impl& m = *impl_;
  m.buildFine(
    width, height, cellX, cellY, unknown, u, [](std::size_t, int) { return true; }, stats);
  Level& F = m.levels[0];
  const double wx = 1.0 / (cellX * cellX);
  const double wy = 1.0 / (cellY * cellY);
  m.res.assign(F.unknown.size(), 0.0);
  for (int j = 0; j < height; ++j)
  {
    for (int i = 0; i < width; ++i)
    {
      const std::size_t k = F.pad(i, j);
      if (!F.unknown[k])
        continue;
      const std::size_t g = static_cast<std::size_t>(j) * width + i;
      double lu = 0.0;
      auto edge = [&](std::size_t gq, double w)
      {
        if (unknown[gq] || std::isfinite(u[gq]))
          lu += w * (u[gq] - u[g]);
      };
      if (i + 1 < width)
        edge(g + 1, wx);
      if (i > 0)
        edge(g - 1, wx);
      if (j + 1 < height)
        edge(g + width, wy);
      if (j > 0)
        edge(g - width, wy);
      // (-L) delta = -(laplacian - L u)
      m.res[k] = lu - laplacian[g];
    }
  }
  m.buildHierarchy();
  m.pcg(options, stats);
  for (int j = 0; j < height; ++j)
  {
    for (int i = 0; i < width; ++i)
    {
      const std::size_t k = F.pad(i, j);
      if (F.unknown[k])
        u[static_cast<std::size_t>(j) * width + i] += m.delta[k];
    }
  }
  return stats;
}

} // namespace tsynth
