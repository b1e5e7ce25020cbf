// Paths to test data and scratch files shared by the C++ tests.
#pragma once

#include <filesystem>
#include <string>
#include <unistd.h>

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

inline std::string sharedDem(const std::string& name)
{
  return (sharedData() / "dems" / name).string();
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
