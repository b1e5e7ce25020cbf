// Seeded randomness that does not depend on the order of the calls: each
// decision hashes (seed, stream, index) to its own number, so threads, backends
// and the order of a loop never change what a seed gives.
#pragma once

#include <cstdint>

namespace tsynth
{

// SplitMix64's finaliser (Steele, Lea and Flood 2014): a bijective mix whose
// outputs pass the usual tests of randomness.
constexpr std::uint64_t mixBits(std::uint64_t x)
{
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

// A number in [0, 1) for decision `index` of kind `stream` under `seed`.
constexpr double seededUniform(std::uint64_t seed, std::uint64_t stream, std::uint64_t index)
{
  const std::uint64_t h = mixBits(mixBits(mixBits(seed) ^ stream) ^ index);
  return static_cast<double>(h >> 11) * (1.0 / 9007199254740992.0); // 53 bits
}

} // namespace tsynth
