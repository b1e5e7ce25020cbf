// The Terrain Hillshade filter (Filters/vtkTerrainHillshade.h): its kernel's
// shading, nodata kept, and a refused volume.
#include "FilterTesting.h"
#include "TerrainImageConversion.h"
#include "TestData.h"
#include "vtkTerrainHillshade.h"

#include "Analysis/Hillshade.h"
#include "Core/Error.h"

#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

TEST(Filters, HillshadeMatchesTheKernelAndKeepsNodata)
{
  tsynth::Heightfield hf(20, 10);
  hf.cellX = 30.0;
  hf.cellY = 60.0;
  for (int j = 0; j < hf.height; ++j)
  {
    for (int i = 0; i < hf.width; ++i)
    {
      hf.at(i, j) = static_cast<float>(100.0 * std::sin(0.3 * i) + 5.0 * j);
    }
  }
  hf.at(7, 4) = std::numeric_limits<float>::quiet_NaN();
  tsynth::normaliseMask(hf);
  vtkNew<vtkImageData> image;
  tsynth::heightfieldToImage(hf, image);

  vtkNew<vtkTerrainHillshade> shade;
  shade->SetInputData(image);
  shade->SetAltitude(30.0);
  shade->Update();
  vtkImageData* out = shade->GetOutput();
  vtkDataArray* h = out->GetPointData()->GetArray("Hillshade");
  vtkDataArray* s = out->GetPointData()->GetArray("Slope");
  ASSERT_NE(h, nullptr);
  ASSERT_NE(s, nullptr);
  ASSERT_NE(out->GetPointData()->GetArray("Valid"), nullptr);
  EXPECT_STREQ(out->GetPointData()->GetScalars()->GetName(), "Hillshade");

  tsynth::HillshadeOptions o;
  o.altitudeDeg = 30.0;
  const auto expected = tsynth::computeHillshade(hf, o);
  for (vtkIdType k = 0; k < h->GetNumberOfTuples(); ++k)
  {
    const auto kk = static_cast<std::size_t>(k);
    if (std::isnan(expected.shade[kk]))
    {
      EXPECT_TRUE(std::isnan(h->GetComponent(k, 0)));
      continue;
    }
    EXPECT_FLOAT_EQ(static_cast<float>(h->GetComponent(k, 0)), expected.shade[kk]);
    EXPECT_FLOAT_EQ(static_cast<float>(s->GetComponent(k, 0)), expected.slopeDeg[kk]);
  }
  EXPECT_TRUE(std::isnan(h->GetComponent(static_cast<vtkIdType>(hf.index(7, 4)), 0)));
}

TEST(Filters, HillshadeRejectsAThreeDimensionalImage)
{
  vtkNew<vtkImageData> volume;
  volume->SetDimensions(4, 4, 4);
  volume->AllocateScalars(VTK_FLOAT, 1);
  volume->GetPointData()->GetScalars()->SetName("Elevation");
  vtkNew<vtkTerrainHillshade> shade;
  tsynth::test::FilterErrors errors(shade);
  shade->SetInputData(volume);
  shade->Update();
  EXPECT_FALSE(errors.text.empty());
}
