#include "PoissonEditing.h"

#include "Core/Cancellation.h"

#include "../Core/Error.h"

#include <limits>
#include <string>

namespace tsynth
{
namespace
{

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void checkSize(std::size_t got, std::size_t want, const char* what)
{
  if (got != want)
  {
    throw Error(std::string("The ") + what + " has " + std::to_string(got) + " values for " +
      std::to_string(want) + " cells: give one per cell.");
  }
}

// Solves the masked cells of `destination` (valid ones only) for the wanted
// differences along edges.
PoissonEditResult solve(const Heightfield& destination,
  std::vector<std::uint8_t> unknown,
  const std::vector<double>& gx,
  const std::vector<double>& gy,
  double tolerance)
{
  PoissonEditResult r;
  r.terrain = destination;
  std::vector<double> u(destination.size());
  for (std::size_t k = 0; k < destination.size(); ++k)
  {
    u[k] = destination.isValid(k) ? static_cast<double>(destination.z[k]) : kNaN;
    unknown[k] = unknown[k] != 0 && destination.isValid(k) ? 1 : 0;
    r.solvedCells += unknown[k];
  }
  if (r.solvedCells == 0)
  {
    return r;
  }
  PoissonOptions options;
  options.tolerance = tolerance;
  options.maxIterations = kPoissonEditMaxIterations;
  MaskedPoissonSolver solver;
  r.statistics = solver.solveGuided(destination.width,
    destination.height,
    destination.cellX,
    destination.cellY,
    unknown.data(),
    gx.data(),
    gy.data(),
    u.data(),
    options);
  for (std::size_t k = 0; k < destination.size(); ++k)
  {
    if (unknown[k] != 0)
    {
      r.terrain.z[k] = static_cast<float>(u[k]);
    }
  }
  return r;
}

} // namespace

PoissonEditResult seamlessClone(const Heightfield& destination,
  const Heightfield& source,
  const std::vector<std::uint8_t>* mask,
  double tolerance)
{
  const int w = destination.width;
  const int h = destination.height;
  if (source.width != w || source.height != h)
  {
    throw Error("The source must lie on the destination's grid (" + std::to_string(w) + " x " +
      std::to_string(h) + " cells); resample it first.");
  }
  std::vector<std::uint8_t> unknown(destination.size(), 0);
  if (mask != nullptr)
  {
    checkSize(mask->size(), destination.size(), "mask");
    unknown = *mask;
  }
  else
  {
    for (std::size_t k = 0; k < source.size(); ++k)
    {
      unknown[k] = source.isValid(k) ? 1 : 0;
    }
  }
  std::vector<double> gx(destination.size(), kNaN);
  std::vector<double> gy(destination.size(), kNaN);
  for (int j = 0; j < h; ++j)
  {
    if (j % kCancellationBandRows == 0)
    {
      checkCancellation();
    }
    for (int i = 0; i < w; ++i)
    {
      const std::size_t k = destination.index(i, j);
      if (i + 1 < w && source.isValid(i, j) && source.isValid(i + 1, j))
      {
        gx[k] = static_cast<double>(source.at(i + 1, j)) - source.at(i, j);
      }
      if (j + 1 < h && source.isValid(i, j) && source.isValid(i, j + 1))
      {
        gy[k] = static_cast<double>(source.at(i, j + 1)) - source.at(i, j);
      }
    }
  }
  return solve(destination, std::move(unknown), gx, gy, tolerance);
}

PoissonEditResult integrateSlopes(const Heightfield& destination,
  const std::vector<double>& slopeX,
  const std::vector<double>& slopeY,
  const std::vector<std::uint8_t>& mask,
  double tolerance)
{
  checkSize(slopeX.size(), destination.size(), "slope field");
  checkSize(slopeY.size(), destination.size(), "slope field");
  checkSize(mask.size(), destination.size(), "mask");
  const int w = destination.width;
  const int h = destination.height;
  std::vector<double> gx(destination.size(), kNaN);
  std::vector<double> gy(destination.size(), kNaN);
  for (int j = 0; j < h; ++j)
  {
    if (j % kCancellationBandRows == 0)
    {
      checkCancellation();
    }
    for (int i = 0; i < w; ++i)
    {
      const std::size_t k = destination.index(i, j);
      if (i + 1 < w)
      {
        gx[k] = 0.5 * (slopeX[k] + slopeX[destination.index(i + 1, j)]) * destination.cellX;
      }
      if (j + 1 < h)
      {
        gy[k] = 0.5 * (slopeY[k] + slopeY[destination.index(i, j + 1)]) * destination.cellY;
      }
    }
  }
  return solve(destination, mask, gx, gy, tolerance);
}

const std::vector<OptionRow>& poissonEditOptionRows()
{
  static const std::vector<OptionRow> rows = {
    choiceRow("Mode",
      "",
      static_cast<int>(PoissonEditMode::SeamlessClone),
      choicesOf(kPoissonEditModeWords),
      { "Seamless clone", "Guidance field" }),
    numberRow("Tolerance",
      "",
      OptionType::Real,
      PoissonOptions{}.tolerance,
      kMinEditTolerance,
      kMaxEditTolerance),
  };
  return rows;
}

} // namespace tsynth
