// Tests of Kernels/Merging/PatchMerger.cxx.
// Patch merging on real DEMs: exact round trip, seam smoothness of the modes,
// clipping, nodata and the dry run.
#include "Core/Error.h"
#include "Core/HeightfieldIO.h"
#include "Merging/PatchMerger.h"
#include "TestData.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

using namespace tsynth;

namespace
{

const Heightfield& alps()
{
  static const Heightfield hf =
    readHeightfield(test::bundledData() / "dems" / "alps-montblanc.png");
  return hf;
}

const Heightfield& colorado()
{
  static const Heightfield hf = readHeightfield(test::bundledData() / "dems" / "colorado.png");
  return hf;
}

Heightfield crop(const Heightfield& src, int x0, int y0, int w, int h)
{
  Heightfield out(w, h);
  out.cellX = src.cellX;
  out.cellY = src.cellY;
  out.cellSizeKnown = src.cellSizeKnown;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
      out.at(i, j) = src.at(x0 + i, y0 + j);
  return out;
}

// Slopes |dz| / cell of every pair of 4-adjacent valid cells.
std::vector<double> slopes(const Heightfield& hf)
{
  std::vector<double> s;
  for (int j = 0; j < hf.height; ++j)
    for (int i = 0; i < hf.width; ++i)
    {
      if (!hf.isValid(i, j))
        continue;
      if (i + 1 < hf.width && hf.isValid(i + 1, j))
        s.push_back(std::abs(hf.at(i + 1, j) - hf.at(i, j)) / hf.cellX);
      if (j + 1 < hf.height && hf.isValid(i, j + 1))
        s.push_back(std::abs(hf.at(i, j + 1) - hf.at(i, j)) / hf.cellY);
    }
  return s;
}

double percentile(std::vector<double> v, double p)
{
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(p * (v.size() - 1))];
}

} // namespace

TEST(PatchMerge, PlaceBackLeavesTheDemUnchangedInEveryMode)
{
  const Heightfield& dem = alps();
  const int px = 120, py = 100, size = 96;
  for (MergeMode mode : { MergeMode::Cut, MergeMode::Poisson, MergeMode::Shepard, MergeMode::New })
  {
    SCOPED_TRACE(mergeModeName(mode));
    // Terrain filled left of column 150 (the patch overlaps it by 30 columns)
    // and in a block above the patch; garbage elsewhere.
    Heightfield terrain = dem;
    std::vector<std::uint8_t> filled(terrain.size(), 0);
    for (int j = 0; j < terrain.height; ++j)
      for (int i = 0; i < terrain.width; ++i)
      {
        const bool f = i < 150 || (j >= py + 80 && i < 190);
        filled[terrain.index(i, j)] = f;
        if (!f)
          terrain.at(i, j) = -999.0f;
      }
    const Heightfield patch = crop(dem, px, py, size, size);
    std::vector<std::uint8_t> core(patch.size(), 0);
    for (int j = 40; j < 50; ++j)
      for (int i = 50; i < 60; ++i)
        core[patch.index(i, j)] = 1;
    MergeOptions options;
    options.mode = mode;
    PatchMerger merger;
    const MergeResult r = merger.merge(terrain, filled, patch, px, py, &core, options);
    EXPECT_EQ(r.overlapCells, static_cast<std::size_t>(30 * 96 + 40 * 16));
    EXPECT_EQ(r.cutCost, 0.0);
    for (int j = py; j < py + size; ++j)
      for (int i = px; i < px + size; ++i)
      {
        // Every window cell has an owner and the DEM's height, bit for bit.
        ASSERT_EQ(filled[terrain.index(i, j)], 1) << i << "," << j;
        ASSERT_EQ(terrain.at(i, j), dem.at(i, j)) << i << "," << j;
      }
    EXPECT_GE(r.newCells, static_cast<std::size_t>(66 * 80));
  }
}

