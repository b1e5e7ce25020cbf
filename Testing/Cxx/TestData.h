// Paths to test data and scratch files shared by the C++ tests.
#pragma once

#include <algorithm>
#include <filesystem>
#include <string>
#include <unistd.h>
#include <vector>

namespace tsynth::test
{

inline std::filesystem::path sharedData()
{
  return std::filesystem::path(TSYNTH_SHARED_DATA);
}

inline std::filesystem::path bundledData()
{
  return std::filesystem::path(TSYNTH_BUNDLED_DATA);
}

// A real DEM by file name: the bundled copy in Data/dems when there is one, else the one in
// ../shared/data/dems (which a clone without ../shared lacks: see TSYNTH_SKIP_WITHOUT).
inline std::string realDem(const std::string& name)
{
  const std::filesystem::path bundled = bundledData() / "dems" / name;
  return (std::filesystem::exists(bundled) ? bundled : sharedData() / "dems" / name).string();
}

// Skips the running test when a file only ../shared has is absent, so that a clone without
// ../shared beside it still passes the tests that need nothing from there.
#define TSYNTH_SKIP_WITHOUT(path)                                                                  \
  if (!std::filesystem::exists(path))                                                              \
  GTEST_SKIP() << (path) << " is absent: ../shared/data is not beside the checkout"

// Every real DEM of the project (.png and .tif, sorted): the bundled ones, which
// must exist, and the shared ones, skipped when ../shared is absent.
inline std::vector<std::string> realDems()
{
  std::vector<std::string> out;
  for (const std::filesystem::path& dir : { bundledData() / "dems", sharedData() / "dems" })
  {
    if (!std::filesystem::is_directory(dir))
    {
      continue;
    }
    for (const auto& entry : std::filesystem::directory_iterator(dir))
    {
      const std::string ext = entry.path().extension().string();
      if (ext == ".png" || ext == ".tif")
      {
        out.push_back(entry.path().string());
      }
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

// A fresh scratch folder per test process, removed by the caller's fixture or left in /tmp.
inline std::filesystem::path scratchDir()
{
  static const std::filesystem::path dir = []
  {
    auto d = std::filesystem::temp_directory_path() / ("tsynth-test-" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}

} // namespace tsynth::test
