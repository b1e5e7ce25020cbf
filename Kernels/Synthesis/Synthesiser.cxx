#include "Synthesiser.h"

#include "../Core/Error.h"
#include "../Core/Grid.h"
#include "../Core/Memory.h"
#include "../Core/Random.h"
#include "PatchPlacement.h"
#include "TileRecord.h"
#include "Tiling.h"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <memory>

namespace tsynth
{
namespace
{

using Clock = std::chrono::steady_clock;

// A tiled synthesis reports its tiles' placement as this share of its
// progress, the finishing of the whole output as the rest.
constexpr double kTiledPlacementShare = 0.9;
// ... in two passes over the tiles: feature patches, then the fill.
constexpr std::size_t kTiledPasses = 2;

double secondsSince(Clock::time_point t0)
{
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

} // namespace

namespace
{

// A tile's options: the whole run's, with the tile's own seed (from the run's
// seed and the tile's place), its region's style labels, and its progress as
// its share of the run's.
SynthesisOptions tileOptions(const SynthesisOptions& o,
  const SynthesisTile& t,
  int outputWidth,
  std::size_t done,
  std::size_t tiles)
{
  SynthesisOptions to = o;
  to.tileSize = 0;
  to.seed = derivedSeed(o.seed, kStreamTile, t.index);
  if (!o.regionLabels.empty())
  {
    to.regionLabels.clear();
    for (int j = 0; j < t.regionHeight; ++j)
    {
      const auto row = o.regionLabels.begin() +
        static_cast<std::ptrdiff_t>(rowMajor(t.regionX0, t.regionY0 + j, outputWidth));
      to.regionLabels.insert(to.regionLabels.end(), row, row + t.regionWidth);
    }
  }
  const ProgressReport whole = o.progress;
  to.progress = [whole, done, tiles](double f, const std::string& stage)
  {
    const double share = kTiledPlacementShare / static_cast<double>(tiles);
    reportProgress(whole, share * (static_cast<double>(done) + f), stage);
  };
  return to;
}

// What a rank that failed a tile shares in place of its outcomes, before the
// sentence that says why (outcomes never start with it: they start with a count).
const std::string kFailedTile = "tsynth: failed tile\n";

// Everything the tiles of one tiled synthesis share.
struct TiledRun
{
  const SynthesisTarget& target;
  const std::vector<const Heightfield*>& exemplars;
  const std::vector<const FeatureGraph*>& graphs;
  const SynthesisOptions& o;
  std::vector<SynthesisTile> tiles;
  PatchMatcher& matcher;
  PatchPlacement& whole;
  std::vector<FeatureSite> sites;
  SynthesisTimings timings;
  std::vector<TileTiming> tileTimings;
  double waited = 0.0;

  // This run's record (SynthesisOptions::keepRecord), else null.
  std::shared_ptr<PlacementRecord> record;
  std::size_t takenOver = 0;

  // The previous run's outcome of tile k in this pass (packOutcome's bytes),
  // if its inputs were these (TileRecord.h); else null.
  const std::string* recorded(TilePass pass, std::size_t k, std::uint64_t inputs) const
  {
    if (o.previous == nullptr)
    {
      return nullptr;
    }
    const std::vector<RecordedTile>& done = o.previous->tiles[static_cast<std::size_t>(pass)];
    return k < done.size() && done[k].inputs == inputs ? &done[k].outcome : nullptr;
  }

