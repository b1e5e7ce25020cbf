// Tests of Kernels/Synthesis/ExemplarCache.cxx.
// The exemplar cache (Synthesis/ExemplarCache.h): an entry read back is the
// preparation computed, and a damaged, stale or unwritable entry is never used.
#include "Core/HeightfieldIO.h"
#include "Synthesis/ExemplarCache.h"
#include "TestData.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

using namespace tsynth;
namespace fs = std::filesystem;

namespace
{

// A patch small enough for a quick pool, large enough for real features.
constexpr int kPatch = 32;

// A fresh cache directory per test.
fs::path cacheDir(const std::string& name)
{
  const fs::path dir = test::scratchDir() / ("cache-" + name);
  fs::remove_all(dir);
  return dir;
}

// A corner of the bundled Colorado DEM: real ridges and valleys, quick to prepare.
Heightfield exemplar()
{
  const Heightfield dem = readHeightfield((test::bundledData() / "dems" / "colorado.png").string());
  constexpr int kSide = 200;
  Heightfield crop(kSide, kSide);
  crop.cellX = dem.cellX;
  crop.cellY = dem.cellY;
  crop.cellSizeKnown = true;
  for (int j = 0; j < kSide; ++j)
  {
    for (int i = 0; i < kSide; ++i)
    {
      crop.at(i, j) = dem.at(i, j);
    }
  }
  return crop;
}

// Field by field: what synthesis reads of a preparation.
void expectSamePreparation(const PreparedExemplars& a, const PreparedExemplars& b)
{
  ASSERT_EQ(a.graphs.size(), b.graphs.size());
  for (std::size_t g = 0; g < a.graphs.size(); ++g)
  {
    const FeatureGraph& x = a.graphs[g];
    const FeatureGraph& y = b.graphs[g];
    ASSERT_EQ(x.nodes.size(), y.nodes.size());
    ASSERT_EQ(x.chains.size(), y.chains.size());
    EXPECT_EQ(x.bfsOrder, y.bfsOrder);
    EXPECT_EQ(x.componentCount, y.componentCount);
    for (std::size_t n = 0; n < x.nodes.size(); ++n)
    {
      EXPECT_EQ(x.nodes[n].position.x, y.nodes[n].position.x);
      EXPECT_EQ(x.nodes[n].kind, y.nodes[n].kind);
      EXPECT_EQ(x.nodes[n].chains, y.nodes[n].chains);
      ASSERT_EQ(x.nodes[n].controls.size(), y.nodes[n].controls.size());
      for (std::size_t c = 0; c < x.nodes[n].controls.size(); ++c)
      {
        EXPECT_EQ(x.nodes[n].controls[c].angle, y.nodes[n].controls[c].angle);
        EXPECT_EQ(x.nodes[n].controls[c].reached, y.nodes[n].controls[c].reached);
      }
    }
    for (std::size_t c = 0; c < x.chains.size(); ++c)
    {
      ASSERT_EQ(x.chains[c].points.size(), y.chains[c].points.size());
      EXPECT_EQ(x.chains[c].points.back().y, y.chains[c].points.back().y);
      EXPECT_EQ(x.chains[c].type, y.chains[c].type);
      EXPECT_EQ(x.chains[c].elevation.size(), y.chains[c].elevation.size());
    }
  }
  const ExemplarStatistics& s = a.statistics;
  const ExemplarStatistics& t = b.statistics;
  EXPECT_EQ(s.low, t.low);
  EXPECT_EQ(s.ridge, t.ridge);
  EXPECT_EQ(s.landform.ridge.relief, t.landform.ridge.relief);
  EXPECT_EQ(s.landform.valley.width, t.landform.valley.width);
  EXPECT_EQ(s.landform.ridge.section.values(), t.landform.ridge.section.values());
  EXPECT_EQ(s.landform.floorGradient, t.landform.floorGradient);
  EXPECT_EQ(s.landform.land.at(7.0), t.landform.land.at(7.0));
  EXPECT_EQ(s.landform.land.steepSlope(20.0), t.landform.land.steepSlope(20.0));
  EXPECT_EQ(s.landform.highest, t.landform.highest);
  const CandidatePool& p = *a.pool;
  const CandidatePool& q = *b.pool;
  EXPECT_EQ(p.patchSize, q.patchSize);
  EXPECT_EQ(p.heightScale, q.heightScale);
  EXPECT_EQ(p.variant, q.variant);
  EXPECT_EQ(p.centreX, q.centreX);
  EXPECT_EQ(p.along, q.along);
  EXPECT_EQ(p.noise, q.noise);
  EXPECT_EQ(p.descriptor, q.descriptor);
  EXPECT_EQ(p.landform, q.landform);
  ASSERT_EQ(p.sites.size(), q.sites.size());
  ASSERT_FALSE(p.sites.empty());
  EXPECT_EQ(p.sites.back().arms.size(), q.sites.back().arms.size());
  ASSERT_EQ(p.exemplars.size(), q.exemplars.size());
  EXPECT_EQ(p.exemplars[0].candidateCount, q.exemplars[0].candidateCount);
}

PreparedExemplars prepare(const Heightfield& ex, const fs::path& dir, ExemplarCacheUse& use)
{
  return prepareExemplarsCached({ &ex }, kPatch, dir.string(), use);
}

// Overwrites the byte at `offset` (from the end when negative) of a file.
void damage(const fs::path& file, long offset)
{
  std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
  f.seekg(offset, offset < 0 ? std::ios::end : std::ios::beg);
  const std::streampos at = f.tellg();
  char c = 0;
  f.read(&c, 1);
  f.seekp(at);
  c = static_cast<char>(c ^ 0x5a);
  f.write(&c, 1);
  ASSERT_TRUE(f.good());
}

} // namespace

