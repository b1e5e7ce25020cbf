// Tests of Kernels/Hydrology/RadixHeap.h.
#include "Hydrology/RadixHeap.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <functional>
#include <queue>
#include <random>
#include <vector>

using namespace tsynth;

TEST(RadixHeap, PopsInTheSameOrderAsAStandardPriorityQueue)
{
  // Monotone use as in the flood: each push is above the last key popped; the
  // bound test (hasKeyBelow) is interleaved as the pit queue does.
  std::mt19937_64 rng(7);
  MonotoneRadixHeap heap;
  std::priority_queue<std::uint64_t, std::vector<std::uint64_t>, std::greater<>> reference;
  std::uint64_t last = 0;
  // Steps of 0 to 2^44 (no overflow in 200000 steps), mostly small: every bucket is used.
  auto step_ = [](std::mt19937_64& r) { return r() >> (20 + r() % 44); };
  for (int step = 0; step < 200000; ++step)
  {
    const int action = static_cast<int>(rng() % 5);
    if (action < 3 || reference.empty())
    {
      const std::uint64_t key = last + step_(rng);
      heap.push(key);
      reference.push(key);
    }
    else if (action == 3)
    {
      const std::uint64_t bound = last + step_(rng);
      const bool below = heap.hasKeyBelow(bound);
      ASSERT_EQ(below, reference.top() < bound) << "step " << step;
      if (below) // the flood pops the heap's top at once
      {
        last = reference.top();
        reference.pop();
        ASSERT_EQ(heap.pop(), last) << "step " << step;
      }
      else
      {
        last = bound; // the flood takes the pit cell at `bound` instead
      }
    }
    else
    {
      last = reference.top();
      reference.pop();
      ASSERT_EQ(heap.pop(), last) << "step " << step;
    }
    ASSERT_EQ(heap.size(), reference.size());
  }
}
