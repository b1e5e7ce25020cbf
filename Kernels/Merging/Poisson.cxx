#include "Poisson.h"

#include "../Core/Cancellation.h"
#include "../Core/Constants.h"
#include "../Core/Error.h"
#include "../Core/Grid.h"

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

// Plans live for the whole process: sizes are few, planning is the expensive part.
// The cache destroys them at exit, so that nothing FFTW allocated is left behind.
class PlanCache
{
public:
  PlanCache() = default;
  PlanCache(const PlanCache&) = delete;
  PlanCache& operator=(const PlanCache&) = delete;
  ~PlanCache()
  {
    for (const auto& entry : plans_)
    {
      fftw_destroy_plan(entry.second);
    }
  }

  fftw_plan get(int nx, int ny, bool measure)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto key = std::make_tuple(nx, ny, measure);
    auto it = plans_.find(key);
    if (it != plans_.end())
    {
      return it->second;
    }
    double* scratch = fftw_alloc_real(cellCount(nx, ny));
    fftw_plan plan = fftw_plan_r2r_2d(
      ny, nx, scratch, scratch, FFTW_RODFT00, FFTW_RODFT00, measure ? FFTW_MEASURE : FFTW_ESTIMATE);
    fftw_free(scratch);
    if (!plan)
    {
      throw Error("FFTW could not plan a sine transform of " + std::to_string(nx) + " x " +
        std::to_string(ny) + " values.");
    }
    plans_.emplace(key, plan);
    return plan;
  }

private:
  std::mutex mutex_;
  std::map<std::tuple<int, int, bool>, fftw_plan> plans_;
};

