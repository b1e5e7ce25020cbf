// tsynth, the program users run: a launcher that puts synth's start-up
// settings in the environment (RuntimeSettings.h) and then becomes
// tsynth-main, the command line itself (tsynth.cxx), found beside it. The
// same process (same pid, arguments and signals), loaded once with the
// settings in place. tsynth-main loaded 168 libraries (VTK, GDAL and theirs)
// in 0.14-0.16 s here; when it set the settings itself and re-ran, every
// synth paid that twice (0.30-0.32 s to fail on a missing exemplar, against
// 0.14-0.16 s with the settings already set). Nothing else happens here: this
// program links no library of the project's but the settings.
#include "RuntimeSettings.h"

#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstring>
#include <string>
#include <unistd.h>

namespace
{

// The command line program's file name, in the launcher's own folder.
constexpr const char* kCommandLineProgram = "tsynth-main";

// The folder this program's file is in (symbolic links followed), with a
// trailing slash; empty if it cannot be read.
std::string ownFolder()
{
  char path[PATH_MAX];
  const ssize_t length = readlink("/proc/self/exe", path, sizeof(path) - 1);
  if (length <= 0)
  {
    return {};
  }
  const std::string self(path, static_cast<std::size_t>(length));
  return self.substr(0, self.rfind('/') + 1);
}

} // namespace

int main(int argc, char** argv)
{
  if (argc > 1 && std::strcmp(argv[1], "synth") == 0)
  {
    tsynth::cli::setSynthRuntimeSettings();
  }
  const std::string program = ownFolder() + kCommandLineProgram;
  execv(program.c_str(), argv); // returns only on failure
  std::fprintf(stderr,
    "tsynth: cannot start %s (%s); reinstall TerrainSynthesis.\n",
    program.c_str(),
    std::strerror(errno));
  return 1;
}
