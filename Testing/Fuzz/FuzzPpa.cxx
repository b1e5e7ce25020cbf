// Fuzz target: PPA feature extraction (ridges and valleys) on small
// heightfields. The first bytes give the width and height (2..64), the cell
// size, the profile length and whether significance is tested; then each cell
// takes two bytes: a code byte (0: nodata, 1: NaN left valid, 2: +inf, 3: -inf,
// else a height) and a height byte.
#include "Core/Error.h"
#include "Features/Ppa.h"
#include "FuzzSupport.h"

#include <cmath>
#include <limits>

namespace
{

constexpr int kMinSide = 2;
constexpr int kMaxSide = 64;
constexpr int kMaxHalfProfile = 8;
// Cell sizes 0.5 .. 128 m in powers of two.
constexpr int kMaxCellExponent = 7;

float heightOf(std::uint8_t code, std::uint8_t value)
{
  switch (code)
  {
    case 1:
      return std::numeric_limits<float>::quiet_NaN();
    case 2:
      return std::numeric_limits<float>::infinity();
    case 3:
      return -std::numeric_limits<float>::infinity();
    default:
      // The two bytes as a 16-bit height in 1/16 m: -1984 to 2048 m.
      return static_cast<float>((static_cast<int>(code) << 8 | value) - 32768) / 16.0f;
  }
}

tsynth::Heightfield decodeField(tsynth::fuzz::Bytes& in)
{
  tsynth::Heightfield hf(in.inRange(kMinSide, kMaxSide), in.inRange(kMinSide, kMaxSide));
  hf.cellX = std::ldexp(1.0, in.inRange(-1, kMaxCellExponent));
  hf.cellY = std::ldexp(1.0, in.inRange(-1, kMaxCellExponent));
  hf.valid.assign(hf.size(), 1);
  for (std::size_t k = 0; k < hf.size(); ++k)
  {
    const std::uint8_t code = in.byte();
    const std::uint8_t value = in.byte();
    if (code == 0)
    {
      hf.valid[k] = 0;
      hf.z[k] = std::numeric_limits<float>::quiet_NaN();
      continue;
    }
    hf.z[k] = heightOf(code, value);
  }
  return hf;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  tsynth::fuzz::Bytes in(data, size);
  tsynth::PpaOptions options;
  options.halfProfileLength = in.inRange(1, kMaxHalfProfile);
  options.significance = in.byte() % 2 == 0 ? 0.0 : options.significance;
  options.presmoothSigma = 0.5 * in.inRange(0, 4);
  const tsynth::Heightfield hf = decodeField(in);
  for (tsynth::FeatureType type : { tsynth::FeatureType::Ridge, tsynth::FeatureType::Valley })
  {
    try
    {
      tsynth::extractFeatures(hf, type, options);
    }
    catch (const tsynth::Error&)
    {
      // Bad input, told as it should be.
    }
  }
  return 0;
}