TEST(ExemplarCache, AnEntryReadBackIsThePreparationComputed)
{
  const Heightfield ex = exemplar();
  const fs::path dir = cacheDir("roundtrip");
  ExemplarCacheUse none;
  const PreparedExemplars computed = prepareExemplarsCached({ &ex }, kPatch, "", none);
  EXPECT_TRUE(none.directory.empty());
  EXPECT_FALSE(none.hit);

  ExemplarCacheUse first;
  const PreparedExemplars stored = prepare(ex, dir, first);
  EXPECT_FALSE(first.hit);
  EXPECT_EQ(first.problem, "");
  ASSERT_TRUE(fs::exists(first.entry));
  EXPECT_EQ(fs::path(first.entry).parent_path(), dir);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1)
    << "no temporary file is left beside the entry";

  ExemplarCacheUse second;
  const PreparedExemplars read = prepare(ex, dir, second);
  EXPECT_TRUE(second.hit);
  EXPECT_EQ(second.problem, "");
  EXPECT_EQ(second.entry, first.entry);
  expectSamePreparation(computed, stored);
  expectSamePreparation(computed, read);
}

TEST(ExemplarCache, TheKeyFollowsTheContentThePatchAndTheCellSize)
{
  Heightfield ex = exemplar();
  const std::uint64_t key = exemplarPreparationKey({ &ex }, kPatch);
  EXPECT_EQ(exemplarPreparationKey({ &ex }, kPatch), key);
  EXPECT_NE(exemplarPreparationKey({ &ex }, kPatch + 8), key);
  EXPECT_NE(exemplarPreparationKey({ &ex, &ex }, kPatch), key);
  Heightfield coarser = ex;
  coarser.cellX *= 2.0;
  EXPECT_NE(exemplarPreparationKey({ &coarser }, kPatch), key);
  Heightfield edited = ex;
  edited.at(100, 100) += 0.5f; // one cell half a metre higher: another file
  EXPECT_NE(exemplarPreparationKey({ &edited }, kPatch), key);
  Heightfield masked = ex;
  masked.valid.assign(ex.size(), 1);
  masked.valid[5] = 0;
  EXPECT_NE(exemplarPreparationKey({ &masked }, kPatch), key);

  // An edited exemplar is prepared afresh, not read from the entry of the old one.
  const fs::path dir = cacheDir("edited");
  ExemplarCacheUse use;
  prepare(ex, dir, use);
  const PreparedExemplars fresh = prepare(edited, dir, use);
  EXPECT_FALSE(use.hit);
  ExemplarCacheUse none;
  expectSamePreparation(prepareExemplarsCached({ &edited }, kPatch, "", none), fresh);
}

