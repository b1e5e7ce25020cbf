// Everything between "files read" and synthesise(): the one set-up both the
// command line and the ParaView filter call, so that the same inputs give the
// same terrain whichever front end reads them. It names the sketch, turns
// poly-lines in metres into output cells, decides the output grid, resamples the
// exemplars to its cell size, finds their features, refuses what would not fit
// in memory, and builds the target.
#pragma once

#include "../Core/Heightfield.h"
#include "../Core/HeightfieldIO.h"
#include "../Core/Memory.h"
#include "../Core/PatchSize.h"
#include "../Features/FeatureGraph.h"
#include "../Features/Sketch.h"
#include "ExemplarCache.h"
#include "OptionLimits.h"
#include "Synthesiser.h"
#include "Target.h"

#include <cstddef>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace tsynth
{

// A poly-line sketch in METRES in the output's raster frame (DESIGN.md: the
// lower-left cell centre is (0, 0), x east, y north), as `tsynth features`
// writes them and as a ParaView user draws them over a DEM read at origin 0.
struct PolylineSketch
{
  std::vector<Polyline> lines; // points in metres; elevation in metres (NaN: none)
  // Size in metres (edge to edge: cells x cell size) of the raster the lines were
  // drawn on, e.g. the DEM whose features they are; 0 when unknown, and the
  // output then reaches half a patch past the lines' far end (polylineSize).
  double frameWidth = 0.0;
  double frameHeight = 0.0;
};

// Exactly one sketch: a colour (stroke map) or grey image, a DEM used as the
// target (heights in metres), or poly-lines in metres.
using SketchInput = std::variant<ColourImage, Heightfield, PolylineSketch>;

// A raster sketch read from a file or an image: one band that is not 8-bit is a
// DEM used as the target; anything else is a sketch image (grey or strokes).
bool rasterIsDemTarget(int bands, bool eightBit);

// What a front end calls the settings, so that messages name what to change
// (the command line's options or the filter's properties).
struct SetupOptionNames
{
  std::string size = "the output size";
  std::string cell = "the output cell size";
  std::string patch = "the patch size";
  std::string memory = "the memory budget";
};

// The output grid asked for; zeros mean "from the inputs".
struct GridRequest
{
  int width = 0; // cells; 0 0: the raster sketch's pixels, or the poly-lines' frame or extent
  int height = 0;
  double cellX = 0.0; // metres; 0: the first exemplar's cell size
  double cellY = 0.0;
};

struct OutputGrid
{
  int width = 0; // cells
  int height = 0;
  double cellX = 0.0; // metres
  double cellY = 0.0;
};

// What the output size is taken from when none is asked for: a raster sketch's
// pixels, or a poly-line sketch's bounding box and frame in metres.
struct SketchExtent
{
  bool polylines = false;
  int pixelsX = 0; // raster sketches
  int pixelsY = 0;
  double minX = 0.0; // poly-lines, metres
  double minY = 0.0;
  double maxX = 0.0;
  double maxY = 0.0;
  double frameWidth = 0.0;
  double frameHeight = 0.0;
};

SketchExtent rasterExtent(int pixelsX, int pixelsY);
// Throws tsynth::Error for a sketch without a single point.
SketchExtent polylineExtent(const PolylineSketch& sketch);
SketchExtent sketchExtent(const SketchInput& sketch);

// The grid a synthesis will produce (what the filter announces before it runs):
// the requested size and cell size where given; else the raster sketch's pixels,
// or for poly-lines their frame (or extent and half a patch) divided by the cell size; the cell
// size defaults to the first exemplar's (exemplarCellX/Y). Throws tsynth::Error
// with what was found and what to change for: a bad request, poly-lines whose
// extent gives an absurd output (coordinates in cells or degrees rather than
// metres, or outside the raster frame), an output smaller than one patch or
// larger than kMaxOutputSide.
OutputGrid outputGrid(const SketchExtent& sketch,
  const GridRequest& request,
  double exemplarCellX,
  double exemplarCellY,
  int patchSize,
  const SetupOptionNames& names = {});

// More cells a side than any machine holds the work arrays of (10^12 cells of
// about 128 bytes); sizes above it are typing errors.
constexpr int kMaxOutputSide = 1000000;

// Peak memory in bytes of a synthesis of width x height cells from exemplars of
// these cell counts (at the output's cell size): measured, with a margin, on
// 512^2 to 4096^2 outputs (DESIGN.md's machines; see Setup.cxx).
// With `openCl`, also what the OpenCL matcher holds: the runtime with its
// compiled kernels and the device's copy of the exemplar pool (on PoCL's CPU
// device both are host memory).
double synthesisMemoryEstimate(int width,
  int height,
  const std::vector<std::size_t>& exemplarCells,
  bool openCl = false);

// defaultMemoryBudget() and kDefaultMemoryFraction: Core/Memory.h.

// A sketch analysed on its own terms: its feature graph in its own pixels (a
// raster sketch) or on the output grid (poly-lines), and its heights for a grey
// map or a DEM.
struct AnalysedSketch
{
  FeatureGraph graph;
  int width = 0; // the pixels `graph` is drawn on
  int height = 0;
  bool hasHeights = false;
  Heightfield heights; // grey map or DEM (when hasHeights)
  std::string kind;    // "stroke map", "grey sketch", "DEM" or "poly-lines"
  std::vector<std::string> warnings;
};

// Grey maps and DEMs through PPA (ridges and valleys), stroke maps through
// thinning, poly-lines divided by the grid's cell size. A raster sketch smaller
// than one patch is refused (tsynth::Error).
// A raster sketch (an image or a DEM) is analysed at `rasterPatch` of its own
// pixels when given (> 0), else at patchSize: a preview reads the same lines
// from it as the synthesis it previews (SetupInputs::rasterSketchPatch).
AnalysedSketch analyseSketch(const SketchInput& sketch,
  const OutputGrid& grid,
  int patchSize,
  int rasterPatch = 0);

// The landform relief's bounds and default: OptionLimits.h.

struct SetupInputs
{
  std::vector<Heightfield> exemplars;     // heights in metres, with their cell sizes
  std::vector<std::string> exemplarNames; // for messages (file names); empty: "exemplar N"
  SketchInput sketch;
  GridRequest grid;
  int patchSize = kDefaultSynthesisPatch;
  double memoryBudget = 0.0; // bytes; 0: defaultMemoryBudget()
  // The backend the matcher is asked for: when it runs on OpenCL
  // (matchesOnOpenCl, asked only when the memory is checked), OpenCL's memory
  // counts too.
  Backend matcherBackend = Backend::OpenCL;
  std::uint64_t seed = 0; // breaks ties in the target (valley outlets)
  // Sketched ridges and valleys get this times the relief they are given to
  // stand out of the exemplars' own land (the exemplars' major ones', raised
  // on rugged land: LandformFieldOptions::standOut); a DEM target keeps its own.
  double landformRelief = kDefaultLandformRelief;
  // The patch size a raster sketch is analysed at, in its own pixels; 0: patchSize. A
  // preview (Preview.h) gives the whole synthesis' patch, so that both follow the same lines.
  int rasterSketchPatch = 0;
  // A feature candidate pool given from outside (the Terrain Candidate
  // Builder's table): used in place of the one prepared from the exemplars,
  // once checkGivenPool finds it fits them as resampled. Null: prepared.
  std::shared_ptr<const CandidatePool> pool;
  // Where what is computed from the exemplars alone is kept between runs
  // (ExemplarCache.h; defaultExemplarCacheDirectory()); empty: no cache.
  std::string cacheDirectory;
  // Tile records held while the synthesis runs (TileRecord.h), for the memory
  // estimate: its own record at this tile size (0: none kept), and the bytes of
  // the previous run's record it takes tiles from.
  int recordedTileSize = 0;
  double previousRecordBytes = 0.0;
  SetupOptionNames names;
};

// Everything synthesise() needs, and what the set-up found on the way.
struct SynthesisSetup
{
  std::vector<Heightfield> exemplars;        // at the output's cell size
  std::vector<FeatureGraph> graphs;          // their PPA ridges and valleys
  std::shared_ptr<const CandidatePool> pool; // their feature candidates (SynthesisOptions::pool)
  ExemplarCacheUse cache;                    // whether these came from the exemplar cache
  SynthesisTarget target;                    // on the output grid
  LandformStatistics landform;               // the exemplars' cross-sections the target uses
  OutputGrid grid;
  // What the pool and the target were prepared for: synthesise(setup, options)
  // refuses options that ask for another patch size or seed.
  int patchSize = 0;
  std::uint64_t seed = 0;
  std::string sketchKind;      // as AnalysedSketch::kind
  double memoryEstimate = 0.0; // bytes
  double memoryBudget = 0.0;   // bytes, the one applied
  // The set-up's own warnings (sketch, resampling); the target's travel in
  // target.warnings, which synthesise() passes on.
  std::vector<std::string> warnings;

  std::vector<const Heightfield*> exemplarPointers() const;
  std::vector<const FeatureGraph*> graphPointers() const;
};

// A warning when the target's strokes (a DEM target's ridges and valleys) are
// closer together than patches of this size can draw them at their own scale,
// naming the spacing found and the patch that would follow them.
std::optional<std::string> finenessWarning(const SynthesisTarget& target, int patchSize, bool dem);

// The whole set-up. Throws tsynth::Error, one sentence saying what was found and
// what to change: no exemplar, a bad grid (see outputGrid), a sketch smaller
// than a patch, a synthesis estimated above the memory budget (before any
// exemplar is resampled or analysed), a sketch with nothing drawn (no feature
// line and no relief: a blank image, a flat DEM), an exemplar smaller than a
// patch at the output's cell size.
SynthesisSetup prepareSynthesis(SetupInputs inputs);

// The grid prepareSynthesis() will make of these inputs, without preparing
// anything (what the options laid on the grid, such as style regions, need
// first). Throws tsynth::Error as outputGrid() does, and for no exemplar or a
// bad patch size (checkPatchSize).
OutputGrid plannedGrid(const SetupInputs& inputs);

// A key of everything that decides a synthesis' terrain: the set-up's inputs
// (the exemplars' heights and cells, the sketch's content, the grid asked for,
// patch, seed, landform relief) and the options that change it (the tile size
// among them: a tiled terrain differs from an untiled one). Not the
// backend (every backend gives the same bits), the progress report, a prepared
// pool, the memory budget or the cache. Equal keys: the same terrain.
std::uint64_t synthesisRequestKey(const SetupInputs& inputs, const SynthesisOptions& options);

// synthesise() on what the set-up prepared, with its candidate pool. Throws
// tsynth::Error if the options' patch size or seed is not the set-up's (the
// pool, the target's valley outlets and the seed's streams would disagree).
SynthesisResult synthesise(const SynthesisSetup& setup, SynthesisOptions options);

// synthesise(setup, options) for a caller that synthesises from the set-up
// once (tsynth synth): it takes the set-up's candidate pool over, so the pool
// is let go when the placement ends instead of being held through the
// finishing (190 MB of the finishing's 1.5 GB at 4096 x 4096 from five
// exemplars). setup.pool is null afterwards.
SynthesisResult synthesiseTakingPool(SynthesisSetup& setup, SynthesisOptions options);

} // namespace tsynth
