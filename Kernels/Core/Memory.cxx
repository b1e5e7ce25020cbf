#include "Memory.h"

#include "Error.h"

#include <iomanip>
#include <mutex>
#include <sstream>
#include <unistd.h>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace tsynth
{
namespace
{

constexpr double kBytesPerMB = 1.0e6;
// One decimal is noise above this many GB.
constexpr double kWholeGBFrom = 100.0;

} // namespace

void reuseFreedWorkMemory()
{
  static std::once_flag once;
  std::call_once(once,
    []
    {
#if defined(__GLIBC__)
      // Each call only changes a tuning parameter; a refused one (a C library
      // with other limits) leaves glibc's default, which is slower, not wrong.
      mallopt(M_MMAP_THRESHOLD, static_cast<int>(kReusedBlockBytes));
      mallopt(M_MMAP_MAX, 0); // no block is mapped on its own, however large
      mallopt(M_TRIM_THRESHOLD, static_cast<int>(kKeptFreeBytes));
      mallopt(M_TOP_PAD, static_cast<int>(kHeapGrowthPadBytes));
#endif
    });
}

void returnFreedMemory()
{
#if defined(__GLIBC__)
  if (mallinfo2().fordblks > static_cast<std::size_t>(kKeptFreeBytes))
  {
    malloc_trim(0);
  }
#endif
}

double physicalMemory()
{
  return static_cast<double>(sysconf(_SC_PHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGE_SIZE));
}

double defaultMemoryBudget()
{
  return kDefaultMemoryFraction * physicalMemory();
}

std::string bytesText(double bytes)
{
  std::ostringstream o;
  if (bytes >= kBytesPerGB)
  {
    o << std::fixed << std::setprecision(bytes < kWholeGBFrom * kBytesPerGB ? 1 : 0)
      << bytes / kBytesPerGB << " GB";
  }
  else
  {
    // Below one MB one decimal, so that a budget of 0.1 MB is printed as such.
    o << std::fixed << std::setprecision(bytes < kBytesPerMB ? 1 : 0) << bytes / kBytesPerMB
      << " MB";
  }
  return o.str();
}

double checkMemoryBudget(double estimate,
  double budget,
  const std::string& run,
  const std::string& advice,
  const std::string& option)
{
  const double applied = budget > 0.0 ? budget : defaultMemoryBudget();
  if (estimate <= applied)
  {
    return applied;
  }
  std::ostringstream share;
  share << kDefaultMemoryFraction * 100.0;
  throw Error(run + " needs about " + bytesText(estimate) + " but the memory budget is " +
    bytesText(applied) +
    (budget > 0.0 ? std::string() : " (" + share.str() + "% of this machine's memory)") + "; " +
    advice + ", or raise " + option + ".");
}

void checkReadFits(const std::string& path, int width, int height, double bytesPerCell)
{
  const double needed = bytesPerCell * static_cast<double>(width) * static_cast<double>(height);
  const double budget = defaultMemoryBudget();
  if (needed <= budget)
  {
    return;
  }
  throw Error(path + " is " + std::to_string(width) + " x " + std::to_string(height) +
    " cells: reading it needs about " + bytesText(needed) + ", more than the " + bytesText(budget) +
    " this machine's memory allows; its header may be damaged.");
}

} // namespace tsynth
