// Tests of Kernels/Core/Cancellation.cxx.
// A kernel stops within one stride of polls (or one band of rows) of the
// scope's test saying stop, only on the thread that opened it, and never
// without a scope.
#include "Core/Cancellation.h"

#include <gtest/gtest.h>

#include <atomic>
#include <thread>
#include <vector>

using namespace tsynth;

TEST(Cancellation, WithoutAScopePollsNeverStop)
{
  ASSERT_EQ(openCancellationScopes.load(), 0);
  for (unsigned k = 0; k < 3 * kCancellationStride; ++k)
  {
    pollCancellation();
  }
  EXPECT_NO_THROW(checkCancellation());
  EXPECT_FALSE(cancellationRequested());
}

TEST(Cancellation, PollsStopWithinOneStrideOfTheTestSayingStop)
{
  bool stop = false;
  int asked = 0;
  const CancellationScope scope(
    [&]
    {
      ++asked;
      return stop;
    });
  // A stride of polls asks the test once, and it says go on.
  for (unsigned k = 0; k < kCancellationStride; ++k)
  {
    pollCancellation();
  }
  EXPECT_EQ(asked, 1);
  stop = true;
  unsigned polls = 0;
  EXPECT_THROW(
    {
      for (;; ++polls)
      {
        pollCancellation();
      }
    },
    Cancelled);
  EXPECT_LT(polls, kCancellationStride) << "more than a stride of work after the stop";
  EXPECT_THROW(checkCancellation(), Cancelled);
  EXPECT_TRUE(cancellationRequested());
}

TEST(Cancellation, ScopesNestAndCloseCleanly)
{
  {
    const CancellationScope outer([] { return false; });
    {
      const CancellationScope inner([] { return true; });
      EXPECT_THROW(checkCancellation(), Cancelled);
    }
    EXPECT_NO_THROW(checkCancellation()) << "the outer scope's test answers again";
  }
  EXPECT_EQ(openCancellationScopes.load(), 0);
  EXPECT_NO_THROW(checkCancellation());
}

TEST(Cancellation, AnotherThreadsScopeDoesNotStopThisOne)
{
  std::atomic<bool> opened{ false };
  std::atomic<bool> done{ false };
  std::thread other(
    [&]
    {
      const CancellationScope stopEverything([] { return true; });
      opened = true;
      while (!done)
      {
        std::this_thread::yield();
      }
    });
  while (!opened)
  {
    std::this_thread::yield();
  }
  EXPECT_NO_THROW(checkCancellation());
  EXPECT_FALSE(cancellationRequested());
  done = true;
  other.join();
}

TEST(Cancellation, RowBandsRunEveryRowOnceAndStopBetweenBands)
{
  const int rows = 3 * kCancellationBandRows + 17;
  std::vector<int> runs(static_cast<std::size_t>(rows), 0);
  forRowBands(rows, [&](int j) { ++runs[static_cast<std::size_t>(j)]; });
  for (int r : runs)
  {
    EXPECT_EQ(r, 1);
  }
  // Stop once the first band is done: the rows of the later bands never run.
  std::vector<int> ran(static_cast<std::size_t>(rows), 0);
  const CancellationScope scope([&] { return ran[0] == 1; });
  EXPECT_THROW(forRowBands(rows, [&](int j) { ran[static_cast<std::size_t>(j)] = 1; }), Cancelled);
  int done = 0;
  for (int r : ran)
  {
    done += r;
  }
  EXPECT_EQ(done, kCancellationBandRows);
}
