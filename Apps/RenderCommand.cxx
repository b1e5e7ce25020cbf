// tsynth render: a hillshade map tinted by height, or an oblique lit 3D view.
#include "Commands.h"

#include "CliSupport.h"
#include "CommandLine.h"
#include "Render3D.h"

#include "Analysis/Hillshade.h"
#include "Analysis/ReliefImage.h"
#include "Core/Error.h"
#include "Core/FileRoles.h"
#include "Core/HeightfieldIO.h"

#include <climits>
#include <cstdlib>
#include <dlfcn.h>
#include <iostream>
#include <optional>
#include <string>
#include <unistd.h>
#include <vector>

namespace tsynth::cli
{
namespace
{

// The 3D view's picture size: smaller shows nothing; larger than most
// OpenGL implementations' largest framebuffer.
constexpr int kMinPictureSide = 16;
constexpr int kMaxPictureSide = 8192;

const char* const kRenderHelp = R"(Usage: tsynth render DEM -o OUT.png [--3d] [options]

Writes a picture of the terrain: a multi-directional hillshade tinted by height,
one pixel per cell. With --3d, an oblique lit 3D view instead (needs an X display;
without one tsynth re-runs itself under xvfb-run).

  -o, --output PNG       the picture to write (.png)
  --3d                   oblique 3D view
  --grey                 the hillshade alone, in grey (the map only)
  --exaggeration F       vertical exaggeration, from 0.001 to 1000 (default 1 for the map,
                         2 for --3d)
  --altitude DEG         sun elevation for the map, from 0 to 90 (default 45)
  --azimuth DEG          single light from this direction, clockwise from north, 0 to 360
  --size WxH             3D picture size in pixels (default 1600x1000)
)";

// Re-runs this command under xvfb-run when there is no X display for --3d.
// True if an X server answers at $DISPLAY. Asked through libX11 (loaded here, as VTK's
// window would load it): VTK's own attempt aborts the process when nothing answers.
bool displayAnswers()
{
  void* x11 = dlopen("libX11.so.6", RTLD_NOW | RTLD_LOCAL);
  if (x11 == nullptr)
  {
    return false;
  }
  using OpenDisplay = void* (*)(const char*);
  using CloseDisplay = int (*)(void*);
  const auto open = reinterpret_cast<OpenDisplay>(dlsym(x11, "XOpenDisplay"));
  const auto close = reinterpret_cast<CloseDisplay>(dlsym(x11, "XCloseDisplay"));
  void* connection = open != nullptr && close != nullptr ? open(nullptr) : nullptr;
  if (connection != nullptr)
  {
    close(connection);
  }
  dlclose(x11);
  return connection != nullptr;
}

// Where the module is: the library folder beside the program's (the build tree mirrors the
// installed one, CMakeLists.txt), named by path. A bare name would do through tsynth-main's
// RUNPATH, but not under AddressSanitizer, whose dlopen interceptor searches only the system's
// folders; the bare name stays as the last resort.
std::vector<std::string> render3DModuleCandidates()
{
  std::vector<std::string> candidates;
  char self[PATH_MAX];
  const ssize_t length = readlink("/proc/self/exe", self, sizeof(self) - 1);
  if (length > 0)
  {
    const std::string program(self, static_cast<std::size_t>(length));
    candidates.push_back(program.substr(0, program.rfind('/') + 1) + TSYNTH_LIBDIR_FROM_BINDIR +
      "/" + kRender3DModule);
  }
  candidates.emplace_back(kRender3DModule);
  return candidates;
}

// render3D from its module (Render3D.h); the module stays loaded until the program ends.
Render3DFunction loadRender3D()
{
  std::string why = "no reason given";
  for (const std::string& candidate : render3DModuleCandidates())
  {
    void* module = dlopen(candidate.c_str(), RTLD_NOW | RTLD_LOCAL);
    const auto entry = module == nullptr
      ? nullptr
      : reinterpret_cast<Render3DFunction (*)()>(dlsym(module, kRender3DEntry));
    if (entry != nullptr)
    {
      return entry();
    }
    if (const char* error = dlerror(); error != nullptr && candidate.front() == '/')
    {
      why = error; // the path beside the program says most about what is wrong
    }
  }
  throw Error(std::string("--3d needs ") + kRender3DModule + ", which did not load (" + why +
    "); reinstall TerrainSynthesis.");
}

void ensureDisplay(int argc, char** argv)
{
  const char* display = std::getenv("DISPLAY");
  if (display != nullptr && *display != '\0')
  {
    if (displayAnswers())
    {
      return;
    }
    if (std::getenv("TSYNTH_UNDER_XVFB") != nullptr)
    {
      throw Error("--3d needs an X display and xvfb-run did not provide one.");
    }
    std::cerr << "tsynth: warning: no X server answers at DISPLAY=" << display
              << "; rendering under xvfb-run instead.\n";
    unsetenv("DISPLAY");
  }
  if (std::getenv("TSYNTH_UNDER_XVFB") != nullptr)
  {
    throw Error("--3d needs an X display and xvfb-run did not provide one.");
  }
  setenv("TSYNTH_UNDER_XVFB", "1", 1);
  std::vector<char*> command = { const_cast<char*>("xvfb-run"),
    const_cast<char*>("-a"),
    const_cast<char*>("-s"),
    const_cast<char*>("-screen 0 1920x1200x24") };
  for (int k = 0; k < argc; ++k)
  {
    command.push_back(argv[k]);
  }
  command.push_back(nullptr);
  execvp("xvfb-run", command.data());
  throw Error("--3d needs an X display: set DISPLAY or install xvfb (xvfb-run).");
}

// Everything `tsynth render` was asked to draw, checked.
struct RenderArguments
{
  std::string input;
  std::string output;
  ReadOptions read;
  bool threeD = false;
  bool grey = false;
  std::optional<double> exaggeration;
  std::optional<double> altitude;
  std::optional<double> azimuth;
  Render3DOptions view;
};

// --size WxH of the 3D picture, within the picture sides any OpenGL draws.
void takePictureSize(const std::string& size, Render3DOptions& view)
{
  const auto sides = parseSides(size);
  const auto inRange = [](int v) { return v >= kMinPictureSide && v <= kMaxPictureSide; };
  if (!sides || !inRange(sides->first) || !inRange(sides->second))
  {
    throw UsageError("--size expects WxH between " + std::to_string(kMinPictureSide) + " and " +
      std::to_string(kMaxPictureSide) + " pixels, e.g. 1600x1000, not \"" + size + "\".");
  }
  view.width = sides->first;
  view.height = sides->second;
}

RenderArguments parseRenderArguments(std::vector<std::string> args)
{
  CommandLine cl(std::move(args));
  RenderArguments a;
  const std::optional<std::string> output = cl.take("--output", "-o");
  a.threeD = cl.takeFlag("--3d");
  a.grey = cl.takeFlag("--grey");
  const std::vector<OptionRow>& rows = hillshadeOptionRows();
  a.exaggeration = takeRowNumber(cl, optionRow(rows, "ZFactor"));
  a.altitude = takeRowNumber(cl, optionRow(rows, "Altitude"));
  a.azimuth = takeRowNumber(cl, optionRow(rows, "Azimuth"));
  const std::optional<std::string> size = cl.take("--size");
  a.read = takeReadOptions(cl);
  a.input = oneInput(cl, "render");
  if (!output)
  {
    throw UsageError("tsynth render needs an output picture: -o OUT.png.");
  }
  a.output = *output;
  if (!hasExtension(a.output, ".png"))
  {
    throw UsageError("The picture must be a .png file, not " + a.output + ".");
  }
  if (size && !a.threeD)
  {
    throw UsageError("--size applies to the 3D view (--3d); the map has one pixel per cell.");
  }
  if (a.grey && a.threeD)
  {
    throw UsageError("--grey shades the map; the 3D view has its own colours.");
  }
  if ((a.altitude || a.azimuth) && a.threeD)
  {
    throw UsageError("--altitude and --azimuth light the map; the 3D view has its own lights.");
  }
  if (size)
  {
    takePictureSize(*size, a.view);
  }
  return a;
}

// The map: a hillshade tinted by height (or grey), one pixel per cell.
void drawMap(const Heightfield& hf, const RenderArguments& a)
{
  HillshadeOptions shading;
  shading.zFactor = a.exaggeration.value_or(shading.zFactor);
  shading.altitudeDeg = a.altitude.value_or(shading.altitudeDeg);
  if (a.azimuth)
  {
    shading.multidirectional = false;
    shading.azimuthDeg = *a.azimuth;
  }
  const ShadedRelief relief = computeHillshade(hf, shading);
  writeRgbPng(a.output,
    hf.width,
    hf.height,
    a.grey ? renderGreyRelief(hf, relief) : renderRelief(hf, relief));
}

} // namespace

int runRender(std::vector<std::string> args, int argc, char** argv)
{
  if (wantsHelp(args))
  {
    std::cout << kRenderHelp << kReadOptionsHelp;
    return 0;
  }
  RenderArguments a = parseRenderArguments(std::move(args));
  FileRoles files;
  files.input(a.input, "the DEM", a.read.useSidecar);
  files.output(a.output, "-o", FileRoles::Content::Other);
  files.check();

  const Heightfield hf = readDem(a.input, a.read);
  if (a.threeD)
  {
    ensureDisplay(argc, argv);
    a.view.exaggeration = a.exaggeration.value_or(a.view.exaggeration);
    loadRender3D()(hf, a.output, a.view);
  }
  else
  {
    drawMap(hf, a);
  }
  std::cout << "Wrote " << a.output << "\n";
  return 0;
}

} // namespace tsynth::cli
