// Tests of Kernels/Core/Memory.cxx.
// Memory budgets: the one refusal sentence (Core/Memory.h) and the estimates of
// pit removal and terrain optimisation, each refused by its kernel's own set-up
// before any work, with the estimate in the message (those kernels' other tests
// are in tsynth_hydrology_tests and tsynth_optimisation_tests); the reuse of
// freed work memory.
#include "Core/Error.h"
#include "Core/Memory.h"
#include "Core/MemoryTestData.h"
#include "ErrorOf.h"
#include "Hydrology/PitRemoval.h"
#include "Optimisation/TerrainOptimisation.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <sys/resource.h>
#include <unistd.h>
#include <vector>

using namespace tsynth;
using tsynth::test::memory::about;

namespace
{

using tsynth::test::errorOf;

Heightfield slope(int width, int height)
{
  Heightfield hf(width, height);
  for (int j = 0; j < height; ++j)
  {
    for (int i = 0; i < width; ++i)
    {
      hf.at(i, j) = static_cast<float>(3 * i + 2 * j + ((i * 7 + j * 13) % 5));
    }
  }
  hf.cellX = hf.cellY = 30.0;
  return hf;
}

} // namespace

TEST(MemoryBudget, TheRefusalNamesEstimateBudgetAdviceAndOption)
{
  EXPECT_EQ(bytesText(164.4e6), "164 MB");
  EXPECT_EQ(bytesText(2.54e9), "2.5 GB");
  EXPECT_EQ(bytesText(1.0e5), "0.1 MB");
  EXPECT_EQ(bytesText(812.0e9), "812 GB");
  EXPECT_EQ(checkMemoryBudget(5.0e6, 6.0e6, "A run", "do less", "--max-memory"), 6.0e6);
  EXPECT_EQ(errorOf([] { checkMemoryBudget(7.0e6, 6.0e6, "A run", "do less", "--max-memory"); }),
    "A run needs about 7 MB but the memory budget is 6 MB; do less, or raise --max-memory.");
  const std::string byDefault = errorOf(
    [] { checkMemoryBudget(10.0 * physicalMemory(), 0.0, "A run", "do less", "MemoryBudget"); });
  EXPECT_NE(byDefault.find("(80% of this machine's memory); do less, or raise MemoryBudget."),
    std::string::npos)
    << byDefault;
  EXPECT_NEAR(defaultMemoryBudget(), kDefaultMemoryFraction * physicalMemory(), 1.0);
}

TEST(MemoryBudget, PitRemovalIsRefusedByItsSetUpWithTheEstimate)
{
  const double plain = pitRemovalMemoryEstimate(1024, 1024, false);
  EXPECT_NEAR(plain, 128.0e6 + 20.0 * 1024 * 1024, 1.0);
  EXPECT_NEAR(pitRemovalMemoryEstimate(1024, 1024, true) - plain, 8.0 * 1024 * 1024, 1.0);
  EXPECT_NEAR(pitRemovalMemoryEstimate(2048, 2048, false) - 128.0e6, 4.0 * (plain - 128.0e6), 1.0);
  const Heightfield dem = slope(64, 48);
  PitRemovalOptions o;
  o.memoryBudget = 1.0e6;
  o.memoryOption = "--max-memory";
  const std::string m = errorOf([&] { checkDemToDrain(dem, o, true); });
  EXPECT_NE(m.find("This pit removal of 64 x 48 cells with flow routing " +
              about(pitRemovalMemoryEstimate(64, 48, true)) + "1 MB; give a smaller DEM"),
    std::string::npos)
    << m;
  EXPECT_NE(m.find("raise --max-memory."), std::string::npos) << m;
  o.memoryBudget = pitRemovalMemoryEstimate(64, 48, true);
  EXPECT_EQ(errorOf([&] { checkDemToDrain(dem, o, true); }), "");
}

TEST(MemoryBudget, OptimisationCountsOutputSourceAndOrientations)
{
  OptimisationOptions o;
  const double plain = optimisationMemoryEstimate(1024, 1024, 648 * 648, o);
  EXPECT_NEAR(plain, 128.0e6 + 100.0 * 1024 * 1024 + 54.0 * 648 * 648, 1.0);
  o.rotations = true;
  o.reflections = true;
  EXPECT_NEAR(
    optimisationMemoryEstimate(1024, 1024, 648 * 648, o) - plain, 7.0 * 14.0 * 648 * 648, 1.0);
  o.rotations = o.reflections = false;
  o.drainOutput = true;
  EXPECT_NEAR(
    optimisationMemoryEstimate(1024, 1024, 648 * 648, o) - plain, 25.0 * 1024 * 1024, 1.0);
}

TEST(MemoryBudget, OptimisationIsRefusedBeforeAnyWork)
{
  const Heightfield source = slope(96, 96);
  const Heightfield guide = slope(80, 80);
  OptimisationOptions o;
  o.patchSize = 5;
  o.levels = 1;
  o.memoryBudget = 1.0e6;
  o.memoryOption = "MemoryBudget";
  o.sizeOption = "OutputSize";
  bool progressed = false;
  o.progress = [&](double, const std::string&) { progressed = true; };
  const std::string m = errorOf([&] { optimiseTerrain(source, guide, o); });
  EXPECT_NE(m.find("This optimisation of 80 x 80 cells from a source of 9216 cells " +
              about(optimisationMemoryEstimate(80, 80, 96 * 96, o)) +
              "1 MB; give a smaller OutputSize or source"),
    std::string::npos)
    << m;
  EXPECT_NE(m.find("raise MemoryBudget."), std::string::npos) << m;
  EXPECT_FALSE(progressed);
}

