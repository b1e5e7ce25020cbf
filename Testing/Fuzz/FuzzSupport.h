// What the fuzz targets share: a byte reader over the input, a scratch folder
// of the process for the readers that take a path, and the entry point's name.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace tsynth::fuzz
{

// Takes bytes off the front of the input; past its end every read gives 0.
class Bytes
{
public:
  Bytes(const std::uint8_t* data, std::size_t size)
    : data_(data)
    , size_(size)
  {
  }
  std::uint8_t byte() { return pos_ < size_ ? data_[pos_++] : 0; }
  // A whole number from lo to hi (inclusive) out of one byte.
  int inRange(int lo, int hi) { return lo + byte() % (hi - lo + 1); }
  std::size_t left() const { return size_ - pos_; }
  const std::uint8_t* rest() const { return data_ + pos_; }
  void skip(std::size_t n) { pos_ += n < left() ? n : left(); }

private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

// A folder of this process's own under the system's temporary folder, removed
// at exit, so that two fuzzers (or a fuzzer and the replay test) never share files.
inline const std::filesystem::path& scratchDir()
{
  static const std::filesystem::path dir = []
  {
    std::filesystem::path d = std::filesystem::temp_directory_path() /
      ("tsynth-fuzz-" + std::to_string(static_cast<long>(::getpid())));
    std::filesystem::create_directories(d);
    std::atexit([] { std::filesystem::remove_all(scratchDir()); });
    return d;
  }();
  return dir;
}

// Writes bytes to scratchDir()/name (replacing it) and returns the path.
inline std::string writeScratch(const std::string& name, const std::uint8_t* data, std::size_t size)
{
  const std::string path = (scratchDir() / name).string();
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

inline void removeScratch(const std::string& name)
{
  std::error_code ec;
  std::filesystem::remove(scratchDir() / name, ec);
}

} // namespace tsynth::fuzz