  // Places tile k in this pass, on the whole output as it stands, or takes its
  // outcome over from the previous run's record when its inputs are the same.
  TileOutcome place(TilePass pass, std::size_t k)
  {
    const SynthesisTile& t = tiles[k];
    const auto start = Clock::now();
    const std::clock_t cpuStart = std::clock();
    const SynthesisTarget part = regionTarget(target, t);
    const Heightfield known = whole.knownIn(t);
    const std::vector<FeatureSite> own =
      pass == TilePass::Features ? whole.sitesOf(t, sites) : std::vector<FeatureSite>();
    const std::size_t done = (pass == TilePass::Fill ? tiles.size() : 0) + k;
    const SynthesisOptions to =
      tileOptions(o, t, target.field.width, done, kTiledPasses * tiles.size());
    const bool keyed = record != nullptr || o.previous != nullptr;
    const std::uint64_t inputs =
      keyed ? tileInputsKey(pass, t, part, known, own, to.regionLabels, o.patchSize) : 0;
    const std::string* previous = recorded(pass, k, inputs);
    TileOutcome outcome =
      previous != nullptr ? unpackOutcome(*previous) : placeAnew(pass, t, k, part, known, own, to);
    takenOver += previous != nullptr ? 1 : 0;
    if (record != nullptr)
    {
      record->tiles[static_cast<std::size_t>(pass)][k] = { inputs,
        previous != nullptr ? *previous : packOutcome(outcome) };
    }
    tileTimings.push_back({ t.column,
      t.row,
      t.colour,
      pass == TilePass::Fill,
      secondsSince(start),
      static_cast<double>(std::clock() - cpuStart) / CLOCKS_PER_SEC,
      previous != nullptr });
    return outcome;
  }

  // Places tile t (number k) in this pass on its part of the target, with
  // the known cells of its region and its own feature sites.
  TileOutcome placeAnew(TilePass pass,
    const SynthesisTile& t,
    std::size_t k,
    const SynthesisTarget& part,
    const Heightfield& known,
    const std::vector<FeatureSite>& own,
    const SynthesisOptions& to)
  {
    auto t0 = Clock::now();
    PatchPlacement tile(part, &matcher, graphs, to, &known);
    tile.boundHeights(exemplars);
    tile.setTypicalNoise(matcher.dense().typicalNoise());
    timings.setup += secondsSince(t0);
    t0 = Clock::now();
    std::vector<std::uint8_t> border;
    if (pass == TilePass::Features)
    {
      tile.placeFeatures(own);
    }
    else
    {
      // The fill keeps its region less its inner border: there its patches
      // could not see what lies just past the region (other tiles' feature
      // patches), so a later tile fills it, seeing both sides; known cells
      // there stay as they are.
      border = innerBorder(t, target.field.width, target.field.height, o.patchSize);
      std::vector<std::uint8_t> frozen(border.size(), 0);
      for (std::size_t c = 0; c < border.size(); ++c)
      {
        frozen[c] = border[c] != 0 && known.isValid(c) ? 1 : 0;
      }
      tile.freeze(std::move(frozen));
      tile.fill();
    }
    TileOutcome outcome = tile.outcome(k, border);
    (pass == TilePass::Features ? timings.features : timings.fill) += secondsSince(t0);
    return outcome;
  }

