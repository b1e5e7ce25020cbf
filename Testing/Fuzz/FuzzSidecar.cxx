// Fuzz target: the JSON sidecar parser (readSidecar) on any bytes, and the
// sidecar it accepts written back and read again to the same values.
#include "Core/Error.h"
#include "Core/Sidecar.h"
#include "FuzzSupport.h"

#include <cstdlib>

namespace
{

bool same(const std::optional<double>& a, const std::optional<double>& b)
{
  return a.has_value() == b.has_value() && (!a || *a == *b);
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const std::string path = tsynth::fuzz::writeScratch("sidecar.json", data, size);
  tsynth::Sidecar first;
  try
  {
    first = tsynth::readSidecar(path);
  }
  catch (const tsynth::Error&)
  {
    return 0; // bad input, told as it should be
  }
  // What was accepted survives a write and a read unchanged.
  tsynth::writeSidecar(path, first);
  const tsynth::Sidecar second = tsynth::readSidecar(path);
  if (first.zUnit != second.zUnit || !same(first.cellX, second.cellX) ||
    !same(first.cellY, second.cellY) || !same(first.zMin, second.zMin) ||
    !same(first.zMax, second.zMax) || !same(first.nodata, second.nodata))
  {
    std::abort();
  }
  return 0;
}
