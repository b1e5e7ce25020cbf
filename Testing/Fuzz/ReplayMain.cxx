// The normal build's driver of a fuzz target: runs LLVMFuzzerTestOneInput once
// on every file of the folders (or files) given, so every input a fuzzer ever
// crashed on stays a regression test (CTest fuzz.replay.<target>). A crash
// fails the test; so does an empty corpus, which would test nothing.
#include "FuzzSupport.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <vector>

namespace fs = std::filesystem;

namespace
{

std::vector<fs::path> inputsOf(const fs::path& p)
{
  std::vector<fs::path> files;
  if (fs::is_directory(p))
  {
    for (const auto& entry : fs::directory_iterator(p))
    {
      if (entry.is_regular_file())
      {
        files.push_back(entry.path());
      }
    }
  }
  else if (fs::is_regular_file(p))
  {
    files.push_back(p);
  }
  std::sort(files.begin(), files.end()); // the same order on every machine
  return files;
}

} // namespace

int main(int argc, char** argv)
{
  std::size_t runs = 0;
  for (int a = 1; a < argc; ++a)
  {
    for (const fs::path& file : inputsOf(argv[a]))
    {
      std::ifstream in(file, std::ios::binary);
      const std::vector<char> bytes(
        (std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      std::cout << "replay " << file.filename().string() << " (" << bytes.size() << " bytes)"
                << std::endl;
      LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
      ++runs;
    }
  }
  if (runs == 0)
  {
    std::cerr << "No input to replay: give corpus folders or files." << std::endl;
    return 1;
  }
  std::cout << runs << " inputs replayed without a crash" << std::endl;
  return 0;
}
