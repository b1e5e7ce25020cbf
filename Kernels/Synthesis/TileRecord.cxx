#include "TileRecord.h"

#include "../Core/ContentHash.h"
#include "../Core/Error.h"
#include "../Core/OutputFile.h"
#include "FeatureOrder.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>

namespace tsynth
{
namespace
{

// The record file's first bytes, and its layout's version: a record of
// another layout is refused, never misread.
const std::string kRecordMagic = "TerrainSynthesis tile record\n";
constexpr std::uint64_t kRecordVersion = 1;
constexpr std::size_t kBitsPerByte = 8;
// A packed outcome per cell of its tile's region: a bit for whether the tile
// keeps it, and for the cells it keeps a height, a patch number, a seam flag
// and a match cost. About half of a region's cells are kept, over both passes
// (at 1024^2 in tiles of 256 with patches of 80: 46%, a record of 27.7 MB,
// estimated 1.08 times that); fewer in tiles of two patches, whose halo is a
// larger share (384 x 256 in tiles of 64: estimated 1.47 times). Counted as
// 0.55: the estimate errs high.
constexpr double kKeptShareOfRegion = 0.55;
constexpr double kRecordBytesPerRegionCell = 1.0 / kBitsPerByte +
  kKeptShareOfRegion *
    (sizeof(float) + sizeof(std::int32_t) + sizeof(std::uint8_t) + sizeof(float));

std::uint64_t exemplarsKey(const std::vector<const Heightfield*>& exemplars)
{
  ContentHasher h;
  h.value(exemplars.size());
  for (const Heightfield* e : exemplars)
  {
    hashHeightfield(h, *e);
  }
  return h.digest();
}

// The options a tile's placement reads besides the patch size, the seed and
// the tile grid (kept apart, to name them when they differ). The backend is
// left out (every backend gives the same bits), and so are the finishing's
// options: the finishing runs anew over the whole terrain.
std::uint64_t optionsKey(const SynthesisOptions& o)
{
  ContentHasher h;
  h.value(o.merge);
  h.value(o.fill);
  h.value(o.k);
  h.value(o.fillK);
  h.value(o.fillSpacing);
  h.value(o.verticalOffset);
  h.value(o.repetitionPenalty);
  h.value(o.regionLabels.empty());
  h.value(o.regionExemplars.size());
  for (const std::vector<int>& served : o.regionExemplars)
  {
    h.values(served);
  }
  return h.digest();
}

// The lines of one type (or of every type) as rasteriseChains lays them on the
// part's grid: all a tile's placement reads of the target's graph.
std::vector<std::uint8_t> linesOfType(const SynthesisTarget& part, const FeatureType* type)
{
  FeatureGraph lines = part.graph;
  if (type != nullptr)
  {
    lines.chains.erase(std::remove_if(lines.chains.begin(),
                         lines.chains.end(),
                         [&](const FeatureChain& c) { return c.type != *type; }),
      lines.chains.end());
  }
  return rasteriseChains(lines, part.field.width, part.field.height);
}

// A site's place and shape. Its node and chain numbers are left out: no
// placement reads them, and an edit elsewhere in the sketch renumbers them.
void hashSite(ContentHasher& h, const FeatureSite& s)
{
  h.value(s.centre.x);
  h.value(s.centre.y);
  h.value(s.type);
  h.value(s.kind);
  h.value(s.arms.size());
  for (const ControlPoint& arm : s.arms)
  {
    h.value(arm.position.x);
    h.value(arm.position.y);
    h.value(arm.angle);
    h.value(arm.reached);
  }
}

// Bytes in native order, as Tiling.cxx shares outcomes between processes.
class RecordWriter
{
public:
  template<class T>
  void value(const T& v)
  {
    static_assert(std::is_trivially_copyable_v<T>);
    out_.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  template<class T>
  void values(const std::vector<T>& v)
  {
    value(static_cast<std::uint64_t>(v.size()));
    out_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  // For transferRecord: a value, a string (its length, then its bytes), and
  // a vector's elements after their count, each written by `item`.
  template<class T>
  void operator()(const T& v)
  {
    value(v);
  }
  void operator()(const std::string& s)
  {
    value(static_cast<std::uint64_t>(s.size()));
    out_.append(s);
  }
  template<class T, class F>
  void each(const std::vector<T>& v, F&& item)
  {
    value(static_cast<std::uint64_t>(v.size()));
    for (const T& x : v)
    {
      item(x);
    }
  }
  std::string& bytes() { return out_; }

private:
  std::string out_;
};

class RecordReader
{
public:
  RecordReader(const std::string& bytes, std::size_t end, std::string source)
    : bytes_(bytes)
    , end_(end)
    , source_(std::move(source))
  {
  }
  template<class T>
  T value()
  {
    T v{};
    take(&v, sizeof v);
    return v;
  }
  template<class T>
  std::vector<T> values()
  {
    const auto n = value<std::uint64_t>();
    if (n > (end_ - at_) / sizeof(T))
    {
      damaged();
    }
    std::vector<T> v(n);
    take(v.data(), n * sizeof(T));
    return v;
  }
  // For transferRecord: what RecordWriter's operator() and each() wrote.
  template<class T>
  void operator()(T& v)
  {
    v = value<T>();
  }
  void operator()(std::string& s)
  {
    s.resize(count());
    take(s.data(), s.size());
  }
  template<class T, class F>
  void each(std::vector<T>& v, F&& item)
  {
    v.resize(count());
    for (T& x : v)
    {
      item(x);
    }
  }
  void skip(std::size_t n)
  {
    if (n > end_ - at_)
    {
      damaged();
    }
    at_ += n;
  }
  bool atEnd() const { return at_ == end_; }
  [[noreturn]] void damaged() const
  {
    throw Error("The tile record " + source_ +
      " is damaged or cut short: synthesise the terrain anew, without it.");
  }

private:
  // A stored count of elements of a byte at least, refused when more than
  // the bytes left.
  std::size_t count()
  {
    const auto n = value<std::uint64_t>();
    if (n > end_ - at_)
    {
      damaged();
    }
    return static_cast<std::size_t>(n);
  }
  void take(void* to, std::size_t n)
  {
    if (n > end_ - at_)
    {
      damaged();
    }
    std::copy_n(bytes_.data() + at_, n, static_cast<char*>(to));
    at_ += n;
  }

  const std::string& bytes_;
  std::size_t end_;
  std::string source_;
  std::size_t at_ = 0;
};

} // namespace

// A tile's outcome: its kept cells as bits, then only those cells' values.
std::string packOutcome(const TileOutcome& o)
{
  RecordWriter w;
  const std::size_t cells = o.kept.size();
  std::vector<std::uint8_t> bits((cells + kBitsPerByte - 1) / kBitsPerByte, 0);
  std::vector<float> heights;
  std::vector<std::int32_t> ids;
  std::vector<std::uint8_t> seam;
  std::vector<float> cost;
  for (std::size_t c = 0; c < cells; ++c)
  {
    if (o.kept[c] == 0)
    {
      continue;
    }
    bits[c / kBitsPerByte] |= static_cast<std::uint8_t>(1u << (c % kBitsPerByte));
    heights.push_back(o.heights[c]);
    ids.push_back(o.patchId[c]);
    seam.push_back(o.seam[c]);
    cost.push_back(o.matchCost[c]);
  }
  w.value(static_cast<std::uint64_t>(o.tile));
  w.value(static_cast<std::uint64_t>(cells));
  w.values(bits);
  w.values(heights);
  w.values(ids);
  w.values(seam);
  w.values(cost);
  w.values(o.placements);
  w.value(o.anchoredMerges);
  return std::move(w.bytes());
}

TileOutcome unpackOutcome(const std::string& bytes)
{
  RecordReader in(bytes, bytes.size(), "in memory");
  TileOutcome o;
  o.tile = in.value<std::uint64_t>();
  const auto cells = in.value<std::uint64_t>();
  const std::vector<std::uint8_t> bits = in.values<std::uint8_t>();
  const std::vector<float> heights = in.values<float>();
  const std::vector<std::int32_t> ids = in.values<std::int32_t>();
  const std::vector<std::uint8_t> seam = in.values<std::uint8_t>();
  const std::vector<float> cost = in.values<float>();
  const std::size_t kept = heights.size();
  if (bits.size() != (cells + kBitsPerByte - 1) / kBitsPerByte || ids.size() != kept ||
    seam.size() != kept || cost.size() != kept)
  {
    in.damaged();
  }
  constexpr float kNone = std::numeric_limits<float>::quiet_NaN();
  o.kept.assign(cells, 0);
  o.heights.assign(cells, kNone);
  o.patchId.assign(cells, -1);
  o.seam.assign(cells, 0);
  o.matchCost.assign(cells, kNone);
  std::size_t k = 0;
  for (std::size_t c = 0; c < cells; ++c)
  {
    if ((bits[c / kBitsPerByte] >> (c % kBitsPerByte) & 1u) == 0)
    {
      continue;
    }
    if (k == kept)
    {
      in.damaged();
    }
    o.kept[c] = 1;
    o.heights[c] = heights[k];
    o.patchId[c] = ids[k];
    o.seam[c] = seam[k];
    o.matchCost[c] = cost[k];
    ++k;
  }
  if (k != kept)
  {
    in.damaged();
  }
  o.placements = in.values<Placement>();
  o.anchoredMerges = in.value<std::uint64_t>();
  if (!in.atEnd())
  {
    in.damaged();
  }
  return o;
}

namespace
{

std::string cellsText(double x, double y)
{
  std::ostringstream s;
  s << x;
  if (y != x)
  {
    s << " x " << y;
  }
  return s.str() + " m";
}

} // namespace

double tileRecordBytes(int width, int height, int tileSize, int patchSize)
{
  double regionCells = 0.0;
  for (const SynthesisTile& t : tileSchedule(width, height, tileSize, patchSize))
  {
    regionCells += static_cast<double>(t.regionWidth) * t.regionHeight;
  }
  return static_cast<double>(kTilePasses) * regionCells * kRecordBytesPerRegionCell;
}

double tileRecordBytes(const PlacementRecord& record)
{
  double bytes = 0.0;
  for (const std::vector<RecordedTile>& pass : record.tiles)
  {
    for (const RecordedTile& t : pass)
    {
      bytes += static_cast<double>(t.outcome.size() + sizeof t);
    }
  }
  return bytes;
}

PlacementRecord emptyRecord(const SynthesisTarget& target,
  const std::vector<const Heightfield*>& exemplars,
  const SynthesisOptions& o)
{
  PlacementRecord r;
  r.width = target.field.width;
  r.height = target.field.height;
  r.cellX = target.field.cellX;
  r.cellY = target.field.cellY;
  r.tileSize = o.tileSize;
  r.patchSize = o.patchSize;
  r.seed = o.seed;
  r.exemplars = exemplarsKey(exemplars);
  r.options = optionsKey(o);
  r.code = codeHash();
  return r;
}

std::string recordMismatch(const PlacementRecord& r,
  const SynthesisTarget& target,
  const std::vector<const Heightfield*>& exemplars,
  const SynthesisOptions& o)
{
  const Heightfield& f = target.field;
  if (r.width != f.width || r.height != f.height)
  {
    return "The previous terrain is " + std::to_string(r.width) + " x " + std::to_string(r.height) +
      " cells and this one " + std::to_string(f.width) + " x " + std::to_string(f.height) +
      ": re-synthesising an edit keeps the terrain's size.";
  }
  if (r.cellX != f.cellX || r.cellY != f.cellY)
  {
    return "The previous terrain's cells are " + cellsText(r.cellX, r.cellY) + " and this one's " +
      cellsText(f.cellX, f.cellY) + ": re-synthesising an edit keeps the cell size.";
  }
  if (r.tileSize != o.tileSize)
  {
    return "The previous terrain was synthesised in tiles of " + std::to_string(r.tileSize) +
      " cells, this run asks for " + std::to_string(o.tileSize) +
      ": re-synthesising an edit keeps the tile grid.";
  }
  if (r.patchSize != o.patchSize)
  {
    return "The previous terrain was synthesised with patches of " + std::to_string(r.patchSize) +
      " cells, this run with " + std::to_string(o.patchSize) +
      ": re-synthesising an edit keeps the patch size.";
  }
  if (r.seed != o.seed)
  {
    return "The previous terrain was synthesised with seed " + std::to_string(r.seed) +
      ", this run with " + std::to_string(o.seed) + ": re-synthesising an edit keeps the seed.";
  }
  if (r.exemplars != exemplarsKey(exemplars))
  {
    return "The previous terrain was synthesised from other exemplars (or the same at another "
           "cell size): re-synthesising an edit keeps the exemplars.";
  }
  if (r.options != optionsKey(o))
  {
    return "The previous terrain was synthesised with other placement options (merge, fill "
           "order, candidates, fill spacing, vertical offset, repetition or style regions): "
           "re-synthesising an edit keeps them.";
  }
  if (r.code == 0 || r.code != codeHash())
  {
    return "The previous terrain's tile record was written by another build of "
           "TerrainSynthesis, whose tiles may differ: synthesise the terrain anew.";
  }
  return {};
}

void useRecordIfItServes(SynthesisOptions& o,
  std::shared_ptr<const PlacementRecord> last,
  const SynthesisTarget& target,
  const std::vector<const Heightfield*>& exemplars)
{
  o.keepRecord = o.tileSize > 0 && o.sharing.ranks <= 1;
  const bool serves =
    o.keepRecord && last != nullptr && recordMismatch(*last, target, exemplars, o).empty();
  o.previous = serves ? std::move(last) : nullptr;
}

std::uint64_t tileInputsKey(TilePass pass,
  const SynthesisTile& tile,
  const SynthesisTarget& part,
  const Heightfield& known,
  const std::vector<FeatureSite>& sites,
  const std::vector<int>& regionLabels,
  int patchSize)
{
  ContentHasher h;
  h.value(pass);
  h.value(tile.index);
  h.value(tile.regionX0);
  h.value(tile.regionY0);
  h.value(tile.regionWidth);
  h.value(tile.regionHeight);
  hashHeightfield(h, part.field);
  h.values(part.weight);
  h.values(part.halfWidth);
  h.values(part.downstream);
  // Of the target's scalars a placement reads whether its sites crowd (from
  // the lines' spacing, a statistic of the whole sketch) and whether the field
  // is a DEM's; the raise factors only shaped the field, hashed above.
  h.value(featureSitesCrowd(part, patchSize));
  h.value(part.detailed);
  h.values(linesOfType(part, nullptr));
  for (FeatureType type : { FeatureType::Ridge, FeatureType::Valley })
  {
    h.values(linesOfType(part, &type));
  }
  hashHeightfield(h, known);
  h.value(sites.size());
  for (const FeatureSite& s : sites)
  {
    hashSite(h, s);
  }
  h.values(regionLabels);
  return h.digest();
}

namespace
{

// The record's fields in one order, for writing (S = RecordWriter, R = const
// PlacementRecord) and reading (S = RecordReader, R = PlacementRecord).
template<class S, class R>
void transferRecord(S& s, R& r)
{
  s(r.width);
  s(r.height);
  s(r.cellX);
  s(r.cellY);
  s(r.tileSize);
  s(r.patchSize);
  s(r.seed);
  s(r.exemplars);
  s(r.options);
  s(r.code);
  for (auto& pass : r.tiles)
  {
    s.each(pass,
      [&](auto& t)
      {
        s(t.inputs);
        s(t.outcome);
      });
  }
}

} // namespace

std::string writeRecord(const PlacementRecord& r)
{
  RecordWriter w;
  w.bytes() = kRecordMagic;
  w.value(kRecordVersion);
  transferRecord(w, r);
  ContentHasher check;
  check.bytes(w.bytes().data(), w.bytes().size());
  w.value(check.digest());
  return std::move(w.bytes());
}

PlacementRecord readRecord(const std::string& bytes, const std::string& source)
{
  if (bytes.compare(0, kRecordMagic.size(), kRecordMagic) != 0)
  {
    throw Error(source + " is not a TerrainSynthesis tile record.");
  }
  const std::size_t body = bytes.size() - std::min(bytes.size(), sizeof(std::uint64_t));
  RecordReader in(bytes, bytes.size(), source);
  in.skip(body);
  const auto checksum = in.value<std::uint64_t>();
  ContentHasher check;
  check.bytes(bytes.data(), body);
  if (bytes.size() < kRecordMagic.size() + sizeof checksum || check.digest() != checksum)
  {
    in.damaged();
  }
  RecordReader r(bytes, body, source);
  r.skip(kRecordMagic.size());
  if (r.value<std::uint64_t>() != kRecordVersion)
  {
    throw Error("The tile record " + source +
      " was written by another version of TerrainSynthesis: synthesise the terrain anew.");
  }
  PlacementRecord rec;
  transferRecord(r, rec);
  if (!r.atEnd())
  {
    r.damaged();
  }
  return rec;
}

std::string recordPathOf(const std::string& terrainPath)
{
  return std::filesystem::path(terrainPath).replace_extension(".tiles").string();
}

void saveRecord(const PlacementRecord& record, const std::string& path)
{
  OutputFile file(path);
  file.write(writeRecord(record));
  file.commit();
}

PlacementRecord loadRecord(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    throw Error("Cannot read the tile record " + path + ".");
  }
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad())
  {
    throw Error("Cannot read the tile record " + path + ".");
  }
  return readRecord(bytes, path);
}

} // namespace tsynth