TEST(ExemplarCache, ADamagedOrTruncatedEntryIsRebuiltNeverUsed)
{
  const Heightfield ex = exemplar();
  ExemplarCacheUse none;
  const PreparedExemplars computed = prepareExemplarsCached({ &ex }, kPatch, "", none);
  const fs::path dir = cacheDir("damaged");
  ExemplarCacheUse use;
  prepare(ex, dir, use);
  const fs::path entry = use.entry;
  const auto size = fs::file_size(entry);

  damage(entry, -1000); // a flipped byte inside the pool's data
  PreparedExemplars p = prepare(ex, dir, use);
  EXPECT_FALSE(use.hit);
  EXPECT_NE(use.problem.find("checksum"), std::string::npos) << use.problem;
  expectSamePreparation(computed, p);
  prepare(ex, dir, use);
  EXPECT_TRUE(use.hit) << "the rebuilt entry replaced the damaged one";

  fs::resize_file(entry, size / 2); // a write cut short
  p = prepare(ex, dir, use);
  EXPECT_FALSE(use.hit);
  EXPECT_NE(use.problem.find("truncated"), std::string::npos) << use.problem;
  expectSamePreparation(computed, p);

  fs::resize_file(entry, 10); // not even a header
  p = prepare(ex, dir, use);
  EXPECT_FALSE(use.hit);
  EXPECT_NE(use.problem.find("not an exemplar cache entry"), std::string::npos) << use.problem;
  expectSamePreparation(computed, p);
  prepare(ex, dir, use);
  EXPECT_TRUE(use.hit);
}

TEST(ExemplarCache, AnEntryOfOtherExemplarsOrAnotherFormatIsRebuilt)
{
  const Heightfield ex = exemplar();
  Heightfield other = ex;
  for (float& z : other.z)
  {
    z = 2.0f * z;
  }
  const fs::path dir = cacheDir("stale");
  ExemplarCacheUse mine;
  prepare(ex, dir, mine);
  ExemplarCacheUse theirs;
  prepare(other, dir, theirs);
  ASSERT_NE(mine.entry, theirs.entry);
  // The other exemplar's entry under this one's name (a copied cache, a renamed file).
  fs::copy_file(theirs.entry, mine.entry, fs::copy_options::overwrite_existing);
  ExemplarCacheUse use;
  const PreparedExemplars p = prepare(ex, dir, use);
  EXPECT_FALSE(use.hit);
  EXPECT_NE(use.problem.find("another version or for other exemplars"), std::string::npos)
    << use.problem;
  ExemplarCacheUse none;
  expectSamePreparation(prepareExemplarsCached({ &ex }, kPatch, "", none), p);

  damage(mine.entry, 8); // the format number, just after the magic
  prepare(ex, dir, use);
  EXPECT_FALSE(use.hit);
  EXPECT_NE(use.problem.find("another version"), std::string::npos) << use.problem;
}

TEST(ExemplarCache, ADirectoryThatCannotBeMadeOnlyCostsTheCache)
{
  const Heightfield ex = exemplar();
  const fs::path blocked = cacheDir("blocked");
  fs::create_directories(blocked.parent_path());
  std::ofstream(blocked) << "a file where the cache directory should be";
  ExemplarCacheUse use;
  const PreparedExemplars p = prepare(ex, blocked / "cache", use);
  EXPECT_FALSE(use.hit);
  EXPECT_NE(use.problem.find("could not be created"), std::string::npos) << use.problem;
  ExemplarCacheUse none;
  expectSamePreparation(prepareExemplarsCached({ &ex }, kPatch, "", none), p);
  fs::remove(blocked);
}