fftw_plan dstPlan(int nx, int ny, bool measure)
{
  static PlanCache cache;
  return cache.get(nx, ny, measure);
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
  const std::size_t n = cellCount(nx, ny);
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
    buf.lambdaX.resize(nx);
    buf.lambdaY.resize(ny);
    for (int k = 0; k < nx; ++k)
    {
      buf.lambdaX[k] = (2.0 - 2.0 * std::cos(kPi * (k + 1) / (nx + 1))) / (cellX * cellX);
    }
    for (int k = 0; k < ny; ++k)
    {
      buf.lambdaY[k] = (2.0 - 2.0 * std::cos(kPi * (k + 1) / (ny + 1))) / (cellY * cellY);
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
    double* row = buf.data + rowMajor(0, j, nx);
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
  std::vector<double> b(cellCount(nx, ny));
  for (int j = 1; j <= ny; ++j)
  {
    for (int i = 1; i <= nx; ++i)
    {
      const std::size_t k = rowMajor(i, j, width);
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
      b[rowMajor(i - 1, j - 1, nx)] = v;
    }
  }
  solveZeroBoundary(nx, ny, cellX, cellY, b.data());
  for (int j = 1; j <= ny; ++j)
  {
    const double* solved = b.data() + rowMajor(0, j - 1, nx);
    std::copy(solved, solved + nx, u + rowMajor(1, j, width));
  }
}

// ---------------------------------------------------------------------------
// Multigrid-preconditioned CG on a mask

namespace
{

// One level of the hierarchy, on a grid padded by a one-cell frame so stencils
// need no bounds tests. The operator is kept in double on the natural layout
// (the CG applies it on the finest level; coarser levels are built from it).
// The V-cycle runs in single precision on a red-black split copy: cell (i, j)
// has colour (i + j) & 1 and lives at (j + 1) * hs + (i >> 1) + 1 of its
// colour's arrays, so the four neighbours of a row of one colour are
// consecutive cells of the other colour's rows and the smoother vectorises.
// Both cells of a 2x2 aggregate (i >> 1 = ci, rows 2cj and 2cj + 1) share
// index ci + 1. Every array is 0 off the unknowns (coefficients included), so
// the loops run over whole row extents without tests.
struct Level
{
  int w = 0, h = 0; // unpadded size
  int stride = 0;
  std::vector<std::uint8_t> unknown;
  std::vector<double> wE, wN; // coupling to the +x / +y unknown neighbour
  std::vector<double> diag;   // includes edges to Dirichlet cells
  // Per row j, the unknowns lie in columns [rowBegin[j], rowEnd[j]) (empty if
  // equal).
  std::vector<int> rowBegin, rowEnd;
  std::size_t count = 0;

  // Split single-precision copy, per colour c: couplings to the east, west,
  // north and south neighbours, diagonal, its inverse, and the V-cycle's
  // solution, right-hand side and residual.
  int hs = 0; // split row length
  std::vector<float> cE[2], cW[2], cN[2], cS[2], sDiag[2], sInv[2], x[2], b[2], r[2];
  // Per row j, the split indices [mBegin[j], mEnd[j]) cover the unknowns of
  // both colours.
  std::vector<int> mBegin, mEnd;

  // Coarsest level: dense Cholesky over its unknowns (split index with the
  // colour in the lowest bit).
  std::vector<int> denseCell;
  Eigen::LLT<Eigen::MatrixXd> dense;
  Eigen::VectorXd denseRhs;

  std::size_t pad(int i, int j) const { return rowMajor(i + 1, j + 1, stride); }
  std::size_t split(int i, int j) const { return rowMajor((i >> 1) + 1, j + 1, hs); }
  // Start of row j in the split arrays (split index 0, the frame).
  std::size_t splitRow(int j) const { return rowMajor(0, j + 1, hs); }
  void allocate(int width, int height)
  {
    w = width;
    h = height;
    stride = w + 2;
    const std::size_t n = cellCount(stride, h + 2);
    // assign keeps the capacity: no allocation once the hierarchy has seen
    // a window this large.
    unknown.assign(n, 0);
    wE.assign(n, 0.0);
    wN.assign(n, 0.0);
    diag.assign(n, 0.0);
    count = 0;
  }
  // After unknown and the couplings are final: row extents, count and the
  // split single-precision copy.
  void finish()
  {
    const std::size_t rows = static_cast<std::size_t>(h); // a count, for assign
    rowBegin.assign(rows, 0);
    rowEnd.assign(rows, 0);
    mBegin.assign(rows, 1);
    mEnd.assign(rows, 1);
    hs = w / 2 + 2;
    const std::size_t n = cellCount(hs, h + 2);
    for (int c = 0; c < 2; ++c)
    {
      for (auto* v : { &cE[c], &cW[c], &cN[c], &cS[c], &sDiag[c], &sInv[c], &x[c], &b[c], &r[c] })
        v->assign(n, 0.0f);
    }
    count = 0;
    for (int j = 0; j < h; ++j)
    {
      int first = w, last = -1;
      for (int i = 0; i < w; ++i)
      {
        const std::size_t k = pad(i, j);
        if (!unknown[k])
          continue;
        const int c = (i + j) & 1;
        const std::size_t m = split(i, j);
        cE[c][m] = static_cast<float>(wE[k]);
        cW[c][m] = static_cast<float>(wE[k - 1]);
        cN[c][m] = static_cast<float>(wN[k]);
        cS[c][m] = static_cast<float>(wN[k - stride]);
        sDiag[c][m] = static_cast<float>(diag[k]);
        sInv[c][m] = static_cast<float>(1.0 / diag[k]);
        first = std::min(first, i);
        last = i;
        ++count;
      }
      rowBegin[j] = last >= 0 ? first : 0;
      rowEnd[j] = last + 1;
      if (last >= 0)
      {
        mBegin[j] = (first >> 1) + 1;
        mEnd[j] = (last >> 1) + 2;
      }
    }
  }
};

// Threads only pay off on large grids; every loop below writes disjoint cells,
// so results do not depend on the thread count.
constexpr long ParallelCells = 32768;

// Serial passes over a whole terrain's rows check for cancellation once a band of rows.
void pollRow(int j)
{
  if (j % kCancellationBandRows == 0)
  {
    checkCancellation();
  }
}

bool parallel(const Level& L)
{
  return static_cast<long>(L.w) * L.h > ParallelCells;
}

void applyOperator(const Level& L, const double* v, double* y)
{
  const std::size_t s = L.stride;
  const double* const diag = L.diag.data();
  const double* const wE = L.wE.data();
  const double* const wN = L.wN.data();
#pragma omp parallel for schedule(static) if (parallel(L))
  for (int j = 0; j < L.h; ++j)
  {
    const std::size_t row = L.pad(0, j);
    // Off the unknowns the diagonal and every coupling are 0 (and v is 0), so
    // y is 0 there without a test, and the loop vectorises.
    for (std::size_t k = row + L.rowBegin[j]; k < row + L.rowEnd[j]; ++k)
    {
      y[k] = diag[k] * v[k] -
        (wE[k] * v[k + 1] + wE[k - 1] * v[k - 1] + wN[k] * v[k + s] + wN[k - s] * v[k - s]);
    }
  }
}

// Row kernels on the split layout: b plus the couplings times the other
// colour's values at m + p (east), m + p - 1 (west), m + hs (north) and m - hs
// (south), p being the column parity of the row's cells. Pointer parameters
// marked __restrict (the written array is never read through another) let the
// loops vectorise without run-time overlap checks.
inline float neighbours(int m,
  std::ptrdiff_t p,
  std::ptrdiff_t hs,
  const float* __restrict o,
  const float* __restrict b,
  const float* __restrict e,
  const float* __restrict wst,
  const float* __restrict n,
  const float* __restrict s)
{
  return b[m] + e[m] * o[m + p] + wst[m] * o[m + p - 1] + n[m] * o[m + hs] + s[m] * o[m - hs];
}

// Gauss-Seidel update of one colour: x = (b + couplings) / diag.
void smoothKernel(int mb,
  int me,
  std::ptrdiff_t p,
  std::ptrdiff_t hs,
  float* __restrict x,
  const float* __restrict o,
  const float* __restrict b,
  const float* __restrict e,
  const float* __restrict wst,
  const float* __restrict n,
  const float* __restrict s,
  const float* __restrict inv)
{
  for (int m = mb; m < me; ++m)
    x[m] = neighbours(m, p, hs, o, b, e, wst, n, s) * inv[m];
}

// Residual of one colour: r = b + couplings - diag x.
void residualKernel(int mb,
  int me,
  std::ptrdiff_t p,
  std::ptrdiff_t hs,
  float* __restrict r,
  const float* __restrict x,
  const float* __restrict o,
  const float* __restrict b,
  const float* __restrict e,
  const float* __restrict wst,
  const float* __restrict n,
  const float* __restrict s,
  const float* __restrict d)
{
  for (int m = mb; m < me; ++m)
    r[m] = neighbours(m, p, hs, o, b, e, wst, n, s) - d[m] * x[m];
}

enum class RowOp
{
  Smooth,      // x = (b + couplings) / diag
  FirstSmooth, // x = b / diag (the other colour is still 0)
  Residual     // r = b + couplings - diag x
};

// Row j of colour c.
template<RowOp Op>
inline void rowOp(Level& L, int j, int c)
{
  const std::size_t row = L.splitRow(j);
  const std::ptrdiff_t p = (c + j) & 1;
  const std::ptrdiff_t hs = L.hs;
  const int mb = L.mBegin[j], me = L.mEnd[j];
  if (Op == RowOp::FirstSmooth)
  {
    float* __restrict x = L.x[c].data() + row;
    const float* __restrict b = L.b[c].data() + row;
    const float* __restrict inv = L.sInv[c].data() + row;
    for (int m = mb; m < me; ++m)
      x[m] = b[m] * inv[m];
    return;
  }
  const float* o = L.x[c ^ 1].data() + row;
  const float* b = L.b[c].data() + row;
  const float* e = L.cE[c].data() + row;
  const float* wst = L.cW[c].data() + row;
  const float* n = L.cN[c].data() + row;
  const float* s = L.cS[c].data() + row;
  if (Op == RowOp::Smooth)
    smoothKernel(mb, me, p, hs, L.x[c].data() + row, o, b, e, wst, n, s, L.sInv[c].data() + row);
  else
    residualKernel(mb,
      me,
      p,
      hs,
      L.r[c].data() + row,
      L.x[c].data() + row,
      o,
      b,
      e,
      wst,
      n,
      s,
      L.sDiag[c].data() + row);
}

// One symmetric red-black Gauss-Seidel sweep: colour first, then the other.
// On small grids the two half sweeps run as one pass over the rows, the other
// colour one row behind (its cells then see every update they would see after
// a full first half sweep), so each row is loaded once: same result, half the
// memory traffic. Large grids run each half sweep in parallel instead.
// fromZero: x is 0 on entry (the first sweep of a V-cycle leg).
void sweep(Level& L, int first, bool fromZero)
{
  auto half = [&](int j, int c)
  {
    if (fromZero && c == first)
      rowOp<RowOp::FirstSmooth>(L, j, c);
    else
      rowOp<RowOp::Smooth>(L, j, c);
  };
  if (parallel(L))
  {
    for (int colour : { first, first ^ 1 })
    {
#pragma omp parallel for schedule(static)
      for (int j = 0; j < L.h; ++j)
        half(j, colour);
    }
    return;
  }
  for (int j = 0; j < L.h; ++j)
  {
    half(j, first);
    if (j > 0)
      half(j - 1, first ^ 1);
  }
  if (L.h > 0)
    half(L.h - 1, first ^ 1);
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
  std::size_t depth = 0; // levels in use
  std::vector<double> delta, res, dir, q, z;
  std::vector<std::size_t> stack; // cells of the component being labelled
  std::vector<int> component;
  std::vector<std::size_t> members;
  std::vector<std::uint8_t> present;
  std::vector<float> coarseRow; // prolongation scratch

  void buildCoarse(const Level& fine, Level& coarse)
  {
    coarse.allocate((fine.w + 1) / 2, (fine.h + 1) / 2);
    for (int j = 0; j < fine.h; ++j)
    {
      for (int i = fine.rowBegin[j]; i < fine.rowEnd[j]; ++i)
      {
        const std::size_t k = fine.pad(i, j);
        if (!fine.unknown[k])
        {
          continue;
        }
        const std::size_t c = coarse.pad(i / 2, j / 2);
        coarse.unknown[c] = 1;
        // Galerkin P^T A P with piecewise-constant P: edges inside the block
        // cancel, edges leaving it stay. Aggregation makes the coarse operator
        // twice as stiff as a rediscretised one; halving it restores the size
        // of the coarse correction.
        double external = fine.diag[k];
        if ((i & 1) == 0)
          external -= fine.wE[k];
        else
          coarse.wE[c] += 0.5 * fine.wE[k];
        if ((i & 1) == 1)
          external -= fine.wE[k - 1];
        if ((j & 1) == 0)
          external -= fine.wN[k];
        else
          coarse.wN[c] += 0.5 * fine.wN[k];
        if ((j & 1) == 1)
          external -= fine.wN[k - fine.stride];
        coarse.diag[c] += 0.5 * external;
      }
    }
    coarse.finish();
  }

  void buildDense(Level& L)
  {
    std::vector<int>& index = component; // scratch: dense index per padded cell
    index.assign(L.unknown.size(), -1);
    L.denseCell.clear();
    for (int j = 0; j < L.h; ++j)
    {
      for (int i = 0; i < L.w; ++i)
      {
        if (L.unknown[L.pad(i, j)])
        {
          index[L.pad(i, j)] = static_cast<int>(L.denseCell.size());
          L.denseCell.push_back(static_cast<int>(L.split(i, j) * 2 + ((i + j) & 1)));
        }
      }
    }
    const int n = static_cast<int>(L.denseCell.size());
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
    for (std::size_t k = 0; k < L.unknown.size(); ++k)
    {
      const int a = index[k];
      if (a < 0)
      {
        continue;
      }
      A(a, a) = L.diag[k];
      if (L.wE[k] > 0.0)
      {
        const int e = index[k + 1];
        A(a, e) = A(e, a) = -L.wE[k];
      }
      if (L.wN[k] > 0.0)
      {
        const int e = index[k + L.stride];
        A(a, e) = A(e, a) = -L.wN[k];
      }
    }
    L.dense.compute(A);
  }

  // Approximately solves A x = b on level l (x and b in the split arrays).
  void vcycle(std::size_t l, int sweeps)
  {
    checkCancellation(); // a fine level of a whole terrain is a good part of a second
    Level& L = levels[l];
    if (l + 1 == depth)
    {
      Eigen::VectorXd& rhs = L.denseRhs;
      rhs.resize(static_cast<Eigen::Index>(L.denseCell.size()));
      for (std::size_t a = 0; a < L.denseCell.size(); ++a)
        rhs[static_cast<Eigen::Index>(a)] = L.b[L.denseCell[a] & 1][L.denseCell[a] >> 1];
      L.dense.solveInPlace(rhs);
      for (std::size_t a = 0; a < L.denseCell.size(); ++a)
        L.x[L.denseCell[a] & 1][L.denseCell[a] >> 1] =
          static_cast<float>(rhs[static_cast<Eigen::Index>(a)]);
      return;
    }
    for (int s = 0; s < sweeps; ++s)
      sweep(L, 0, s == 0);
      // The last half sweep (colour 1) left a zero residual on colour 1: only
      // colour 0 has one, a single cell per row of each 2x2 aggregate.
#pragma omp parallel for schedule(static) if (parallel(L))
    for (int j = 0; j < L.h; ++j)
      rowOp<RowOp::Residual>(L, j, 0);
    Level& C = levels[l + 1];
    const std::size_t hs = L.hs;
    // Restriction by coarse row, so threads never share an output cell. Rows
    // past the last (the frame) hold zeros.
#pragma omp parallel for schedule(static) if (parallel(L))
    for (int cj = 0; cj < C.h; ++cj)
    {
      // Fine rows 2 cj and 2 cj + 1 (split index 1 of padded rows 2 cj + 1 and
      // 2 cj + 2): r0[ci] and r1[ci] are aggregate ci's cells.
      const float* r0 = L.r[0].data() + rowMajor(1, 2 * cj + 1, hs);
      const float* r1 = r0 + hs;
      for (int c = 0; c < 2; ++c)
      {
        // Coarse cells of colour c in row cj: ci = 2 (m - 1) + p.
        const int p = (c + cj) & 1;
        float* cb = C.b[c].data() + C.splitRow(cj);
        for (int m = 1; m < C.hs; ++m)
        {
          const int ci = 2 * (m - 1) + p;
          cb[m] = ci < C.w ? r0[ci] + r1[ci] : 0.0f;
        }
      }
    }
    vcycle(l + 1, sweeps);
    // Prolongation: each cell of an aggregate gets its coarse value; cells
    // that are not unknowns (zero inverse diagonal) stay 0.
    // The coarse row is interleaved once for both fine rows of its aggregates.
    coarseRow.resize(static_cast<std::size_t>(C.w) + 1); // a count, for resize
#pragma omp parallel for schedule(static) if (parallel(L)) firstprivate(coarseRow)
    for (int cj = 0; cj < C.h; ++cj)
    {
      float* nat = coarseRow.data();
      const float* cx[2] = { C.x[cj & 1].data() + C.split(0, cj),
        C.x[(cj + 1) & 1].data() + C.split(0, cj) };
      for (int ci = 0; ci < C.w; ++ci)
        nat[ci] = cx[ci & 1][ci >> 1];
      nat[C.w] = 0.0f;
      for (int j = 2 * cj; j < std::min(2 * cj + 2, L.h); ++j)
      {
        const std::size_t row = rowMajor(0, j + 1, hs); // L.splitRow(j)
        for (int c = 0; c < 2; ++c)
        {
          float* __restrict x = L.x[c].data() + row;
          const float* __restrict inv = L.sInv[c].data() + row;
          for (int m = L.mBegin[j]; m < L.mEnd[j]; ++m)
            x[m] += inv[m] != 0.0f ? nat[m - 1] : 0.0f;
        }
      }
    }
    // Reverse colour order so the V-cycle is a symmetric preconditioner.
    for (int s = 0; s < sweeps; ++s)
      sweep(L, 1, false);
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
    if (levels.empty())
      levels.resize(1);
    depth = 1;
    Level& F = levels[0];
    F.allocate(width, height);
    const double wx = 1.0 / (cellX * cellX);
    const double wy = 1.0 / (cellY * cellY);
    // present: unknown or holding a value (0 on the frame).
    present.assign(F.unknown.size(), 0);
    for (int j = 0; j < height; ++j)
    {
      pollRow(j);
      const std::size_t g0 = rowMajor(0, j, width);
      for (int i = 0; i < width; ++i)
      {
        const std::size_t k = F.pad(i, j);
        F.unknown[k] = unknownIn[g0 + i] != 0;
        present[k] = F.unknown[k] || std::isfinite(u[g0 + i]);
      }
    }
    // Edge weights: an edge counts if it touches an unknown, both ends have a
    // value or are unknown, and its guidance is defined.
    const std::size_t s = F.stride;
    for (int j = 0; j < height; ++j)
    {
      pollRow(j);
      for (int i = 0; i < width; ++i)
      {
        const std::size_t k = F.pad(i, j);
        if (!present[k])
          continue;
        const std::size_t g = rowMajor(i, j, width);
        if ((F.unknown[k] || F.unknown[k + 1]) && present[k + 1] && edgeOk(g, 0))
        {
          if (F.unknown[k] && F.unknown[k + 1])
            F.wE[k] = wx;
          F.diag[k] += F.unknown[k] ? wx : 0.0;
          F.diag[k + 1] += F.unknown[k + 1] ? wx : 0.0;
        }
        if ((F.unknown[k] || F.unknown[k + s]) && present[k + s] && edgeOk(g, 1))
        {
          if (F.unknown[k] && F.unknown[k + s])
            F.wN[k] = wy;
          F.diag[k] += F.unknown[k] ? wy : 0.0;
          F.diag[k + s] += F.unknown[k + s] ? wy : 0.0;
        }
      }
    }
    // Components of unknowns with no Dirichlet edge (diag > couplings nowhere)
    // are singular: pin them (drop them from the unknowns).
    component.assign(F.unknown.size(), -1);
    for (std::size_t seed = 0; seed < F.unknown.size(); ++seed)
    {
      if (!F.unknown[seed] || component[seed] >= 0)
        continue;
      members.clear();
      bool anchored = false;
      stack.assign(1, seed);
      component[seed] = 1;
      while (!stack.empty())
      {
        pollCancellation();
        const std::size_t k = stack.back();
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
            stack.push_back(nb[d]);
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

  // Levels 1 .. depth - 1; levels past depth keep their storage for later calls.
  void buildHierarchy()
  {
    constexpr std::size_t denseLimit = 64;
    while (
      levels[depth - 1].count > denseLimit && (levels[depth - 1].w > 1 || levels[depth - 1].h > 1))
    {
      if (levels.size() == depth)
        levels.emplace_back();
      checkCancellation();
      buildCoarse(levels[depth - 1], levels[depth]);
      ++depth;
    }
    buildDense(levels[depth - 1]);
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
    // The residual-only restriction in vcycle needs a sweep.
    const int sweeps = std::max(options.smoothingSweeps, 1);
    // z = V-cycle(res), in single precision on the split layout: the CG
    // keeps res, z and the iterates in double, so only the preconditioner is
    // rounded; the flexible beta below tolerates that.
    auto precondition = [&]()
    {
#pragma omp parallel for schedule(static) if (parallel(F))
      for (int j = 0; j < F.h; ++j)
      {
        const double* rrow = res.data() + F.pad(-1, j);
        for (int c = 0; c < 2; ++c)
        {
          // Colour c cells: i = 2 (m - 1) + p, at rrow[i + 1].
          const int p = (c + j) & 1;
          float* b = F.b[c].data() + F.splitRow(j);
          for (int m = F.mBegin[j]; m < F.mEnd[j]; ++m)
            b[m] = static_cast<float>(rrow[2 * m - 1 + p]);
        }
      }
      vcycle(0, sweeps);
#pragma omp parallel for schedule(static) if (parallel(F))
      for (int j = 0; j < F.h; ++j)
      {
        double* zrow = z.data() + F.pad(-1, j);
        for (int c = 0; c < 2; ++c)
        {
          const int p = (c + j) & 1;
          const float* x = F.x[c].data() + F.splitRow(j);
          for (int m = F.mBegin[j]; m < F.mEnd[j]; ++m)
            zrow[2 * m - 1 + p] = x[m];
        }
      }
    };
    // rz = res . z, zq = z . q, and whether the estimated error max |z| is
    // small enough.
    auto examine = [&](double& rz, double& zq)
    {
      double s = 0.0, t = 0.0, e = 0.0;
      for (std::size_t k = 0; k < n; ++k)
      {
        s += res[k] * z[k];
        t += z[k] * q[k];
        e = std::max(e, std::abs(z[k]));
      }
      rz = s;
      zq = t;
      return options.errorTolerance > 0.0 && e <= options.errorTolerance;
    };
    precondition();
    double rz = 0.0, zq = 0.0;
    if (examine(rz, zq))
    {
      return;
    }
    dir = z;
    for (int it = 1; it <= options.maxIterations; ++it)
    {
      checkCancellation();
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
      if (examine(rzNew, zq))
      {
        break;
      }
      // Flexible (Polak-Ribiere) beta = z . (res - resOld) / rz, with
      // res - resOld = -alpha q: robust to the rounding of the preconditioner.
      const double beta = -alpha * zq / rz;
      rz = rzNew;
      for (std::size_t k = 0; k < n; ++k)
      {
        dir[k] = z[k] + beta * dir[k];
      }
    }
  }

  // With the fine level and the residual of u set up: solve for the correction
  // and add it to u's unknown cells.
  void solveAndApply(double* u, const PoissonOptions& options, PoissonStatistics& stats)
  {
    buildHierarchy();
    pcg(options, stats);
    const Level& F = levels[0];
    for (int j = 0; j < F.h; ++j)
    {
      for (int i = 0; i < F.w; ++i)
      {
        const std::size_t k = F.pad(i, j);
        if (F.unknown[k])
          u[rowMajor(i, j, F.w)] += delta[k];
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
    pollRow(j);
    for (int i = 0; i < width; ++i)
    {
      const std::size_t k = F.pad(i, j);
      if (!F.unknown[k])
        continue;
      const std::size_t g = rowMajor(i, j, width);
      double r = 0.0;
      // present is 0 on the frame, so the neighbour's guidance is read only
      // inside the grid.
      auto edge =
        [&](std::size_t kq, std::ptrdiff_t dg, const double* field, std::size_t gf, double sign)
      {
        if (!m.present[kq])
          return;
        const double wanted = field ? sign * field[gf] : 0.0;
        if (!std::isnan(wanted))
          r += (wanted - (u[g + dg] - u[g]));
      };
      const std::ptrdiff_t w = width;
      const std::size_t s = F.stride;
      edge(k + 1, 1, gx, g, 1.0);
      edge(k - 1, -1, gx, g - 1, -1.0);
      const double rx = r;
      r = 0.0;
      edge(k + s, w, gy, g, 1.0);
      edge(k - s, -w, gy, g - width, -1.0);
      // A delta = -(residual of the normal equations) with A = -L.
      m.res[k] = -(wx * rx + wy * r);
    }
  }
  m.solveAndApply(u, options, stats);
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
    pollRow(j);
    for (int i = 0; i < width; ++i)
    {
      const std::size_t k = F.pad(i, j);
      if (!F.unknown[k])
        continue;
      const std::size_t g = rowMajor(i, j, width);
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
  m.solveAndApply(u, options, stats);
  return stats;
}

} // namespace tsynth