  // One step: the tiles [first, last) of one colour class in this pass, this
  // process's share placed here, everyone's shared, all taken over in
  // schedule order.
  void step(TilePass pass, std::size_t first, std::size_t last)
  {
    const SynthesisOptions::TileSharing& share = o.sharing;
    if (share.ranks <= 1)
    {
      for (std::size_t k = first; k < last; ++k)
      {
        whole.adopt(tiles[k], place(pass, k));
      }
      return;
    }
    // A tile that fails here fails every rank, with the same sentence, after
    // the gathering they all wait in: no rank is left waiting for this one.
    std::vector<TileOutcome> outcomes;
    std::string failure;
    for (std::size_t k = first; k < last && failure.empty(); ++k)
    {
      if ((k - first) % static_cast<std::size_t>(share.ranks) ==
        static_cast<std::size_t>(share.rank))
      {
        try
        {
          outcomes.push_back(place(pass, k));
        }
        catch (const std::exception& e)
        {
          failure = "Tile " + std::to_string(tiles[k].column) + ", " +
            std::to_string(tiles[k].row) + " (rank " + std::to_string(share.rank) +
            ") failed: " + e.what();
        }
      }
    }
    const auto gathering = Clock::now();
    const std::vector<std::string> all =
      share.allGather(failure.empty() ? writeOutcomes(outcomes) : kFailedTile + failure);
    waited += secondsSince(gathering);
    outcomes.clear();
    for (const std::string& bytes : all)
    {
      if (bytes.compare(0, kFailedTile.size(), kFailedTile) == 0)
      {
        throw Error(bytes.substr(kFailedTile.size()));
      }
      for (TileOutcome& outcome : readOutcomes(bytes))
      {
        outcomes.push_back(std::move(outcome));
      }
    }
    std::sort(outcomes.begin(),
      outcomes.end(),
      [](const TileOutcome& a, const TileOutcome& b) { return a.tile < b.tile; });
    if (outcomes.size() != last - first)
    {
      throw Error("The processes of this tiled synthesis placed " +
        std::to_string(outcomes.size()) + " of the " + std::to_string(last - first) +
        " tiles of a step: they disagree on the tile grid.");
    }
    for (const TileOutcome& outcome : outcomes)
    {
      whole.adopt(tiles[outcome.tile], outcome);
    }
  }
};

// Tiling.h: the tiles in their fixed order place their feature patches, then
// in the same order fill what is left, each on its region with what the
// tiles before it wrote held as known; then the whole output is finished at
// once, as an untiled synthesis is. Features first, over all tiles, as
// without tiles: a tile's fill would otherwise cover the strokes in its halo
// before the next tile's feature patches could lay them.
SynthesisResult synthesiseTiled(const SynthesisTarget& target,
  const std::vector<const Heightfield*>& exemplars,
  const std::vector<const FeatureGraph*>& graphs,
  SynthesisOptions& o)
{
  auto t0 = Clock::now();
  reportProgress(o.progress, 0.0, "setup");
  auto matcher = makeSynthesisMatcher(exemplars, graphs, o);
  PatchPlacement whole(target, nullptr, graphs, o);
  whole.boundHeights(exemplars);
  TiledRun run{ target,
    exemplars,
    graphs,
    o,
    tileSchedule(target.field.width, target.field.height, o.tileSize, o.patchSize),
    *matcher,
    whole,
    whole.sitesInOrder(),
    {},
    {},
    0.0,
    nullptr,
    0 };
  if (o.keepRecord)
  {
    run.record = std::make_shared<PlacementRecord>(emptyRecord(target, exemplars, o));
    for (std::vector<RecordedTile>& pass : run.record->tiles)
    {
      pass.resize(run.tiles.size());
    }
  }
  run.timings.setup = secondsSince(t0);
  for (TilePass pass : { TilePass::Features, TilePass::Fill })
  {
    std::size_t first = 0;
    while (first < run.tiles.size())
    {
      std::size_t last = first;
      while (last < run.tiles.size() && run.tiles[last].colour == run.tiles[first].colour)
      {
        ++last;
      }
      run.step(pass, first, last);
      first = last;
    }
  }
  t0 = Clock::now();
  const std::string backend = matcher->backendName();
  const std::vector<std::string> matcherWarnings = matcher->warnings();
  matcher.reset();
  o.pool.reset(); // the pool too, unless the caller holds it
  whole.report(kTiledPlacementShare, "finishing");
  whole.releasePlacement(); // as untiled: the finishing's fields take that memory
  returnFreedMemory();
  SynthesisResult r = whole.finish();
  run.timings.finish = secondsSince(t0);
  r.timings = run.timings;
  r.tiles = std::move(run.tileTimings);
  r.waitedSeconds = run.waited;
  r.record = std::move(run.record);
  r.tilesTakenOver = run.takenOver;
  r.backend = backend;
  r.warnings.insert(r.warnings.begin(), matcherWarnings.begin(), matcherWarnings.end());
  r.warnings.insert(r.warnings.begin(), target.warnings.begin(), target.warnings.end());
  return r;
}

// Throws tsynth::Error if the options' tile records cannot be used: shared
// among processes, or a previous record made for another run (recordMismatch).
void checkRecordUse(const SynthesisTarget& target,
  const std::vector<const Heightfield*>& exemplars,
  const SynthesisOptions& o)
{
  if ((o.previous != nullptr || o.keepRecord) && o.sharing.ranks > 1)
  {
    throw Error("Re-synthesising an edit from a tile record runs in one process, not " +
      std::to_string(o.sharing.ranks) + ".");
  }
  if (o.previous != nullptr)
  {
    const std::string why = recordMismatch(*o.previous, target, exemplars, o);
    if (!why.empty())
    {
      throw Error(why);
    }
  }
}

} // namespace

SynthesisResult synthesise(const SynthesisTarget& target,
  const std::vector<const Heightfield*>& exemplars,
  const std::vector<const FeatureGraph*>& graphs,
  SynthesisOptions o)
{
  if (exemplars.empty())
  {
    throw Error("No exemplar: give at least one DEM to copy terrain from.");
  }
  if (!(o.fillSpacing > 0.0 && o.fillSpacing <= kMaxFillSpacing))
  {
    throw Error("The fill's windows must stand more than 0 and at most " +
      std::to_string(kMaxFillSpacing) + " patches apart, not " + std::to_string(o.fillSpacing) +
      ".");
  }
  if (target.field.width < o.patchSize || target.field.height < o.patchSize)
  {
    throw Error("The output (" + std::to_string(target.field.width) + " x " +
      std::to_string(target.field.height) + " cells) is smaller than one patch (" +
      std::to_string(o.patchSize) + ").");
  }
  if (!o.regionLabels.empty())
  {
    if (o.regionLabels.size() != target.field.size())
    {
      throw Error("The region labels must cover the output grid (" +
        std::to_string(target.field.width) + " x " + std::to_string(target.field.height) +
        " cells).");
    }
    for (std::size_t r = 0; r < o.regionExemplars.size(); ++r)
    {
      for (int e : o.regionExemplars[r])
      {
        if (e < 0 || static_cast<std::size_t>(e) >= exemplars.size())
        {
          throw Error("Region " + std::to_string(r) + " names exemplar " + std::to_string(e) +
            ", but there are " + std::to_string(exemplars.size()) + " exemplars.");
        }
      }
    }
  }
  if (o.tileSize == 0 && (o.previous != nullptr || o.keepRecord))
  {
    throw Error("Re-synthesising an edit works tile by tile: give a tile size.");
  }
  if (o.tileSize > 0)
  {
    if (o.placementLimit != kAllPlacements)
    {
      throw Error("Stepping through the placements works on one piece: give a tile size of 0.");
    }
    checkRecordUse(target, exemplars, o);
    return synthesiseTiled(target, exemplars, graphs, o);
  }
  auto t0 = Clock::now();
  reportProgress(o.progress, 0.0, "setup");
  auto matcher = makeSynthesisMatcher(exemplars, graphs, o);
  checkCancellation(); // the set-up's parts take a tenth of a second each at 1024^2
  PatchPlacement state(target, matcher.get(), graphs, o);
  checkCancellation();
  state.boundHeights(exemplars);
  state.setTypicalNoise(matcher->dense().typicalNoise());
  const double setup = secondsSince(t0);
  state.report(0.1, "setup");
  t0 = Clock::now();
  state.placeFeatures();
  const double features = secondsSince(t0);
  t0 = Clock::now();
  state.fill();
  const double fill = secondsSince(t0);
  t0 = Clock::now();
  const std::string backend = matcher->backendName();
  const std::vector<std::string> matcherWarnings = matcher->warnings();
  state.releasePlacement();
  matcher.reset();
  o.pool.reset();      // the pool too, unless the caller holds it
  returnFreedMemory(); // the finishing's fields take what the placement held
  SynthesisResult r = o.placementLimit == kAllPlacements ? state.finish() : state.unfinished();
  r.timings = { setup, features, fill, secondsSince(t0) };
  r.backend = backend;
  r.warnings.insert(r.warnings.begin(), matcherWarnings.begin(), matcherWarnings.end());
  r.warnings.insert(r.warnings.begin(), target.warnings.begin(), target.warnings.end());
  return r;
}

} // namespace tsynth
