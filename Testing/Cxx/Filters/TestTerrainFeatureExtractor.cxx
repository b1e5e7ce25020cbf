// The Terrain Feature Extractor (Filters/vtkTerrainFeatureExtractor.h): its
// tree in the image's frame.
#include "TestData.h"
#include "vtkTerrainFeatureExtractor.h"
#include "vtkTerrainReader.h"

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPolyData.h>

#include <gtest/gtest.h>

TEST(Filters, FeatureExtractorOffsetsPointsByTheImageOrigin)
{
  vtkNew<vtkTerrainReader> reader;
  reader->SetFileName((tsynth::test::bundledData() / "dems" / "colorado.png").string().c_str());
  reader->Update();
  vtkNew<vtkImageData> shifted;
  shifted->ShallowCopy(reader->GetOutput());
  shifted->SetOrigin(5000.0, -3000.0, 0.0);
  vtkNew<vtkTerrainFeatureExtractor> features;
  features->SetInputData(shifted);
  features->Update();
  vtkPolyData* tree = features->GetOutput(0);
  ASSERT_GT(tree->GetNumberOfPoints(), 100);
  double bounds[6];
  tree->GetBounds(bounds);
  EXPECT_GE(bounds[0], 5000.0);
  EXPECT_LE(bounds[1], 5000.0 + 647 * 90.0);
  EXPECT_GE(bounds[2], -3000.0);
  EXPECT_LE(bounds[3], -3000.0 + 647 * 90.0);
  EXPECT_GT(features->GetOutput(1)->GetNumberOfPoints(), 100); // control points
}
