// Memory budgets: how much of this machine a run may use, and the one refusal
// every front end prints when a run's estimate is above it (before any work).
#pragma once

#include <string>

namespace tsynth
{

// Bytes in a gigabyte, as memory options (--max-memory, MemoryBudget) count them.
constexpr double kBytesPerGB = 1.0e9;

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

} // namespace tsynth