TEST(PatchMerge, NewModeRemovesTheSeamThatCutLeaves)
{
  // Old terrain: Colorado (heights in metres from feet). New patch: the Alps,
  // thousands of metres higher, given the terrain's cell size (as if resampled).
  const Heightfield& col = colorado();
  const Heightfield& alp = alps();
  const int tw = 260, th = 200;
  const Heightfield base = crop(col, 20, 20, tw, th);
  Heightfield patch = crop(alp, 200, 150, 96, 96);
  patch.cellX = base.cellX;
  patch.cellY = base.cellY;
  std::vector<double> exemplarSlopes = slopes(base);
  const std::vector<double> alpSlopes = slopes(patch);
  exemplarSlopes.insert(exemplarSlopes.end(), alpSlopes.begin(), alpSlopes.end());
  const double p99 = percentile(exemplarSlopes, 0.99);

  const int px = 100, py = 50;
  auto seamJumps = [&](MergeMode mode, double& p95Jump, double& medianJump)
  {
    Heightfield terrain = base;
    std::vector<std::uint8_t> filled(terrain.size(), 0);
    for (int j = 0; j < th; ++j)
      for (int i = 0; i < tw; ++i)
        filled[terrain.index(i, j)] = i < 140; // overlap: 40 columns
    const std::vector<std::uint8_t> before = filled;
    MergeOptions options;
    options.mode = mode;
    PatchMerger merger;
    const MergeResult r = merger.merge(terrain, filled, patch, px, py, nullptr, options);
    EXPECT_GT(r.cutEdges, 0);
    // Slopes across edges between a new cell and an old one.
    std::vector<double> jumps;
    auto isNew = [&](int i, int j)
    {
      const int ri = i - r.x0, rj = j - r.y0;
      return ri >= 0 && rj >= 0 && ri < r.width && rj < r.height && r.takeNew[rj * r.width + ri];
    };
    auto isOld = [&](int i, int j) { return before[terrain.index(i, j)] && !isNew(i, j); };
    auto across = [&](int i, int j, int i2, int j2)
    { return (isNew(i, j) && isOld(i2, j2)) || (isOld(i, j) && isNew(i2, j2)); };
    for (int j = 0; j + 1 < th; ++j)
      for (int i = 0; i + 1 < tw; ++i)
      {
        if (across(i, j, i + 1, j))
          jumps.push_back(std::abs(terrain.at(i + 1, j) - terrain.at(i, j)) / terrain.cellX);
        if (across(i, j, i, j + 1))
          jumps.push_back(std::abs(terrain.at(i, j + 1) - terrain.at(i, j)) / terrain.cellY);
      }
    ASSERT_GT(jumps.size(), 50u);
    p95Jump = percentile(jumps, 0.95);
    medianJump = percentile(jumps, 0.5);
  };
  double cutP95 = 0, cutMedian = 0, newP95 = 0, newMedian = 0, zhouP95 = 0, zhouMedian = 0;
  seamJumps(MergeMode::Cut, cutP95, cutMedian);
  seamJumps(MergeMode::New, newP95, newMedian);
  seamJumps(MergeMode::Poisson, zhouP95, zhouMedian);
  std::printf("exemplar slope p99 %.3f; seam slope p95/median: cut %.3f/%.3f, new %.3f/%.3f, "
              "poisson %.3f/%.3f\n",
    p99,
    cutP95,
    cutMedian,
    newP95,
    newMedian,
    zhouP95,
    zhouMedian);
  // The seam crosses real terrain, whose own slopes exceed their p99 on 1% of
  // the edges, so the test takes the seam's 95th percentile, not its maximum.
  EXPECT_GT(cutMedian, p99); // the raw cut: a cliff along most of the seam
  EXPECT_GT(cutP95, 5.0 * p99);
  EXPECT_LE(newP95, p99); // Tasse's merge: the seam is as steep as real terrain
  EXPECT_LT(newMedian, 0.1 * cutMedian);
  EXPECT_LE(zhouMedian, p99); // Zhou's: smooth on the whole, with kinks
}