namespace
{

// Page faults taken while `arrays` arrays of `bytes` each are allocated
// together, filled and freed, `times` times: a synthesis stage's work arrays.
long faultsOfRepeatedArrays(std::size_t bytes, int arrays, int times)
{
  rusage before{};
  getrusage(RUSAGE_SELF, &before);
  for (int t = 0; t < times; ++t)
  {
    std::vector<std::vector<char>> work;
    for (int a = 0; a < arrays; ++a)
    {
      work.emplace_back(bytes, static_cast<char>(t + a));
    }
    EXPECT_EQ(work.back()[bytes / 2], static_cast<char>(t + arrays - 1));
  }
  rusage after{};
  getrusage(RUSAGE_SELF, &after);
  return after.ru_minflt - before.ru_minflt;
}

} // namespace

TEST(MemoryReuse, FreedWorkArraysAreNotFaultedInAgain)
{
  // Four 8 MB arrays at once (a 1024 x 1024 stage's fields): by default glibc
  // trims the heap once more than twice its largest freed block is free at
  // the top, so each use faults all their pages in anew.
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer's allocator replaces glibc's; its tuning does not apply";
#endif
  constexpr std::size_t kBytes = 8u << 20;
  constexpr int kArrays = 4;
  constexpr int kUses = 10;
  const long pages =
    kArrays * static_cast<long>(kBytes / static_cast<std::size_t>(sysconf(_SC_PAGESIZE)));
  reuseFreedWorkMemory();
  reuseFreedWorkMemory();                     // a second call changes nothing
  faultsOfRepeatedArrays(kBytes, kArrays, 1); // the heap grows once
  const long faults = faultsOfRepeatedArrays(kBytes, kArrays, kUses);
  // Kept for reuse, the later uses fault in (almost) nothing, where trimming
  // would fault kUses * pages.
  EXPECT_LT(faults, pages) << faults << " faults for " << kUses << " uses of " << pages << " pages";
}

TEST(MemoryReuse, FieldsAboveAnyMappingThresholdAreReusedToo)
{
  // Two 64 MB arrays (a 4096 x 4096 field of floats), above the largest
  // threshold glibc accepts: mapped each, every use would fault them in anew.
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer's allocator replaces glibc's; its tuning does not apply";
#endif
  constexpr std::size_t kBytes = 64u << 20;
  static_assert(kBytes > static_cast<std::size_t>(kReusedBlockBytes));
  constexpr int kArrays = 2;
  constexpr int kUses = 5;
  const long pages =
    kArrays * static_cast<long>(kBytes / static_cast<std::size_t>(sysconf(_SC_PAGESIZE)));
  reuseFreedWorkMemory();
  faultsOfRepeatedArrays(kBytes, kArrays, 1); // the heap grows once
  const long faults = faultsOfRepeatedArrays(kBytes, kArrays, kUses);
  EXPECT_LT(faults, pages) << faults << " faults for " << kUses << " uses of " << pages << " pages";
}

namespace
{

long residentBytes()
{
  std::ifstream statm("/proc/self/statm");
  long size = 0;
  long resident = 0;
  statm >> size >> resident;
  return resident * sysconf(_SC_PAGESIZE);
}

struct Resident
{
  long beforeReturning = 0;
  long afterReturning = 0;
};

// Resident memory before and after returnFreedMemory(), once `arrays` work
// arrays of `bytes` are freed under a small block still held above them on
// the heap (so that freeing them trims nothing by itself).
Resident residentAroundReturning(std::size_t bytes, int arrays)
{
  std::vector<std::vector<char>> work;
  for (int a = 0; a < arrays; ++a)
  {
    work.emplace_back(bytes, static_cast<char>(a + 1));
  }
  std::vector<char> held(1u << 20, 7);
  // The premise: the held block lies above every array.
  for (const std::vector<char>& w : work)
  {
    EXPECT_GT(held.data(), w.data() + w.size()) << "the held block is not above the arrays";
  }
  std::vector<std::vector<char>>().swap(work);
  Resident r;
  r.beforeReturning = residentBytes();
  returnFreedMemory();
  r.afterReturning = residentBytes();
  EXPECT_EQ(held[held.size() / 2], 7);
  return r;
}

} // namespace

TEST(MemoryReuse, FreedMemoryUnderAHeldBlockGoesBackOnlyWhenMuchOfItIsFree)
{
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer's allocator replaces glibc's; its tuning does not apply";
#endif
  constexpr std::size_t kBytes = 64u << 20;
  constexpr long kSlack = 16L << 20; // what other allocations may move meanwhile
  reuseFreedWorkMemory();
  // 128 MB free: under kKeptFreeBytes, kept for the next stage to reuse.
  const Resident few = residentAroundReturning(kBytes, 2);
  EXPECT_GT(few.afterReturning, few.beforeReturning - kSlack)
    << few.beforeReturning << " -> " << few.afterReturning;
  // More than kKeptFreeBytes free: handed back, though a block above them is held.
  const int many = static_cast<int>(kKeptFreeBytes / static_cast<long>(kBytes)) + 2;
  const Resident lots = residentAroundReturning(kBytes, many);
  EXPECT_LT(lots.afterReturning, lots.beforeReturning - (many - 1) * static_cast<long>(kBytes))
    << lots.beforeReturning << " -> " << lots.afterReturning;
}
