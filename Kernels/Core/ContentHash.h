// A 64-bit hash of bytes, eight at a time through SplitMix64's mix (Random.h):
// content keys (the exemplar cache's entries, a synthesis request) and
// checksums. A collision needs about 2^32 different contents, not a flipped bit.
#pragma once

#include "Random.h"

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <vector>

namespace tsynth
{

class ContentHasher
{
public:
  void bytes(const void* data, std::size_t n)
  {
    const auto* p = static_cast<const unsigned char*>(data);
    std::size_t k = 0;
    for (; k + sizeof(std::uint64_t) <= n; k += sizeof(std::uint64_t))
    {
      std::uint64_t w = 0;
      std::memcpy(&w, p + k, sizeof w);
      h_ = mixBits(h_ ^ w);
    }
    std::uint64_t tail = n; // the length too, so "ab" + "" differs from "a" + "b"
    if (n > k) // memcpy may not be given the null data() of an empty vector, even for 0 bytes
    {
      std::memcpy(&tail, p + k, n - k);
    }
    h_ = mixBits(h_ ^ tail ^ (static_cast<std::uint64_t>(n) << 56));
  }
  template<class T>
  void value(const T& v)
  {
    static_assert(std::is_arithmetic_v<T> || std::is_enum_v<T>);
    bytes(&v, sizeof v);
  }
  template<class T>
  void values(const std::vector<T>& v)
  {
    static_assert(std::is_arithmetic_v<T>);
    bytes(v.data(), v.size() * sizeof(T));
  }
  std::uint64_t digest() const { return h_; }

private:
  std::uint64_t h_ = 0;
};

// The code that computes what is keyed: a hash of the bytes of the file this
// function was loaded from (the kernels library, or a static executable), read
// once; 0 if it cannot be read, and then nothing keyed by it may be reused.
std::uint64_t codeHash();

} // namespace tsynth
