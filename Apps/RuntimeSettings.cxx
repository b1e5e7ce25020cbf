#include "RuntimeSettings.h"

#include <cstdlib>
#include <string>

namespace tsynth::cli
{

// - glibc.malloc.hugetlb=1 (GLIBC_TUNABLES): malloc asks for transparent huge
//   pages, where the system gives them on request (THP mode "madvise", as
//   here). A 1024^2 synthesis touches 270 MB of fresh memory; in 4 KB pages
//   that was 67,000 page faults and 0.3-0.4 s of a 5.7 s run, in 2 MB pages
//   4,000. Left alone if the user set the tunable either way.
// - OMP_WAIT_POLICY=passive unless the user chose a policy: libgomp's
//   threads spin for milliseconds after each parallel region and took the
//   cores PoCL's threads need (fill 20% faster passive), and on a machine busy
//   with other work the cores everything else needs (a preview, all small
//   parallel regions, took 2.9 s instead of 0.2 s beside another run with
//   spinning threads; Norway as a DEM target on the CPU backend, beside a
//   build and a test run, 26.7 s instead of 8.3 s). On an idle machine
//   spinning gained 2% there (7.5 s against 7.7 s): not worth the risk.
bool setSynthRuntimeSettings()
{
  bool changed = false;
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  const std::string given = tunables != nullptr ? tunables : "";
  if (given.find("glibc.malloc.hugetlb") == std::string::npos)
  {
    const std::string hugePages = "glibc.malloc.hugetlb=1";
    setenv("GLIBC_TUNABLES", (given.empty() ? hugePages : given + ":" + hugePages).c_str(), 1);
    changed = true;
  }
  if (std::getenv("OMP_WAIT_POLICY") == nullptr)
  {
    setenv("OMP_WAIT_POLICY", "passive", 1);
    changed = true;
  }
  return changed;
}

} // namespace tsynth::cli