TEST(PatchMerge, NewModeKeepsThePatchShapeOnItsFreeBorder)
{
  // An Alps patch merged into Colorado with 40 columns of overlap on its west;
  // its east side borders unfilled land. Anchored, the free border beyond the
  // Shepard radius is kept at the patch's own heights plus one shift (the seam's
  // mean mismatch), so the next patch fits to an untilted edge.
  const Heightfield base = crop(colorado(), 20, 20, 260, 200);
  Heightfield patch = crop(alps(), 200, 150, 96, 96);
  patch.cellX = base.cellX;
  patch.cellY = base.cellY;
  const int px = 100, py = 50;
  // Spread of (terrain - patch) along the patch's east column, and its mean.
  auto eastOffsets = [&](bool anchor, float highest, double& mean, double& spread)
  {
    Heightfield terrain = base;
    std::vector<std::uint8_t> filled(terrain.size(), 0);
    for (int j = 0; j < terrain.height; ++j)
      for (int i = 0; i < terrain.width; ++i)
        filled[terrain.index(i, j)] = i < 140;
    MergeOptions options;
    options.anchorFreeBorder = anchor;
    options.highestHeight = highest;
    PatchMerger merger;
    merger.merge(terrain, filled, patch, px, py, nullptr, options);
    const int i = patch.width - 1;
    double sum = 0.0, square = 0.0;
    for (int j = 0; j < patch.height; ++j)
    {
      const double d = terrain.at(px + i, py + j) - patch.at(i, j);
      sum += d;
      square += d * d;
    }
    mean = sum / patch.height;
    spread = std::sqrt(std::max(0.0, square / patch.height - mean * mean));
  };
  const float unbounded = std::numeric_limits<float>::infinity();
  double anchoredMean = 0, anchoredSpread = 0, freeMean = 0, freeSpread = 0;
  eastOffsets(true, unbounded, anchoredMean, anchoredSpread);
  eastOffsets(false, unbounded, freeMean, freeSpread);
  // A free border above highestHeight makes the merge solve again, anchored.
  double boundedMean = 0, boundedSpread = 0;
  eastOffsets(false, 0.0f, boundedMean, boundedSpread);
  EXPECT_EQ(boundedMean, anchoredMean);
  EXPECT_EQ(boundedSpread, anchoredSpread);
  std::printf(
    "east border offset: anchored %.1f m (spread %.4f m), unanchored %.1f m (spread %.1f m)\n",
    anchoredMean,
    anchoredSpread,
    freeMean,
    freeSpread);
  // This part of Colorado stands about 600 m above the Alps patch: the patch
  // is lifted by that, one number for the whole border (measured 595 m).
  EXPECT_GT(anchoredMean, 300.0);
  EXPECT_LT(anchoredSpread, 0.01);
  // Unanchored, the spread gradient correction carries the far side a further
  // 265 m and leans it (spread 18 m): the drift that adds up patch by patch.
  EXPECT_GT(std::abs(freeMean - anchoredMean), 100.0);
  EXPECT_GT(freeSpread, 10.0 * std::max(anchoredSpread, 0.1));
}

TEST(PatchMerge, ShepardIsExactOnTheSeamAndFadesWithoutAStep)
{
  const Heightfield& dem = alps();
  const int tw = 240, th = 200;
  const Heightfield base = crop(dem, 0, 0, tw, th);
  const int px = 80, py = 50;
  // The terrain's own heights plus 400 m: the mismatch is -400 everywhere, so
  // the Shepard correction is exactly -400 times the fall-off.
  Heightfield patch = crop(dem, px, py, 96, 96);
  for (float& z : patch.z)
    z += 400.0f;
  Heightfield terrain = base;
  std::vector<std::uint8_t> filled(terrain.size(), 0);
  for (int j = 0; j < th; ++j)
    for (int i = 0; i < tw; ++i)
      filled[terrain.index(i, j)] = i < 110;
  MergeOptions options;
  options.mode = MergeMode::Shepard;
  options.shepardRadius = 20.0;
  PatchMerger merger;
  const MergeResult r = merger.merge(terrain, filled, patch, px, py, nullptr, options);
  // Correction = merged - patch on new cells.
  double maxCorrection = 0.0, maxStep = 0.0;
  int farCells = 0;
  for (int j = 0; j < r.height; ++j)
    for (int i = 0; i < r.width; ++i)
    {
      if (!r.takeNew[j * r.width + i])
        continue;
      const double c = terrain.at(r.x0 + i, r.y0 + j) - patch.at(r.x0 + i - px, r.y0 + j - py);
      maxCorrection = std::max(maxCorrection, std::abs(c));
      if (i + 1 < r.width && r.takeNew[j * r.width + i + 1])
      {
        const double c2 =
          terrain.at(r.x0 + i + 1, r.y0 + j) - patch.at(r.x0 + i + 1 - px, r.y0 + j - py);
        maxStep = std::max(maxStep, std::abs(c2 - c));
      }
      // Beyond the radius (columns far right of the overlap) nothing changes.
      if (r.x0 + i >= 110 + 21 + 1)
      {
        EXPECT_EQ(c, 0.0);
        ++farCells;
      }
    }
  EXPECT_GT(farCells, 1000);
  EXPECT_NEAR(maxCorrection, 400.0, 1e-3);
  // Spread over 20 cells with a C1 fall-off: no step larger than a tenth of it
  // (a hard cut-off at the radius would step by the full correction).
  EXPECT_LT(maxStep, 0.1 * maxCorrection);
  // On seam cells taken from the patch, the height is the old terrain's.
  int seamChecked = 0;
  for (int j = 0; j < r.height; ++j)
    for (int i = 0; i < r.width; ++i)
    {
      const std::size_t k = j * r.width + i;
      if (r.takeNew[k] && r.seam[k])
      {
        EXPECT_NEAR(terrain.at(r.x0 + i, r.y0 + j), base.at(r.x0 + i, r.y0 + j), 1e-3);
        ++seamChecked;
      }
    }
  EXPECT_GT(seamChecked, 40);
}

