// Seeded randomness that does not depend on the order of the calls: each
// decision hashes (seed, stream, index) to its own number, so threads, backends
// and the order of a loop never change what a seed gives, and work split into
// tiles or redone in part can derive the same numbers from coordinates.
//
// The project's one scheme: every seeded choice goes through seededUniform or
// seededIndex, never a sequential engine (std::mt19937 and its distributions,
// whose results differ between standard libraries and depend on how many
// numbers were drawn before). The streams of a synthesis seed are listed here,
// so that no two kinds of decision share one.
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

// A seed of its own for part `index` of the work of kind `stream` under
// `seed` (a tile of a tiled synthesis): its decisions differ from every other
// part's, and follow from the part's place alone.
constexpr std::uint64_t derivedSeed(std::uint64_t seed, std::uint64_t stream, std::uint64_t index)
{
  return mixBits(mixBits(mixBits(seed) ^ stream) ^ index);
}

// An index in [0, n) for decision `index` of kind `stream` under `seed`; n > 0.
constexpr std::uint64_t seededIndex(std::uint64_t seed,
  std::uint64_t stream,
  std::uint64_t index,
  std::uint64_t n)
{
  const auto k =
    static_cast<std::uint64_t>(seededUniform(seed, stream, index) * static_cast<double>(n));
  return k < n ? k : n - 1;
}

// Streams of the synthesis seed (SynthesisOptions::seed, LandformFieldOptions::seed).
constexpr std::uint64_t kStreamGrid = 1;      // the fill grid's jitter
constexpr std::uint64_t kStreamFillOrder = 2; // ties in the best-first fill order
constexpr std::uint64_t kStreamChoice = 3;    // the choice among equally good candidates
constexpr std::uint64_t kStreamSites = 4;     // phases of the sites along features
constexpr std::uint64_t kStreamOutlet = 5;    // a valley network's outlet among near-ties
constexpr std::uint64_t kStreamTile = 6;      // a tile's own seed (tiled synthesis)

} // namespace tsynth
