// Local re-synthesis of an edited sketch. A tiled synthesis (Tiling.h) can
// keep a record of what each tile's placement made, in each pass, beside a
// key of everything that placement read: its part of the target (fields,
// scalars and the sketched lines as they fall on its region's cells), the
// cells earlier tiles left in its region, its feature sites, its style labels
// and its place in the grid. The next run of the same exemplars and options
// takes a tile's outcome from the record when that key is the same, and
// places the tile again otherwise. Placement is deterministic, so a tile
// taken over is bit for bit what placing it again would make, and the
// terrain equals a full synthesis of the edited sketch everywhere: an edit
// re-places the tiles whose region it reaches, the later tiles whose known
// cells those change, and no other. The whole terrain is then finished as
// always (Finishing.h).
#pragma once

#include "Synthesiser.h"
#include "Tiling.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace tsynth
{

// The two passes of a tiled synthesis over its tiles, in their order.
enum class TilePass
{
  Features = 0,
  Fill = 1
};
constexpr std::size_t kTilePasses = 2;

// One tile in one pass: the key of what its placement read, and what it made
// (packOutcome's bytes: a record of a large terrain stays as small in memory
// as on disk).
struct RecordedTile
{
  std::uint64_t inputs = 0;
  std::string outcome;
};

// Everything a tiled synthesis placed, for the next run of an edited sketch.
struct PlacementRecord
{
  // The grid: an edit keeps the output's size and cells, and the tile grid.
  int width = 0;
  int height = 0;
  double cellX = 0.0;
  double cellY = 0.0;
  int tileSize = 0;
  int patchSize = 0;
  std::uint64_t seed = 0;
  // Keys of the exemplars' contents, of the placement's other options, and
  // of the program's build (codeHash): any of them changed, no tile is the same.
  std::uint64_t exemplars = 0;
  std::uint64_t options = 0;
  std::uint64_t code = 0;
  // Per pass, per tile in schedule order (tileSchedule).
  std::vector<RecordedTile> tiles[kTilePasses];
};

// What a record holds in memory and on disk, in bytes: of a tiled synthesis
// of width x height cells (an estimate, for the memory estimate), and of a
// record at hand.
double tileRecordBytes(int width, int height, int tileSize, int patchSize);
double tileRecordBytes(const PlacementRecord& record);

// An empty record of a tiled run with these exemplars and options on this target.
PlacementRecord emptyRecord(const SynthesisTarget& target,
  const std::vector<const Heightfield*>& exemplars,
  const SynthesisOptions& o);

// Why a record cannot serve a run with these exemplars and options on this
// target, in one sentence (another grid, tile or patch size, seed, exemplars,
// placement options or build); empty when it can.
std::string recordMismatch(const PlacementRecord& record,
  const SynthesisTarget& target,
  const std::vector<const Heightfield*>& exemplars,
  const SynthesisOptions& o);

// A front end's automatic re-synthesis (the Terrain Synthesis filter, which
// keeps its last record): a tiled run in one process keeps its own record,
// and takes tiles from `last` when that record can serve it; any other run
// neither keeps nor takes one. Never refuses: a record that cannot serve is
// left unused, and the run is a full synthesis.
void useRecordIfItServes(SynthesisOptions& o,
  std::shared_ptr<const PlacementRecord> last,
  const SynthesisTarget& target,
  const std::vector<const Heightfield*>& exemplars);

// What a tile's placement in this pass reads besides the run's exemplars and
// options: its part of the target, the known cells of its region, its feature
// sites and its style labels (o.regionLabels over its region, may be empty),
// at this patch size.
std::uint64_t tileInputsKey(TilePass pass,
  const SynthesisTile& tile,
  const SynthesisTarget& part,
  const Heightfield& known,
  const std::vector<FeatureSite>& sites,
  const std::vector<int>& regionLabels,
  int patchSize);

// A tile's outcome as bytes and back, with only its kept cells (adopt reads
// no other). unpackOutcome throws tsynth::Error if the bytes are cut short.
std::string packOutcome(const TileOutcome& outcome);
TileOutcome unpackOutcome(const std::string& bytes);

// The record as bytes and back. readRecord throws tsynth::Error, one sentence
// naming `source`, if the bytes are not a whole record of this format.
std::string writeRecord(const PlacementRecord& record);
PlacementRecord readRecord(const std::string& bytes, const std::string& source);

// The record kept beside a terrain file: OUT with its extension replaced by
// ".tiles" (terrain.tif: terrain.tiles).
std::string recordPathOf(const std::string& terrainPath);

// Writes the record (OutputFile: complete or not at all) and reads one back
// (tsynth::Error, one sentence, if it is missing or damaged).
void saveRecord(const PlacementRecord& record, const std::string& path);
PlacementRecord loadRecord(const std::string& path);

} // namespace tsynth
