// The Terrain Poisson Solver (Filters/vtkTerrainPoissonSolver.h) gives what its
// kernel (Kernels/Merging/PoissonEditing.h) gives, in both modes, touches only
// the masked cells, and refuses a guidance field without a mask.
#include "FilterTesting.h"
#include "vtkTerrainPoissonSolver.h"

#include "Merging/PoissonEditing.h"

#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkUnsignedCharArray.h>

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace tsynth
{
namespace
{

using test::pointValues;

constexpr double kTolerance = 1e-10; // the solver's own default

// A disc of `radius` cells round the grid's middle.
std::vector<std::uint8_t> disc(const Heightfield& hf, double radius)
{
  std::vector<std::uint8_t> mask(hf.size(), 0);
  for (int j = 0; j < hf.height; ++j)
  {
    for (int i = 0; i < hf.width; ++i)
    {
      const double dx = i - 0.5 * hf.width, dy = j - 0.5 * hf.height;
      mask[hf.index(i, j)] = dx * dx + dy * dy <= radius * radius ? 1 : 0;
    }
  }
  return mask;
}

void addMask(vtkImageData* image, const std::vector<std::uint8_t>& mask)
{
  vtkNew<vtkUnsignedCharArray> a;
  a->SetName(vtkTerrainPoissonSolver::kDefaultMaskArray);
  a->SetNumberOfTuples(static_cast<vtkIdType>(mask.size()));
  for (std::size_t k = 0; k < mask.size(); ++k)
  {
    a->SetValue(static_cast<vtkIdType>(k), mask[k]);
  }
  image->GetPointData()->AddArray(a);
}

} // namespace

TEST(TerrainPoissonSolverFilter, SeamlessCloneIsTheKernelsAndLeavesTheRestAlone)
{
  const Heightfield destination = test::roughDem(48, 40, false);
  Heightfield source = test::roughDem(48, 40, false);
  for (int j = 0; j < source.height; ++j)
  {
    for (int i = 0; i < source.width; ++i)
    {
      source.at(i, j) = 300.0f + 0.5f * source.at(j % source.width, i % source.height);
    }
  }
  const std::vector<std::uint8_t> mask = disc(destination, 12.0);
  auto sourceImage = test::imageOf(source);
  addMask(sourceImage, mask);
  vtkNew<vtkTerrainPoissonSolver> filter;
  test::FilterErrors errors(filter);
  filter->SetInputData(0, test::imageOf(destination));
  filter->SetInputData(1, sourceImage);
  filter->Update();
  ASSERT_TRUE(errors.text.empty()) << errors.text;

  const PoissonEditResult kernel = seamlessClone(destination, source, &mask, kTolerance);
  const std::vector<double> heights = pointValues(filter->GetOutput(), "Elevation");
  ASSERT_EQ(heights.size(), destination.size());
  std::size_t changed = 0;
  for (std::size_t k = 0; k < heights.size(); ++k)
  {
    ASSERT_EQ(heights[k], kernel.terrain.z[k]) << "cell " << k;
    if (mask[k] == 0)
    {
      ASSERT_EQ(heights[k], destination.z[k]) << "outside the mask, cell " << k;
    }
    changed += heights[k] != destination.z[k] ? 1 : 0;
  }
  EXPECT_GT(changed, kernel.solvedCells / 2) << "the source's slopes came in";
  vtkFieldData* fields = filter->GetOutput()->GetFieldData();
  EXPECT_EQ(fields->GetArray("Iterations")->GetComponent(0, 0), kernel.statistics.iterations);
  EXPECT_LE(fields->GetArray("RelativeResidual")->GetComponent(0, 0), kTolerance);
}

TEST(TerrainPoissonSolverFilter, AGuidanceFieldIsIntegratedAsTheKernelDoes)
{
  // A bowl on a tilted plane, z = 1000 + 0.1 x - 0.05 y + 2e-4 ((x - 600)^2 + (y - 600)^2)
  // (metres), whose heights inside a disc are lost (0) and come back from its slopes: an
  // edge's difference is the mean of its ends' slopes times the cell, exact for a quadratic.
  Heightfield destination(40, 40);
  destination.cellX = destination.cellY = 30.0;
  Heightfield bowl = destination;
  std::vector<double> slopeX(destination.size());
  std::vector<double> slopeY(destination.size());
  constexpr double kCurvature = 2e-4; // 1/m
  for (int j = 0; j < destination.height; ++j)
  {
    for (int i = 0; i < destination.width; ++i)
    {
      const double x = i * destination.cellX, y = j * destination.cellY;
      const std::size_t k = destination.index(i, j);
      bowl.z[k] = static_cast<float>(1000.0 + 0.1 * x - 0.05 * y +
        kCurvature * ((x - 600.0) * (x - 600.0) + (y - 600.0) * (y - 600.0)));
      slopeX[k] = 0.1 + 2.0 * kCurvature * (x - 600.0);
      slopeY[k] = -0.05 + 2.0 * kCurvature * (y - 600.0);
    }
  }
  const std::vector<std::uint8_t> mask = disc(destination, 10.0);
  for (std::size_t k = 0; k < destination.size(); ++k)
  {
    destination.z[k] = mask[k] != 0 ? 0.0f : bowl.z[k];
  }
  auto image = test::imageOf(destination);
  addMask(image, mask);
  vtkNew<vtkDoubleArray> gradient;
  gradient->SetName(vtkTerrainPoissonSolver::kDefaultGradientArray);
  gradient->SetNumberOfComponents(2);
  gradient->SetNumberOfTuples(static_cast<vtkIdType>(destination.size()));
  for (std::size_t k = 0; k < destination.size(); ++k)
  {
    gradient->SetTuple2(static_cast<vtkIdType>(k), slopeX[k], slopeY[k]);
  }
  image->GetPointData()->AddArray(gradient);
  vtkNew<vtkTerrainPoissonSolver> filter;
  test::FilterErrors errors(filter);
  filter->SetInputData(0, image);
  filter->SetMode(vtkTerrainPoissonSolver::GUIDANCE_FIELD);
  filter->Update();
  ASSERT_TRUE(errors.text.empty()) << errors.text;
  const PoissonEditResult kernel = integrateSlopes(destination, slopeX, slopeY, mask, kTolerance);
  const std::vector<double> heights = pointValues(filter->GetOutput(), "Elevation");
  ASSERT_EQ(heights.size(), destination.size());
  for (std::size_t k = 0; k < heights.size(); ++k)
  {
    ASSERT_EQ(heights[k], kernel.terrain.z[k]) << "cell " << k;
    ASSERT_NEAR(heights[k], bowl.z[k], 1e-3) << "the bowl, back from its slopes, cell " << k;
  }
}

TEST(TerrainPoissonSolverFilter, AGuidanceFieldWithoutAMaskOrACloneWithoutASourceFails)
{
  const Heightfield destination = test::roughDem(24, 24, false);
  vtkNew<vtkTerrainPoissonSolver> guided;
  test::FilterErrors guidedErrors(guided);
  guided->SetInputData(0, test::imageOf(destination));
  guided->SetMode(vtkTerrainPoissonSolver::GUIDANCE_FIELD);
  guided->SetMaskArray("");
  guided->Update();
  EXPECT_NE(guidedErrors.text.find("name it in MaskArray"), std::string::npos) << guidedErrors.text;

  vtkNew<vtkTerrainPoissonSolver> clone;
  test::FilterErrors cloneErrors(clone);
  clone->SetInputData(0, test::imageOf(destination));
  clone->Update();
  EXPECT_NE(cloneErrors.text.find("needs a source heightfield"), std::string::npos)
    << cloneErrors.text;
}

} // namespace tsynth
