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

#include <algorithm>
#include <array>
#include <cmath>

namespace tsynth
{
namespace
{

// The mesh keeps to about this many cells a side: more adds nothing at 1600 pixels.
constexpr int kMaxMeshSide = 1000;
// Colour stops along the height range: enough that the ramp shows no bands.
constexpr int kColourStops = 20;
// The surface takes a little ambient light, so shadowed slopes keep their colour, and no
// shine, which bare rock and soil lack.
constexpr double kAmbient = 0.15;
constexpr double kDiffuse = 0.9;
// The sun stands this far to the right of the camera and this high: the slopes facing the
// viewer are lit from the side, so relief reads clearly.
constexpr double kSunRightOfViewDeg = 70.0;
constexpr double kSunElevationDeg = 40.0;
// A moderate lens, and the fitted terrain brought closer to fill the frame.
constexpr double kViewAngleDeg = 30.0;
constexpr double kFillZoom = 1.35;
// Antialiasing samples per pixel.
constexpr int kMultiSamples = 8;
constexpr double kRadiansPerDegree = kPi / 180.0;

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

// Nodata drawn flat at the lowest height, so the mesh stays finite.
void flattenNodata(Heightfield& hf, const HeightRange& range)
{
  for (std::size_t k = 0; k < hf.size(); ++k)
  {
    if (!hf.isValid(k))
    {
      hf.z[k] = range.min;
    }
  }
  hf.valid.clear();
}

// The surface, raised by the exaggeration and coloured by height.
vtkNew<vtkActor> terrainActor(const Heightfield& hf, const HeightRange& range, double exaggeration)
{
  vtkNew<vtkImageData> image;
  heightfieldToImage(hf, image);
  vtkNew<vtkImageDataGeometryFilter> surface;
  surface->SetInputData(image);
  vtkNew<vtkWarpScalar> warp;
  warp->SetInputConnection(surface->GetOutputPort());
  warp->SetScaleFactor(exaggeration);
  warp->UseNormalOn();
  warp->SetNormal(0.0, 0.0, 1.0);
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputConnection(warp->GetOutputPort());
  normals->SplittingOff();

  vtkNew<vtkColorTransferFunction> colours;
  const double span = range.max > range.min ? range.max - range.min : 1.0;
  for (int s = 0; s <= kColourStops; ++s)
  {
    const double t = static_cast<double>(s) / kColourStops;
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
  actor->GetProperty()->SetAmbient(kAmbient);
  actor->GetProperty()->SetDiffuse(kDiffuse);
  actor->GetProperty()->SetSpecular(0.0);
  return actor;
}

// The point a direction (azimuth clockwise from north, elevation) reaches at `distance` from
// `centre`.
std::array<double, 3> towards(const double centre[3],
  double azimuthDeg,
  double elevationDeg,
  double distance)
{
  const double az = azimuthDeg * kRadiansPerDegree;
  const double el = elevationDeg * kRadiansPerDegree;
  return { centre[0] + distance * std::cos(el) * std::sin(az),
    centre[1] + distance * std::cos(el) * std::cos(az),
    centre[2] + distance * std::sin(el) };
}

// One distant sun, to the camera's right (kSunRightOfViewDeg) and kSunElevationDeg high.
void addSun(vtkRenderer* renderer, const double centre[3], const Render3DOptions& options)
{
  renderer->AutomaticLightCreationOff();
  vtkNew<vtkLight> sun;
  sun->SetLightTypeToSceneLight();
  sun->SetPositional(false);
  sun->SetFocalPoint(centre);
  const std::array<double, 3> position =
    towards(centre, options.viewAzimuthDeg + kSunRightOfViewDeg, kSunElevationDeg, 1.0);
  sun->SetPosition(position.data());
  sun->SetIntensity(1.0);
  renderer->AddLight(sun);
}

// The camera looking at `centre` from the options' direction, the terrain filling the frame.
void aimCamera(vtkRenderer* renderer,
  const double centre[3],
  double distance,
  const Render3DOptions& options)
{
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetFocalPoint(centre);
  const std::array<double, 3> position =
    towards(centre, options.viewAzimuthDeg, options.viewElevationDeg, distance);
  camera->SetPosition(position.data());
  camera->SetViewUp(0.0, 0.0, 1.0);
  camera->SetViewAngle(kViewAngleDeg);
  // Fit the terrain's bounding sphere from this direction, then fill the frame.
  renderer->ResetCamera();
  camera->Zoom(kFillZoom);
  renderer->ResetCameraClippingRange();
}

// The window's pixels as a PNG at `pngPath`, complete or not at all.
void writeWindowPng(vtkRenderWindow* window, const std::string& pngPath)
{
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

} // namespace

void render3D(const Heightfield& input, const std::string& pngPath, const Render3DOptions& options)
{
  Heightfield hf = subsampled(input, kMaxMeshSide);
  const HeightRange range = computeHeightRange(hf);
  flattenNodata(hf, range);

  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(terrainActor(hf, range, options.exaggeration));
  renderer->GradientBackgroundOn();
  renderer->SetBackground(0.93, 0.95, 0.98);  // a pale sky overhead ...
  renderer->SetBackground2(0.55, 0.70, 0.88); // ... bluer towards the top of the frame
  const double centre[3] = { 0.5 * (hf.width - 1) * hf.cellX,
    0.5 * (hf.height - 1) * hf.cellY,
    range.min * options.exaggeration };
  addSun(renderer, centre, options);
  aimCamera(renderer, centre, std::max(hf.width * hf.cellX, hf.height * hf.cellY), options);

  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(kMultiSamples);
  window->SetSize(options.width, options.height);
  window->AddRenderer(renderer);
  window->Render();
  writeWindowPng(window, pngPath);
}

} // namespace tsynth

// The module's entry (Render3D.h): looked up by name with dlsym.
extern "C" __attribute__((visibility("default"))) tsynth::Render3DFunction tsynthRender3D()
{
  return &tsynth::render3D;
}