TEST(PatchMerge, ClippingOutsideAndZeroOverlap)
{
  const Heightfield patch = crop(alps(), 10, 10, 32, 32);
  Heightfield terrain(100, 80, 0.0f);
  terrain.cellX = patch.cellX;
  terrain.cellY = patch.cellY;
  std::vector<std::uint8_t> filled(terrain.size(), 0);
  PatchMerger merger;
  EXPECT_THROW(merger.merge(terrain, filled, patch, 100, 0, nullptr), Error);
  EXPECT_THROW(merger.merge(terrain, filled, patch, -32, 5, nullptr), Error);
  EXPECT_THROW(merger.seamCost(terrain, filled, patch, 0, 80, nullptr), Error);
  std::vector<std::uint8_t> wrongSize(10, 0);
  EXPECT_THROW(merger.merge(terrain, wrongSize, patch, 0, 0, nullptr), Error);
  // Zero overlap (empty terrain), partly outside: the visible part is copied.
  const MergeResult r = merger.merge(terrain, filled, patch, -10, 60, nullptr);
  EXPECT_EQ(r.x0, 0);
  EXPECT_EQ(r.y0, 60);
  EXPECT_EQ(r.width, 22);
  EXPECT_EQ(r.height, 20);
  EXPECT_EQ(r.overlapCells, 0u);
  EXPECT_EQ(r.cutEdges, 0);
  EXPECT_EQ(r.cutCost, 0.0);
  EXPECT_EQ(r.newCells, 22u * 20u);
  for (int j = 60; j < 80; ++j)
    for (int i = 0; i < 22; ++i)
    {
      EXPECT_EQ(terrain.at(i, j), patch.at(i + 10, j - 60));
      EXPECT_EQ(filled[terrain.index(i, j)], 1);
    }
  EXPECT_EQ(filled[terrain.index(22, 60)], 0);
  EXPECT_EQ(filled[terrain.index(0, 59)], 0);
  EXPECT_THROW(parseMergeMode("blend"), Error);
  EXPECT_EQ(parseMergeMode("shepard"), MergeMode::Shepard);
}

TEST(PatchMerge, NodataNeverEntersTheResult)
{
  const Heightfield& dem = colorado();
  Heightfield terrain = crop(dem, 0, 0, 160, 120);
  std::vector<std::uint8_t> filled(terrain.size(), 0);
  for (int j = 0; j < 120; ++j)
    for (int i = 0; i < 160; ++i)
    {
      filled[terrain.index(i, j)] = i < 70;
      if (i >= 40 && i < 70 && j % 7 == 0)
        terrain.at(i, j) = std::numeric_limits<float>::quiet_NaN(); // filled but nodata
    }
  Heightfield patch = crop(alps(), 30, 30, 64, 64);
  patch.cellX = terrain.cellX;
  patch.cellY = terrain.cellY;
  patch.valid.assign(patch.size(), 1);
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 64; ++i)
      if ((i + j) % 11 == 0 || (i > 40 && j > 40))
      {
        patch.valid[patch.index(i, j)] = 0;
        patch.at(i, j) = std::numeric_limits<float>::quiet_NaN();
      }
  for (MergeMode mode : { MergeMode::Cut, MergeMode::Poisson, MergeMode::Shepard, MergeMode::New })
  {
    SCOPED_TRACE(mergeModeName(mode));
    Heightfield t = terrain;
    std::vector<std::uint8_t> f = filled;
    MergeOptions options;
    options.mode = mode;
    PatchMerger merger;
    const MergeResult r = merger.merge(t, f, patch, 45, 20, nullptr, options);
    EXPECT_GT(r.newCells, 1000u);
    for (int j = 0; j < r.height; ++j)
      for (int i = 0; i < r.width; ++i)
      {
        const std::size_t tk = t.index(r.x0 + i, r.y0 + j);
        if (r.takeNew[j * r.width + i])
        {
          ASSERT_TRUE(std::isfinite(t.z[tk])) << i << "," << j;
          ASSERT_TRUE(patch.isValid(r.x0 + i - 45, r.y0 + j - 20));
        }
        else if (!filled[tk])
        {
          // Neither side had data: still empty.
          EXPECT_EQ(f[tk], 0);
        }
      }
  }
}

