// What a synthesis computes from its exemplars alone (their ridges and valleys,
// their landform statistics, the feature candidate pool), kept on disk so that
// the next run with the same exemplars, cell size and patch size reads it back
// instead of computing it again: from one 648 x 648 exemplar at patch 80, 0.1 s
// read back against 0.55 s computed (Testing/Benchmarks/bench_synthesis.sh --cache).
//
// An entry is named by a key that hashes the exemplars' heights and validity
// (after resampling to the output's cell size), their grids, the patch size,
// the entry format and the code that computes it (the library file's bytes), so
// a changed exemplar, option or build never finds an old entry. An entry whose
// header, size or checksum does not match what it claims (a truncated write, a
// flipped bit, another version's file) is rebuilt and replaced, never used.
// Entries are written to a temporary file and renamed into place, so a reader
// sees a whole entry or none; the directory is kept under kExemplarCacheLimitBytes.
#pragma once

#include "../Core/Heightfield.h"
#include "../Features/FeatureGraph.h"
#include "../Features/Ppa.h"
#include "../Matching/CandidatePool.h"
#include "Target.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace tsynth
{

// The most the entries of one cache directory hold; past it the entries used
// longest ago are removed. An entry takes about 40 bytes per exemplar cell at
// the output's cell size (27 MB for a 648 x 648 exemplar at patch 80), so this
// keeps a few dozen exemplar sets.
constexpr std::uintmax_t kExemplarCacheLimitBytes = std::uintmax_t{ 1 } << 30;

// Everything synthesis derives from the exemplars alone, in their order.
// The PPA settings the synthesis finds its exemplars' ridges and valleys with
// (ridgesAndValleys): what the Candidate Builder and the Patch Matcher extract
// when given no feature trees, so that their pool is the synthesis' own.
PpaOptions exemplarPpaOptions();

struct PreparedExemplars
{
  std::vector<FeatureGraph> graphs;          // PPA ridges and valleys
  ExemplarStatistics statistics;             // exemplarStatistics()
  std::shared_ptr<const CandidatePool> pool; // buildCandidatePool(), default variants
};

// What became of the cache in one preparation, for reports and messages.
struct ExemplarCacheUse
{
  std::string directory; // empty: no cache was used
  std::string entry;     // the entry's file
  bool hit = false;      // read back rather than computed
  double seconds = 0.0;  // the preparation's time, computed or read
  // Why an entry was not used or not written (corrupt, stale, unwritable);
  // empty when all went well.
  std::string problem;
};

// The cache directory a user gets by default: $TSYNTH_CACHE_DIR, else
// $XDG_CACHE_HOME/terrainsynthesis, else $HOME/.cache/terrainsynthesis; empty
// (no cache) when none of them is set.
std::string defaultExemplarCacheDirectory();

// The key of the preparation of these exemplars (at the output's cell size)
// for this patch size.
std::uint64_t exemplarPreparationKey(const std::vector<const Heightfield*>& exemplars,
  int patchSize);

// Computes the preparation (PPA graphs, statistics, pool), or reads it from
// `directory` when an intact entry for the same key is there; a computed one
// is then stored. An empty directory computes without a cache. Cache trouble
// (an unreadable, corrupt or stale entry, a directory that cannot be written)
// never fails the preparation: it is computed and `use.problem` says what
// happened. Errors of the computation itself propagate (tsynth::Error).
// `limit`: what the directory's entries may hold, in bytes.
PreparedExemplars prepareExemplarsCached(const std::vector<const Heightfield*>& exemplars,
  int patchSize,
  const std::string& directory,
  ExemplarCacheUse& use,
  std::uintmax_t limit = kExemplarCacheLimitBytes);

// The same for a synthesis given its candidate pool (a Candidate Builder's
// table): the lines and statistics, with `pool` left null. A cache hit is read
// as above; a miss builds no pool and so stores no entry (an entry holds one).
PreparedExemplars prepareExemplarsForGivenPool(const std::vector<const Heightfield*>& exemplars,
  int patchSize,
  const std::string& directory,
  ExemplarCacheUse& use);

} // namespace tsynth
