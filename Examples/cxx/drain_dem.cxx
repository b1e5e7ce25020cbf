// Reads a DEM, breaches its depressions and writes the result, with the pit
// counts and the flow at the outlet that drains the most: the kernels of an
// installed TerrainSynthesis, found with find_package(TerrainSynthesis).
//   drain_dem DEM OUT.tif
#include "Core/Error.h"
#include "Core/HeightfieldIO.h"
#include "Hydrology/Flow.h"
#include "Hydrology/PitRemoval.h"

#include <algorithm>
#include <iostream>

int main(int argc, char** argv)
{
  if (argc != 3)
  {
    std::cerr << "usage: drain_dem DEM OUT.tif\n";
    return 2;
  }
  try
  {
    const tsynth::Heightfield dem = tsynth::readHeightfield(argv[1]);
    tsynth::PitRemovalOptions options; // breaching, as Scott & Dodgson chose
    const tsynth::PitRemovalResult drained = tsynth::removePits(dem, options);
    const std::vector<std::uint32_t> flow = tsynth::flowAccumulation(
      tsynth::flowDirections(drained.dem), dem.width, dem.height);
    tsynth::writeHeightfield(argv[2], drained.dem);
    std::cout << "pits before " << tsynth::countPits(dem) << ", after "
              << tsynth::countPits(drained.dem) << "; " << drained.loweredCells
              << " cells lowered; largest outlet drains "
              << *std::max_element(flow.begin(), flow.end()) << " cells\n";
    return 0;
  }
  catch (const tsynth::Error& e)
  {
    std::cerr << "drain_dem: " << e.what() << "\n";
    return 1;
  }
}
