// Memory budgets: how much of this machine a run may use, and the one refusal
// every front end prints when a run's estimate is above it (before any work).
#pragma once

#include <string>

namespace tsynth
{

// Bytes in a gigabyte, as memory options (--max-memory, MemoryBudget) count them.
constexpr double kBytesPerGB = 1.0e9;
// The largest memory budget the front ends take, in GB: more is a typing error.
constexpr double kMaxMemoryBudgetGB = 1.0e6;

// This machine's physical memory, in bytes.
double physicalMemory();

// kDefaultMemoryFraction of this machine's physical memory, in bytes.
double defaultMemoryBudget();
constexpr double kDefaultMemoryFraction = 0.8; // leaves room for the system and the caller

// "164 MB", "2.5 GB": what messages print.
std::string bytesText(double bytes);

// Throws tsynth::Error unless estimate <= budget (budget 0: defaultMemoryBudget()),
// as one sentence: "<run> needs about E but the memory budget is B[ (80% of this
// machine's memory)]; <advice>, or raise <option>." `run` says what would run,
// e.g. "This pit removal of 4096 x 4096 cells"; `advice` what makes it smaller.
// Returns the budget applied.
double checkMemoryBudget(double estimate,
  double budget,
  const std::string& run,
  const std::string& advice,
  const std::string& option);

// Throws tsynth::Error if reading `path` (width x height cells at bytesPerCell)
// would need more than defaultMemoryBudget(): a header claiming an absurd size
// is refused before anything is allocated.
void checkReadFits(const std::string& path, int width, int height, double bytesPerCell);

// Asks the C library (glibc; elsewhere nothing is done) to keep freed work
// arrays for reuse instead of handing them back to the system at once. A
// synthesis allocates and frees arrays of megabytes per patch and per stage;
// by default glibc unmaps each block from 128 kB on and trims the heap when
// 128 kB are free at its top, so the next array page-faults in afresh: a third
// of a 1024 x 1024 synthesis's system time and about 15% of its wall time
// (Testing/Benchmarks/bench_synthesis.sh --vs). Every block then comes from the
// heap, whatever its size (at 4096 x 4096 a field of doubles is 134 MB, above
// any mapping threshold glibc accepts, and mapping them made page faults and
// clearing fresh pages half of the set-up's time), and up to kKeptFreeBytes of
// freed heap are kept. glibc still maps a block the heap cannot grow to hold.
// It changes no result. Called once per process (later calls do nothing) by
// tsynth's main and prepareSynthesis(); safe to call from any thread.
void reuseFreedWorkMemory();
// Between the stages of a large synthesis: hands the freed heap back to the
// system (glibc's malloc_trim, which also releases free pages inside the heap,
// not only at its top) when more than kKeptFreeBytes of it are free. Every
// block lives on the heap (above), so a block still held near its top kept
// every freed one below it resident: at 4096 x 4096 the placement held 1.9 GB
// of resident memory for 1.3 GB in use, and the next stage's new blocks,
// which did not fit the holes, came on top of that. Under the bound nothing
// is done: a 1024 x 1024 synthesis keeps reusing its pages. It changes no
// result. Safe to call from any thread.
void returnFreedMemory();
// The largest block glibc allows on its heap by threshold (64-bit); fixing it
// also stops glibc from moving the threshold as blocks are freed.
constexpr long kReusedBlockBytes = 32L << 20;
constexpr long kKeptFreeBytes = 512L << 20;
// How much more than asked the heap grows by, so growing is rare.
constexpr long kHeapGrowthPadBytes = 64L << 20;

} // namespace tsynth
