// A monotone priority queue of 64-bit keys (Ahuja, Mehlhorn, Orlin & Tarjan
// 1990): a key pushed is never below the last key popped, which holds for the
// flood order of Priority-Flood. Keys live in 65 buckets by the highest bit in
// which they differ from the last key popped; each key moves to a lower bucket
// at most 64 times, so a push or pop costs O(1) amortised plus a scan of one
// bucket, and the memory is contiguous (no heap of pointers to chase).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace tsynth
{

class MonotoneRadixHeap
{
public:
  bool empty() const { return size_ == 0; }
  std::size_t size() const { return size_; }

  // `key` must be >= the last key popped (and >= any `bound` given to hasKeyBelow).
  void push(std::uint64_t key)
  {
    buckets_[bucketOf(key)].push_back(key);
    ++size_;
  }

  // Removes and returns the smallest key. The heap must not be empty.
  std::uint64_t pop()
  {
    if (buckets_[0].empty())
    {
      advance(smallestOf(firstBucket()));
    }
    const std::uint64_t key = buckets_[0].back();
    buckets_[0].pop_back();
    --size_;
    return key;
  }

  // True if some key is strictly below `bound`, which must be >= the last key
  // popped. If true, pop before the next push (the smallest key counts as
  // popped); if false, `bound` counts as popped (the caller takes its own item
  // at `bound` first), so later pushes must not be below it.
  bool hasKeyBelow(std::uint64_t bound)
  {
    if (size_ == 0)
    {
      return false;
    }
    if (!buckets_[0].empty())
    {
      return last_ < bound;
    }
    const std::size_t b = firstBucket();
    // Keys in bucket b agree with last_ above bit b - 1 and have that bit set.
    const std::uint64_t lowest = b >= kKeyBits
      ? (std::uint64_t{ 1 } << (kKeyBits - 1))
      : ((last_ >> b) << b) | (std::uint64_t{ 1 } << (b - 1));
    if (bound <= lowest)
    {
      return false;
    }
    const std::uint64_t smallest = smallestOf(b);
    advance(std::min(smallest, bound));
    return smallest < bound;
  }

private:
  static constexpr std::size_t kKeyBits = 64;

  std::size_t bucketOf(std::uint64_t key) const
  {
    return key == last_ ? 0 : kKeyBits - static_cast<std::size_t>(__builtin_clzll(key ^ last_));
  }

  std::size_t firstBucket() const
  {
    std::size_t b = 0;
    while (buckets_[b].empty())
    {
      ++b;
    }
    return b;
  }

  std::uint64_t smallestOf(std::size_t b) const
  {
    return *std::min_element(buckets_[b].begin(), buckets_[b].end());
  }

  // Makes `pivot` (<= every key, >= last_) the reference and redistributes the
  // first non-empty bucket, whose keys all move to lower buckets.
  void advance(std::uint64_t pivot)
  {
    const std::size_t b = firstBucket();
    last_ = pivot;
    std::vector<std::uint64_t> moving;
    moving.swap(buckets_[b]);
    for (const std::uint64_t key : moving)
    {
      buckets_[bucketOf(key)].push_back(key);
    }
    if (buckets_[b].empty())
    {
      moving.clear();
      moving.swap(buckets_[b]); // keep the capacity for the next time
    }
  }

  std::array<std::vector<std::uint64_t>, kKeyBits + 1> buckets_;
  std::uint64_t last_ = 0;
  std::size_t size_ = 0;
};

} // namespace tsynth