TEST(PatchMerge, DryRunMatchesMergeAndLeavesTerrainAlone)
{
  const Heightfield& dem = alps();
  Heightfield terrain = crop(dem, 0, 0, 200, 160);
  std::vector<std::uint8_t> filled(terrain.size(), 0);
  for (int j = 0; j < 160; ++j)
    for (int i = 0; i < 200; ++i)
      filled[terrain.index(i, j)] = i < 100 || j < 40;
  const Heightfield patch = crop(dem, 220, 180, 80, 80);
  std::vector<std::uint8_t> core(patch.size(), 0);
  for (int j = 30; j < 50; ++j)
    for (int i = 5; i < 25; ++i) // inside the overlap: must come from the patch
      core[patch.index(i, j)] = 1;
  const Heightfield before = terrain;
  const std::vector<std::uint8_t> filledBefore = filled;
  PatchMerger merger;
  const MergeResult dry = merger.seamCost(terrain, filled, patch, 80, 20, &core);
  EXPECT_EQ(terrain.z, before.z);
  EXPECT_EQ(filled, filledBefore);
  EXPECT_GT(dry.cutCost, 0.0);
  EXPECT_NEAR(dry.normalisedCost, dry.cutCost / dry.cutEdges, 1e-12);
  const MergeResult wet = merger.merge(terrain, filled, patch, 80, 20, &core);
  EXPECT_EQ(wet.cutCost, dry.cutCost);
  EXPECT_EQ(wet.takeNew, dry.takeNew);
  for (int j = 30; j < 50; ++j)
    for (int i = 5; i < 25; ++i)
    {
      const int ri = 80 + i - wet.x0, rj = 20 + j - wet.y0;
      EXPECT_EQ(wet.takeNew[rj * wet.width + ri], 1);
    }
  // Old cells never change.
  for (std::size_t k = 0; k < terrain.size(); ++k)
    if (filledBefore[k])
    {
      const int i = static_cast<int>(k % 200), j = static_cast<int>(k / 200);
      const int ri = i - wet.x0, rj = j - wet.y0;
      const bool tookNew =
        ri >= 0 && rj >= 0 && ri < wet.width && rj < wet.height && wet.takeNew[rj * wet.width + ri];
      if (!tookNew)
      {
        ASSERT_EQ(terrain.z[k], before.z[k]);
      }
    }
}

TEST(PatchMerge, MergeWithTheDryRunsCutEqualsAFreshMerge)
{
  // The synthesiser ranks candidates by dry runs and merges the winner with the
  // cut it already has: the terrain must come out exactly as if cut again.
  const Heightfield& dem = alps();
  Heightfield a = crop(dem, 0, 0, 200, 160);
  std::vector<std::uint8_t> filledA(a.size(), 0);
  for (int j = 0; j < 160; ++j)
    for (int i = 0; i < 200; ++i)
      filledA[a.index(i, j)] = i < 100 || j < 40;
  Heightfield b = a;
  std::vector<std::uint8_t> filledB = filledA;
  const Heightfield patch = crop(dem, 220, 180, 80, 80);
  PatchMerger merger;
  const MergeResult dry = merger.seamCost(b, filledB, patch, 80, 20, nullptr);
  const MergeResult fresh = merger.merge(a, filledA, patch, 80, 20, nullptr);
  const MergeResult reused = merger.merge(b, filledB, patch, 80, 20, nullptr, {}, &dry);
  EXPECT_EQ(a.z, b.z);
  EXPECT_EQ(filledA, filledB);
  EXPECT_EQ(reused.takeNew, fresh.takeNew);
  EXPECT_EQ(reused.seam, fresh.seam);
  EXPECT_EQ(reused.cutCost, fresh.cutCost);
  EXPECT_EQ(reused.newCells, fresh.newCells);
  // A cut from another placement is refused, not misused.
  EXPECT_THROW(merger.merge(b, filledB, patch, 81, 20, nullptr, {}, &dry), Error);
}
