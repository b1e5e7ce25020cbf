// Tests of Kernels/Merging/Poisson.cxx.
// Poisson solvers: manufactured solutions on a square (DST and multigrid CG)
// and on an irregular mask, convergence order, and the corner cases.
#include "Core/Error.h"
#include "Merging/Poisson.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

using namespace tsynth;

namespace
{

// A surface that no low-order polynomial reproduces, in metres.
double surface(double x, double y)
{
  return 1500.0 + 300.0 * std::sin(0.013 * x + 0.4) * std::cos(0.021 * y) + 0.02 * x * y -
    0.001 * x * x;
}

std::vector<double> sampled(int w, int h, double cx, double cy)
{
  std::vector<double> u(static_cast<std::size_t>(w) * h);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
      u[static_cast<std::size_t>(j) * w + i] = surface(i * cx, j * cy);
  return u;
}

// Discrete 5-point Laplacian of u at interior cells (NaN on the border).
std::vector<double> discreteLaplacian(const std::vector<double>& u,
  int w,
  int h,
  double cx,
  double cy)
{
  std::vector<double> f(u.size(), std::numeric_limits<double>::quiet_NaN());
  for (int j = 1; j + 1 < h; ++j)
    for (int i = 1; i + 1 < w; ++i)
    {
      const std::size_t k = static_cast<std::size_t>(j) * w + i;
      f[k] = (u[k + 1] - 2.0 * u[k] + u[k - 1]) / (cx * cx) +
        (u[k + w] - 2.0 * u[k] + u[k - w]) / (cy * cy);
    }
  return f;
}

// A surface with the relief of real terrain (about 1 km from valley to peak over 30 km), so an
// error in metres reads against what a user would see.
double terrainSurface(double x, double y)
{
  return 1500.0 + 300.0 * std::sin(0.013 * x + 0.4) * std::cos(0.021 * y) +
    400.0 * std::sin(x / 4700.0) * std::cos(y / 6100.0) + 0.01 * (x - y);
}

// Largest difference in metres on the cells the solver had to find (the border is given).
double maxInteriorError(const std::vector<double>& u,
  const std::vector<double>& exact,
  int w,
  int h)
{
  double err = 0.0;
  for (int j = 1; j + 1 < h; ++j)
    for (int i = 1; i + 1 < w; ++i)
    {
      const std::size_t k = static_cast<std::size_t>(j) * w + i;
      err = std::max(err, std::abs(u[k] - exact[k]));
    }
  return err;
}

double maxRelativeError(const std::vector<double>& a, const std::vector<double>& b)
{
  double err = 0.0, scale = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k)
  {
    err = std::max(err, std::abs(a[k] - b[k]));
    scale = std::max(scale, std::abs(b[k]));
  }
  return err / scale;
}

// A millimetre: far below a DEM's vertical resolution, a thousand times what the solver reaches.
constexpr double kWholeTerrainToleranceMetres = 1e-3;

} // namespace

TEST(Poisson, DstManufacturedSolutionOnRectangle)
{
  for (const auto& size : { std::pair<int, int>{ 97, 97 }, { 98, 65 }, { 40, 130 } })
  {
    const int w = size.first, h = size.second;
    const double cx = 90.0, cy = 70.0; // anisotropic cells
    const std::vector<double> exact = sampled(w, h, cx, cy);
    const std::vector<double> f = discreteLaplacian(exact, w, h, cx, cy);
    std::vector<double> u(exact);
    for (int j = 1; j + 1 < h; ++j)
      for (int i = 1; i + 1 < w; ++i)
        u[static_cast<std::size_t>(j) * w + i] = 0.0; // forget the interior
    DstPoissonSolver solver(false);
    solver.solve(w, h, cx, cy, f.data(), u.data());
    EXPECT_LT(maxRelativeError(u, exact), 1e-9) << w << "x" << h;
    // The border was given exactly, so measure where the solver worked: within a millimetre
    // on a surface spanning 1e6 m.
    EXPECT_LT(maxInteriorError(u, exact, w, h), 1e-3) << w << "x" << h;
  }
}

