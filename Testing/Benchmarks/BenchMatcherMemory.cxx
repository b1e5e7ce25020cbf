// What the dense matcher (Kernels/Matching/DenseSearch.h) holds, part by part,
// and how long it takes to build: the memory a large synthesis cannot tile
// away, since every tile searches the same exemplars. By default the five
// DEMs of the README's 4096^2 run (in ../shared/data), at its patch size.
//   tsynth_bench_matcher_memory [--patch P] [DEM ...]
#include "BenchUtilities.h"
#include "Core/HeightfieldIO.h"
#include "Matching/DenseSearch.h"

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace
{

// The patch size the README's 4096^2 run from five exemplars settles on.
constexpr int kDefaultPatch = 80;

template<class Vector>
double megabytes(const Vector& v)
{
  return static_cast<double>(v.capacity() * sizeof(typename Vector::value_type)) / 1048576.0;
}

struct Parts
{
  double fullZ = 0, fullValid = 0, landformZ = 0, landformValid = 0, blockMeans = 0,
         windowValid = 0, offsetValid = 0;
  double total() const
  {
    return fullZ + fullValid + landformZ + landformValid + blockMeans + windowValid + offsetValid;
  }
};

Parts measure(const tsynth::DenseMatcher& matcher)
{
  Parts p;
  for (const auto& o : matcher.oriented())
  {
    p.fullZ += megabytes(o.full.z);
    p.fullValid += megabytes(o.full.valid);
    p.landformZ += megabytes(o.landform.z);
    p.landformValid += megabytes(o.landform.valid);
    p.blockMeans +=
      megabytes(o.coarse) + megabytes(o.pairs) + megabytes(o.quads) + megabytes(o.landformBlocks);
    p.windowValid += megabytes(o.fullValid);
    p.offsetValid += megabytes(o.coarseValid) + megabytes(o.groupValid);
  }
  return p;
}

} // namespace

int main(int argc, char** argv)
{
  tsynth::DenseOptions options;
  options.patchSize = kDefaultPatch;
  std::vector<std::string> paths;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (arg == "--patch" && i + 1 < argc)
    {
      options.patchSize = std::atoi(argv[++i]);
    }
    else
    {
      paths.push_back(arg);
    }
  }
  if (paths.empty())
  {
    for (const char* name :
      { "colorado", "alaska", "appalachians", "himalaya-everest", "andes-chile" })
    {
      paths.push_back(std::string(TSYNTH_SHARED_DATA) + "/dems/" + name + ".png");
    }
  }
  try
  {
    std::vector<tsynth::Heightfield> exemplars;
    std::vector<const tsynth::Heightfield*> pointers;
    exemplars.reserve(paths.size());
    for (const auto& path : paths)
    {
      exemplars.push_back(tsynth::readHeightfield(path));
      pointers.push_back(&exemplars.back());
    }
    Parts parts;
    std::size_t oriented = 0;
    const double seconds = tsynth::bench::bestSeconds(1,
      [&]
      {
        const tsynth::DenseMatcher matcher(pointers, options);
        parts = measure(matcher);
        oriented = matcher.oriented().size();
      });
    std::printf("%zu exemplars, patch %d: %zu oriented exemplars, built in %.2f s\n",
      exemplars.size(),
      options.patchSize,
      oriented,
      seconds);
    std::printf("  full heights        %6.0f MB\n", parts.fullZ);
    std::printf("  full validity       %6.0f MB\n", parts.fullValid);
    std::printf("  landform heights    %6.0f MB\n", parts.landformZ);
    std::printf("  landform validity   %6.0f MB\n", parts.landformValid);
    std::printf(
      "  block means         %6.0f MB (coarse, pairs, quads, landform)\n", parts.blockMeans);
    std::printf("  valid windows       %6.0f MB (per full offset)\n", parts.windowValid);
    std::printf(
      "  valid offsets       %6.0f MB (coarse offsets and their runs)\n", parts.offsetValid);
    std::printf("  total               %6.0f MB\n", parts.total());
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