TEST(ExemplarCache, TheEntriesUsedLongestAgoMakeRoomForNewOnes)
{
  const Heightfield a = exemplar();
  Heightfield b = a;
  Heightfield c = a;
  for (std::size_t k = 0; k < a.size(); ++k)
  {
    b.z[k] = a.z[k] + 100.0f; // other files, the same size of entry
    c.z[k] = a.z[k] * 1.5f;
  }
  const fs::path dir = cacheDir("limit");
  ExemplarCacheUse ua;
  ExemplarCacheUse ub;
  ExemplarCacheUse uc;
  prepare(a, dir, ua);
  const std::uintmax_t entry = fs::file_size(ua.entry);
  // Room for two entries: a third pushes out the one used longest ago.
  const std::uintmax_t limit = 2 * entry + entry / 2;
  prepareExemplarsCached({ &b }, kPatch, dir.string(), ub, limit);
  fs::last_write_time(ua.entry, fs::last_write_time(ub.entry) - std::chrono::hours(1));
  ExemplarCacheUse again;
  prepareExemplarsCached({ &a }, kPatch, dir.string(), again, limit); // a hit renews a
  EXPECT_TRUE(again.hit);
  prepareExemplarsCached({ &c }, kPatch, dir.string(), uc, limit);
  EXPECT_TRUE(fs::exists(ua.entry)) << "used last but one";
  EXPECT_FALSE(fs::exists(ub.entry)) << "used longest ago";
  EXPECT_TRUE(fs::exists(uc.entry)) << "just written";
  std::ofstream(dir / "notes.txt") << "not an entry: never removed";
  prepareExemplarsCached({ &b }, kPatch, dir.string(), ub, entry / 2); // room for none
  EXPECT_TRUE(fs::exists(ub.entry)) << "the entry just written stays";
  EXPECT_FALSE(fs::exists(ua.entry));
  EXPECT_FALSE(fs::exists(uc.entry));
  EXPECT_TRUE(fs::exists(dir / "notes.txt"));
}

TEST(ExemplarCache, TheDefaultDirectoryFollowsTheEnvironment)
{
  const auto keep = [](const char* name)
  {
    const char* v = std::getenv(name);
    return v == nullptr ? std::string("\x01") : std::string(v);
  };
  const std::string tsynth = keep("TSYNTH_CACHE_DIR");
  const std::string xdg = keep("XDG_CACHE_HOME");
  const std::string home = keep("HOME");
  setenv("TSYNTH_CACHE_DIR", "/a/b", 1);
  EXPECT_EQ(defaultExemplarCacheDirectory(), "/a/b");
  unsetenv("TSYNTH_CACHE_DIR");
  setenv("XDG_CACHE_HOME", "/x", 1);
  EXPECT_EQ(defaultExemplarCacheDirectory(), "/x/terrainsynthesis");
  unsetenv("XDG_CACHE_HOME");
  setenv("HOME", "/h", 1);
  EXPECT_EQ(defaultExemplarCacheDirectory(), "/h/.cache/terrainsynthesis");
  unsetenv("HOME");
  EXPECT_EQ(defaultExemplarCacheDirectory(), "");
  const auto restore = [](const char* name, const std::string& v)
  {
    if (v != "\x01")
    {
      setenv(name, v.c_str(), 1);
    }
  };
  restore("TSYNTH_CACHE_DIR", tsynth);
  restore("XDG_CACHE_HOME", xdg);
  restore("HOME", home);
}

// A synthesis given its pool (the Candidate Builder's) prepares the lines and statistics
// only: it builds no pool of its own, so a miss stores no entry, and a hit leaves the
// entry's pool out.
TEST(ExemplarCache, AGivenPoolIsNotBuiltAgainNorStored)
{
  const Heightfield ex = exemplar();
  const fs::path dir = cacheDir("given-pool");
  ExemplarCacheUse none;
  const PreparedExemplars computed = prepareExemplarsCached({ &ex }, kPatch, "", none);

  ExemplarCacheUse miss;
  PreparedExemplars lines = prepareExemplarsForGivenPool({ &ex }, kPatch, dir.string(), miss);
  EXPECT_EQ(lines.pool, nullptr);
  EXPECT_FALSE(miss.hit);
  EXPECT_FALSE(fs::exists(miss.entry)) << "an entry without its pool was stored";
  lines.pool = computed.pool;
  expectSamePreparation(lines, computed);

  ExemplarCacheUse stored;
  prepare(ex, dir, stored);
  ASSERT_TRUE(fs::exists(stored.entry));
  ExemplarCacheUse hit;
  PreparedExemplars read = prepareExemplarsForGivenPool({ &ex }, kPatch, dir.string(), hit);
  EXPECT_TRUE(hit.hit);
  EXPECT_EQ(read.pool, nullptr);
  read.pool = computed.pool;
  expectSamePreparation(read, computed);
}