TEST(Poisson, DstConvergesToTheContinuousSolutionAtSecondOrder)
{
  // Continuous Laplacian as right-hand side: the error must fall about 4x
  // when the cell size halves (the 5-point stencil is second order).
  auto error = [](int n)
  {
    const double h = 1000.0 / (n + 1);
    const int w = n + 2;
    std::vector<double> u(static_cast<std::size_t>(w) * w), f(u.size()), exact(u.size());
    const double a = 3.14159265358979323846 / 1000.0;
    for (int j = 0; j < w; ++j)
      for (int i = 0; i < w; ++i)
      {
        const std::size_t k = static_cast<std::size_t>(j) * w + i;
        exact[k] = 200.0 * std::sin(a * i * h) * std::sinh(a * j * h) +
          50.0 * std::sin(2 * a * i * h) * std::sin(3 * a * j * h);
        f[k] = -50.0 * 13.0 * a * a * std::sin(2 * a * i * h) * std::sin(3 * a * j * h);
        u[k] = (i == 0 || j == 0 || i == w - 1 || j == w - 1) ? exact[k] : 0.0;
      }
    DstPoissonSolver solver(false);
    solver.solve(w, w, h, h, f.data(), u.data());
    double e = 0.0;
    for (std::size_t k = 0; k < u.size(); ++k)
      e = std::max(e, std::abs(u[k] - exact[k]));
    return e;
  };
  const double e1 = error(31);
  const double e2 = error(63);
  EXPECT_GT(e1 / e2, 3.5);
  EXPECT_LT(e1 / e2, 4.5);
}

TEST(Poisson, MultigridManufacturedSolutionOnSquare)
{
  const int w = 130, h = 130;
  const double cx = 30.0, cy = 30.0;
  const std::vector<double> exact = sampled(w, h, cx, cy);
  const std::vector<double> f = discreteLaplacian(exact, w, h, cx, cy);
  std::vector<std::uint8_t> unknown(exact.size(), 0);
  std::vector<double> u(exact);
  for (int j = 1; j + 1 < h; ++j)
    for (int i = 1; i + 1 < w; ++i)
    {
      unknown[static_cast<std::size_t>(j) * w + i] = 1;
      u[static_cast<std::size_t>(j) * w + i] = 0.0;
    }
  MaskedPoissonSolver solver;
  const PoissonStatistics stats =
    solver.solveLaplacian(w, h, cx, cy, unknown.data(), f.data(), u.data());
  EXPECT_LT(maxRelativeError(u, exact), 1e-7);
  EXPECT_LT(stats.iterations, 30); // multigrid: iterations do not grow with size
  EXPECT_EQ(stats.unknowns, static_cast<std::size_t>((w - 2) * (h - 2)));
}

TEST(Poisson, MultigridManufacturedSolutionOnIrregularMask)
{
  // A disc with a notch and a hole, nodata (NaN) cells around part of it
  // (natural boundary there), Dirichlet values elsewhere.
  const int w = 150, h = 120;
  const double cx = 25.0, cy = 35.0;
  const std::vector<double> exact = sampled(w, h, cx, cy);
  std::vector<std::uint8_t> unknown(exact.size(), 0);
  std::vector<double> u(exact);
  std::vector<double> gx(exact.size(), 0.0), gy(exact.size(), 0.0);
  std::size_t count = 0;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
    {
      const std::size_t k = static_cast<std::size_t>(j) * w + i;
      const double dx = i - 70.0, dy = j - 60.0;
      const double r = std::sqrt(dx * dx + dy * dy);
      const bool inside = r < 50.0 && !(dx > 0 && std::abs(dy) < 6) && r > 8.0;
      if (inside)
      {
        unknown[k] = 1;
        u[k] = 0.0;
        ++count;
      }
      else if (dx < -30.0 && r < 60.0)
      {
        u[k] = std::numeric_limits<double>::quiet_NaN(); // nodata: no boundary value
      }
      if (i + 1 < w)
        gx[k] = exact[k + 1] - exact[k];
      if (j + 1 < h)
        gy[k] = exact[k + w] - exact[k];
    }
  // Gradient-domain form: guidance = the exact differences.
  MaskedPoissonSolver solver;
  std::vector<double> u1(u);
  const PoissonStatistics s1 =
    solver.solveGuided(w, h, cx, cy, unknown.data(), gx.data(), gy.data(), u1.data());
  EXPECT_EQ(s1.unknowns, count);
  EXPECT_EQ(s1.pinnedUnknowns, 0u);
  double err = 0.0, scale = 0.0;
  for (std::size_t k = 0; k < u1.size(); ++k)
  {
    if (!unknown[k])
      continue;
    err = std::max(err, std::abs(u1[k] - exact[k]));
    scale = std::max(scale, std::abs(exact[k]));
  }
  EXPECT_LT(err / scale, 1e-7);
  // Laplacian form on the same mask, Dirichlet cells only (no NaN), and a
  // solver reused from the previous problem.
  std::vector<double> u2(exact);
  for (std::size_t k = 0; k < u2.size(); ++k)
    if (unknown[k])
      u2[k] = 0.0;
  const std::vector<double> f = discreteLaplacian(exact, w, h, cx, cy);
  solver.solveLaplacian(w, h, cx, cy, unknown.data(), f.data(), u2.data());
  EXPECT_LT(maxRelativeError(u2, exact), 1e-7);
}

