// Helpers shared by the priority floods (Flow.cxx: filling, Breach.cxx:
// breaching and the hybrid): sortable keys and one-float steps.
#pragma once

#include <cstdint>
#include <cstring>
#include <limits>

namespace tsynth
{

// Flood keys: the height's bits made to sort as unsigned integers in the high
// half (negative floats reversed), the cell index in the low half, so keys
// order by height and then by index.
inline std::uint64_t floodKey(float z, std::uint32_t cell)
{
  std::uint32_t bits = 0;
  std::memcpy(&bits, &z, sizeof bits);
  constexpr std::uint32_t kSign = 0x80000000u;
  bits = (bits & kSign) != 0 ? ~bits : (bits | kSign);
  return (static_cast<std::uint64_t>(bits) << 32) | cell;
}

inline std::uint32_t cellOfKey(std::uint64_t key)
{
  return static_cast<std::uint32_t>(key);
}

// std::nextafter(z, +infinity) for finite z, without the library call: the
// next float up is the bit pattern one step away from zero for positive z and
// towards zero for negative z (-0 and +0 both step to the smallest positive).
inline float raisedAbove(float z)
{
  if (z == 0.0f)
  {
    return std::numeric_limits<float>::denorm_min();
  }
  std::uint32_t bits = 0;
  std::memcpy(&bits, &z, sizeof bits);
  bits = z > 0.0f ? bits + 1 : bits - 1;
  std::memcpy(&z, &bits, sizeof bits);
  return z;
}

// std::nextafter(z, -infinity) for finite z, the mirror of raisedAbove.
inline float loweredBelow(float z)
{
  if (z == 0.0f)
  {
    return -std::numeric_limits<float>::denorm_min();
  }
  std::uint32_t bits = 0;
  std::memcpy(&bits, &z, sizeof bits);
  bits = z > 0.0f ? bits - 1 : bits + 1;
  std::memcpy(&z, &bits, sizeof bits);
  return z;
}

} // namespace tsynth
