#include "Render3D.h"

#include "TerrainImageConversion.h"

#include "Analysis/ReliefImage.h"
#include "Core/Constants.h"
#include "Core/Error.h"
#include "Core/OutputFile.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkColorTransferFunction.h>
#include <vtkImageData.h>
#include <vtkImageDataGeometryFilter.h>
#include <vtkLight.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataNormals.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkWarpScalar.h>
#include <vtkWindowToImageFilter.h>

#include <cmath>

namespace tsynth
{
namespace
{

// Keeps the mesh to about 1000 cells a side: more adds nothing at 1600 pixels.
Heightfield subsampled(const Heightfield& hf, int maxSide)
{
  const int step = std::max(1, (std::max(hf.width, hf.height) + maxSide - 1) / maxSide);
  if (step == 1)
  {
    return hf;
  }
  Heightfield out((hf.width + step - 1) / step, (hf.height + step - 1) / step);
  out.cellX = hf.cellX * step;
  out.cellY = hf.cellY * step;
  if (hf.hasMask())
  {
    out.valid.assign(out.size(), 1);
  }
  for (int j = 0; j < out.height; ++j)
  {
    for (int i = 0; i < out.width; ++i)
    {
      out.at(i, j) = hf.at(i * step, j * step);
      if (hf.hasMask())
      {
        out.valid[out.index(i, j)] = hf.isValid(i * step, j * step) ? 1 : 0;
      }
    }
  }
  return out;
}

} // namespace

void render3D(const Heightfield& input, const std::string& pngPath, const Render3DOptions& options)
{
  Heightfield hf = subsampled(input, 1000);
  const HeightRange range = computeHeightRange(hf);
  // Nodata is drawn flat at the lowest height so the mesh stays finite.
  for (std::size_t k = 0; k < hf.size(); ++k)
  {
    if (!hf.isValid(k))
    {
      hf.z[k] = range.min;
    }
  }
  hf.valid.clear();

  vtkNew<vtkImageData> image;
  heightfieldToImage(hf, image);
  vtkNew<vtkImageDataGeometryFilter> surface;
  surface->SetInputData(image);
  vtkNew<vtkWarpScalar> warp;
  warp->SetInputConnection(surface->GetOutputPort());
  warp->SetScaleFactor(options.exaggeration);
  warp->UseNormalOn();
  warp->SetNormal(0.0, 0.0, 1.0);
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputConnection(warp->GetOutputPort());
  normals->SplittingOff();

  vtkNew<vtkColorTransferFunction> colours;
  const double span = range.max > range.min ? range.max - range.min : 1.0;
  for (int s = 0; s <= 20; ++s)
  {
    const double t = s / 20.0;
    const auto c = terrainColour(t);
    colours->AddRGBPoint(range.min + t * span, c[0], c[1], c[2]);
  }
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(normals->GetOutputPort());
  mapper->SetLookupTable(colours);
  mapper->SetScalarRange(range.min, range.min + span);
  mapper->SetScalarModeToUsePointFieldData();
  mapper->SelectColorArray(kElevationArray);
  mapper->ScalarVisibilityOn();
  mapper->InterpolateScalarsBeforeMappingOn();

  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetAmbient(0.15);
  actor->GetProperty()->SetDiffuse(0.9);
  actor->GetProperty()->SetSpecular(0.0);

  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  renderer->GradientBackgroundOn();
  renderer->SetBackground(0.93, 0.95, 0.98);
  renderer->SetBackground2(0.55, 0.70, 0.88);
  renderer->AutomaticLightCreationOff();
  vtkNew<vtkLight> sun;
  sun->SetLightTypeToSceneLight();
  sun->SetPositional(false);
  const double width = hf.width * hf.cellX;
  const double depth = hf.height * hf.cellY;
  const double centre[3] = { 0.5 * (hf.width - 1) * hf.cellX,
    0.5 * (hf.height - 1) * hf.cellY,
    range.min * options.exaggeration };
  // Sun 70 degrees to the right of the camera and 40 degrees high: the slopes
  // facing the viewer are lit from the side, so relief reads clearly.
  constexpr double kRad = kPi / 180.0;
  const double sunAz = (options.viewAzimuthDeg + 70.0) * kRad;
  const double sunEl = 40.0 * kRad;
  sun->SetFocalPoint(centre);
  sun->SetPosition(centre[0] + std::cos(sunEl) * std::sin(sunAz),
    centre[1] + std::cos(sunEl) * std::cos(sunAz),
    centre[2] + std::sin(sunEl));
  sun->SetIntensity(1.0);
  renderer->AddLight(sun);

  vtkCamera* camera = renderer->GetActiveCamera();
  const double az = options.viewAzimuthDeg * kRad;
  const double el = options.viewElevationDeg * kRad;
  const double distance = std::max(width, depth);
  camera->SetFocalPoint(centre);
  camera->SetPosition(centre[0] + distance * std::cos(el) * std::sin(az),
    centre[1] + distance * std::cos(el) * std::cos(az),
    centre[2] + distance * std::sin(el));
  camera->SetViewUp(0.0, 0.0, 1.0);
  camera->SetViewAngle(30.0);
  // Fit the terrain's bounding sphere from this direction, then fill the frame.
  renderer->ResetCamera();
  camera->Zoom(1.35);
  renderer->ResetCameraClippingRange();

  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(8);
  window->SetSize(options.width, options.height);
  window->AddRenderer(renderer);
  window->Render();

  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->ReadFrontBufferOff();
  grab->Update();

  tsynth::OutputFile file(pngPath);
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputConnection(grab->GetOutputPort());
  writer->SetFileName(file.temporaryPath().c_str());
  writer->Write();
  if (writer->GetErrorCode() != 0)
  {
    throw Error("Cannot write " + pngPath + ".");
  }
  file.commit();
}

} // namespace tsynth