TEST(Poisson, StartThatFitsIsReturnedUnchanged)
{
  const int w = 40, h = 30;
  std::vector<double> u = sampled(w, h, 10.0, 10.0);
  std::vector<double> gx(u.size(), 0.0), gy(u.size(), 0.0);
  std::vector<std::uint8_t> unknown(u.size(), 0);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
    {
      const std::size_t k = static_cast<std::size_t>(j) * w + i;
      unknown[k] = i > 3 && j > 2 && i < 30;
      if (i + 1 < w)
        gx[k] = u[k + 1] - u[k];
      if (j + 1 < h)
        gy[k] = u[k + w] - u[k];
    }
  const std::vector<double> before(u);
  MaskedPoissonSolver solver;
  const PoissonStatistics s =
    solver.solveGuided(w, h, 10.0, 10.0, unknown.data(), gx.data(), gy.data(), u.data());
  EXPECT_EQ(s.iterations, 0);
  EXPECT_EQ(u, before);
}

TEST(Poisson, UnanchoredComponentsKeepTheirValues)
{
  // Unknowns surrounded by NaN only (no Dirichlet neighbour): pinned.
  const int w = 10, h = 10;
  std::vector<double> u(w * h, std::numeric_limits<double>::quiet_NaN());
  std::vector<std::uint8_t> unknown(w * h, 0);
  for (int j = 2; j < 6; ++j)
    for (int i = 2; i < 6; ++i)
    {
      unknown[j * w + i] = 1;
      u[j * w + i] = 5.0 + i;
    }
  std::vector<double> gx(w * h, 1.0), gy(w * h, 0.0);
  MaskedPoissonSolver solver;
  const PoissonStatistics s =
    solver.solveGuided(w, h, 1.0, 1.0, unknown.data(), gx.data(), gy.data(), u.data());
  EXPECT_EQ(s.pinnedUnknowns, 16u);
  EXPECT_EQ(s.unknowns, 0u);
  EXPECT_EQ(u[3 * w + 4], 9.0);
  // Empty problems do nothing.
  EXPECT_EQ(solver.solveGuided(0, 0, 1.0, 1.0, nullptr, nullptr, nullptr, nullptr).unknowns, 0u);
}

TEST(Poisson, WholeTerrain1024)
{
  // The whole-terrain case: 1024 x 1024 cells of 30 m, Dirichlet frame, manufactured from a
  // surface with a kilometre of relief, so the tolerance is in metres of terrain.
  const int n = 1024;
  const double c = 30.0;
  std::vector<double> exact(static_cast<std::size_t>(n) * n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      exact[static_cast<std::size_t>(j) * n + i] = terrainSurface(i * c, j * c);
  const std::vector<double> f = discreteLaplacian(exact, n, n, c, c);
  std::vector<std::uint8_t> unknown(exact.size(), 0);
  std::vector<double> u(exact);
  for (int j = 1; j + 1 < n; ++j)
    for (int i = 1; i + 1 < n; ++i)
    {
      unknown[static_cast<std::size_t>(j) * n + i] = 1;
      u[static_cast<std::size_t>(j) * n + i] = 0.0;
    }
  MaskedPoissonSolver solver;
  const PoissonStatistics stats =
    solver.solveLaplacian(n, n, c, c, unknown.data(), f.data(), u.data());
  const double err = maxInteriorError(u, exact, n, n);
  std::printf("WholeTerrain1024: max error %.3g m after %d iterations\n", err, stats.iterations);
  EXPECT_LT(err, kWholeTerrainToleranceMetres);
  EXPECT_LT(stats.iterations, 40);
}
