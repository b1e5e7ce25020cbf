#include "Setup.h"

#include "Synthesiser.h"
#include "TileRecord.h"

#include "../Core/Cancellation.h"
#include "../Core/ContentHash.h"
#include "../Core/Error.h"
#include "../Core/Memory.h"
#include "../Core/Resample.h"
#include "../Features/Ppa.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

namespace tsynth
{
namespace
{

// Peak resident memory measured with /usr/bin/time on `tsynth synth` (one
// 648 x 648 exemplar at 90 m): 220 MB at 512^2, 301 MB at 1024^2, 736 MB at
// 2048^2 output cells; 2.5 GB at 4096^2 from five exemplars. The slope between
// the two largest is 138 bytes per output cell, another exemplar of 420 k cells
// added 95 MB (its 16 oriented copies and tables), and the program with its
// libraries holds about 100 MB before it starts.
constexpr double kBytesPerOutputCell = 140.0;
constexpr double kBytesPerExemplarCell = 240.0;
constexpr double kBaseBytes = 128.0e6;
// The OpenCL matcher on PoCL added 110 MB to the peak with one 648 x 648
// exemplar and 137 MB with two (the second of 420 k cells), at 512^2 and
// 1024^2 output cells alike: about 85 MB of runtime and compiled kernels, and
// 64 bytes per exemplar cell (its 16 orientations as floats on the device).
constexpr double kOpenClBaseBytes = 85.0e6;
constexpr double kOpenClBytesPerExemplarCell = 64.0;
// Exemplar cells differing from the output's by more than this fraction are
// resampled (less is rounding in a file's georeference).
constexpr double kResampleTolerance = 0.01;

// Beyond this, whole metres would print hundreds of digits: an exponent instead.
constexpr double kLargestPlainNumber = 1.0e9;

// Four significant digits, whole metres from 1000 up, an exponent from 1e9.
std::string number(double v)
{
  std::ostringstream o;
  if (std::abs(v) >= 1000.0 && std::abs(v) < kLargestPlainNumber)
  {
    o << std::fixed << std::setprecision(0) << v;
  }
  else
  {
    o << std::setprecision(4) << v;
  }
  return o.str();
}

std::string sizeText(int w, int h)
{
  return std::to_string(w) + " x " + std::to_string(h);
}

std::string cellText(double cx, double cy)
{
  return cx == cy ? number(cx) + " m" : number(cx) + " x " + number(cy) + " m";
}

// Cells needed to hold coordinates from 0 to `extent` metres (cell centres at
// multiples of `cell`), clamped to what an int can count.
// The margin beyond unframed poly-lines, in patches (polylineSize).
constexpr double kLineMarginInPatches = 0.5;

int cellsToReach(double extent, double cell)
{
  const double cells = std::floor(extent / cell + 0.5) + 1.0;
  return static_cast<int>(std::min(cells, static_cast<double>(std::numeric_limits<int>::max())));
}

int cellsInFrame(double frame, double cell)
{
  const double cells = std::floor(frame / cell + 0.5);
  return static_cast<int>(std::min(cells, static_cast<double>(std::numeric_limits<int>::max())));
}

void checkRequest(const GridRequest& r, const SetupOptionNames& names)
{
  if (r.width < 0 || r.height < 0 || (r.width == 0) != (r.height == 0))
  {
    throw Error("Give " + names.size + " as two positive numbers of cells, or neither.");
  }
  if (r.width > kMaxOutputSide || r.height > kMaxOutputSide)
  {
    throw Error(names.size + " " + sizeText(r.width, r.height) +
      " is beyond any machine: at most " + std::to_string(kMaxOutputSide) + " cells a side.");
  }
  if (r.cellX < 0.0 || r.cellY < 0.0 || !std::isfinite(r.cellX) || !std::isfinite(r.cellY))
  {
    throw Error(names.cell + " must be a positive number of metres (or 0 for the exemplar's).");
  }
}

// What was found, the start of every poly-line refusal.
std::string spanText(const SketchExtent& s)
{
  return "The poly-lines span " + number(s.maxX - s.minX) + " x " + number(s.maxY - s.minY) +
    " m (x " + number(s.minX) + " to " + number(s.maxX) + ", y " + number(s.minY) + " to " +
    number(s.maxY) + ")";
}

// What to do, the end of every poly-line refusal.
std::string unitAdvice(const SetupOptionNames& names)
{
  return " Poly-line sketches are in metres in the raster frame (lower-left cell centre at "
         "(0, 0)): scale or shift them, or set " +
    names.size + " and " + names.cell + ".";
}

// The poly-lines' size from their frame or extent, refusing coordinates that
// are not metres in the raster frame.
void polylineSize(const SketchExtent& s, OutputGrid& g, int patch, const SetupOptionNames& names)
{
  const std::string span = spanText(s);
  const std::string advice = unitAdvice(names);
  if (s.minX < -0.5 * g.cellX || s.minY < -0.5 * g.cellY)
  {
    throw Error(span +
      ", west or south of the raster frame; are they in degrees or world coordinates?" + advice);
  }
  g.width = std::max(cellsToReach(s.maxX, g.cellX), cellsInFrame(s.frameWidth, g.cellX));
  g.height = std::max(cellsToReach(s.maxY, g.cellY), cellsInFrame(s.frameHeight, g.cellY));
  if (g.width < patch || g.height < patch)
  {
    throw Error(span + ": an output of " + sizeText(g.width, g.height) + " cells of " +
      cellText(g.cellX, g.cellY) + ", smaller than one patch (" + std::to_string(patch) +
      " cells); are they in cells or degrees?" + advice);
  }
  // Without a frame the output reaches past the lines' far end by half a patch, so a stroke
  // drawn last does not lie on the border but has room for its landform's cross-section (a
  // ridge or valley reaches out to about half a patch each side).
  const bool framed = s.frameWidth > 0.0 && s.frameHeight > 0.0;
  if (!framed)
  {
    const double margin = kLineMarginInPatches * patch;
    g.width = cellsToReach(s.maxX + margin * g.cellX, g.cellX);
    g.height = cellsToReach(s.maxY + margin * g.cellY, g.cellY);
  }
  if (g.width > kMaxOutputSide || g.height > kMaxOutputSide)
  {
    throw Error(span + ": an output of " + sizeText(g.width, g.height) + " cells of " +
      cellText(g.cellX, g.cellY) + ", more than " + std::to_string(kMaxOutputSide) +
      " a side; are they in world coordinates, or in cells of a finer grid?" + advice);
  }
}

// Requested size and poly-lines: they must at least reach into the output and
// be longer than a cell.
void checkPolylinesInGrid(const SketchExtent& s, const OutputGrid& g, const SetupOptionNames& names)
{
  const double w = (g.width - 0.5) * g.cellX;
  const double h = (g.height - 0.5) * g.cellY;
  const bool outside =
    s.minX > w || s.minY > h || s.maxX < -0.5 * g.cellX || s.maxY < -0.5 * g.cellY;
  const bool tiny = s.maxX - s.minX < g.cellX && s.maxY - s.minY < g.cellY;
  if (!outside && !tiny)
  {
    return;
  }
  throw Error(spanText(s) +
    (tiny ? ", less than one cell of " + cellText(g.cellX, g.cellY) +
          "; are they in cells or degrees?"
          : ", outside the output (" + number(w + 0.5 * g.cellX) + " x " +
          number(h + 0.5 * g.cellY) + " m); are they in world coordinates?") +
    unitAdvice(names));
}

bool needsResampling(const Heightfield& hf, double cx, double cy)
{
  return std::abs(hf.cellX - cx) > kResampleTolerance * cx ||
    std::abs(hf.cellY - cy) > kResampleTolerance * cy;
}

// The cells an exemplar will have at the output's cell size (resampleToCellSize's count).
std::size_t cellsAtOutputSize(const Heightfield& hf, const OutputGrid& g)
{
  if (!needsResampling(hf, g.cellX, g.cellY))
  {
    return hf.size();
  }
  const double w = std::floor((hf.width - 1) * hf.cellX / g.cellX) + 1.0;
  const double h = std::floor((hf.height - 1) * hf.cellY / g.cellY) + 1.0;
  return static_cast<std::size_t>(std::max(1.0, w) * std::max(1.0, h));
}

void checkMemory(const SetupInputs& in, const OutputGrid& g, SynthesisSetup& s)
{
  std::vector<std::size_t> cells;
  for (const Heightfield& hf : in.exemplars)
  {
    cells.push_back(cellsAtOutputSize(hf, g));
  }
  s.memoryEstimate =
    synthesisMemoryEstimate(g.width, g.height, cells, matchesOnOpenCl(in.matcherBackend)) +
    in.previousRecordBytes +
    (in.recordedTileSize > 0 ? tileRecordBytes(g.width, g.height, in.recordedTileSize, in.patchSize)
                             : 0.0);
  s.memoryBudget = checkMemoryBudget(s.memoryEstimate,
    in.memoryBudget,
    "This synthesis of " + sizeText(g.width, g.height) + " cells from " +
      std::to_string(in.exemplars.size()) + " exemplar(s)",
    "give a smaller " + in.names.size + " or a larger " + in.names.cell +
      ", fewer or smaller exemplars",
    in.names.memory);
}

std::string exemplarName(const SetupInputs& in, std::size_t e)
{
  return e < in.exemplarNames.size() ? in.exemplarNames[e] : "exemplar " + std::to_string(e);
}

// Exemplars at the output's cell size, each checked to hold a whole patch.
void prepareExemplars(SetupInputs& in, SynthesisSetup& s)
{
  const OutputGrid& g = s.grid;
  for (std::size_t e = 0; e < in.exemplars.size(); ++e)
  {
    Heightfield& hf = in.exemplars[e];
    if (needsResampling(hf, g.cellX, g.cellY))
    {
      s.warnings.push_back(exemplarName(in, e) + " has " + cellText(hf.cellX, hf.cellY) +
        " cells; resampled to the output's " + cellText(g.cellX, g.cellY) + ".");
      hf = resampleToCellSize(hf, g.cellX, g.cellY);
    }
    if (hf.width < in.patchSize || hf.height < in.patchSize)
    {
      throw Error(exemplarName(in, e) + " is " + sizeText(hf.width, hf.height) + " cells of " +
        cellText(g.cellX, g.cellY) + ", smaller than one patch (" + std::to_string(in.patchSize) +
        " cells); give a larger exemplar or reduce " + in.names.patch + ".");
    }
    if (!hasValidWindow(hf, in.patchSize))
    {
      throw Error(exemplarName(in, e) + " holds no " + std::to_string(in.patchSize) + " x " +
        std::to_string(in.patchSize) + " window without nodata (" +
        std::to_string(hf.validCount()) + " valid cells of " + std::to_string(hf.size()) +
        "), so no patch can be cut from it; " +
        "give an exemplar with more valid heights or reduce " + in.names.patch + ".");
    }
    s.exemplars.push_back(std::move(hf));
  }
}

AnalysedSketch analyseImage(const ColourImage& image, int patch)
{
  SketchOptions so;
  so.patchSize = patch;
  so.controlRadius = 0.5 * patch;
  SketchFeatures f = sketchFeatures(image, so);
  AnalysedSketch a;
  a.graph = std::move(f.graph);
  a.warnings = std::move(f.warnings);
  a.width = image.width;
  a.height = image.height;
  a.hasHeights = f.kind == SketchKind::Grey;
  if (a.hasHeights)
  {
    a.heights = greyField(image);
  }
  a.kind = a.hasHeights ? "grey sketch" : "stroke map";
  return a;
}

AnalysedSketch analyseDem(const Heightfield& dem, int patch)
{
  if (dem.width < patch || dem.height < patch)
  {
    throw Error("The DEM sketch is " + sizeText(dem.width, dem.height) +
      " cells, smaller than one patch (" + std::to_string(patch) + ").");
  }
  AnalysedSketch a;
  a.graph = ridgesAndValleys(dem, {}); // a DEM target's significant landforms
  a.width = dem.width;
  a.height = dem.height;
  a.hasHeights = true;
  a.heights = dem;
  a.kind = "DEM";
  return a;
}

AnalysedSketch analysePolylines(const PolylineSketch& sketch, const OutputGrid& g, int patch)
{
  std::vector<Polyline> cells = sketch.lines;
  bool outside = false;
  for (Polyline& line : cells)
  {
    for (Point2& p : line.points)
    {
      p.x /= g.cellX;
      p.y /= g.cellY;
      outside = outside || p.x < -0.5 || p.y < -0.5 || p.x > g.width - 0.5 || p.y > g.height - 0.5;
    }
  }
  AnalysedSketch a;
  if (outside)
  {
    a.warnings.push_back("Parts of the poly-lines lie outside the " + sizeText(g.width, g.height) +
      "-cell output; only what lies inside is sketched.");
  }
  a.graph =
    polylineFeatures(cells, g.width, g.height, g.cellX, g.cellY, kDefaultSnapCells, 0.5 * patch);
  a.width = g.width;
  a.height = g.height;
  a.kind = "poly-lines";
  return a;
}

// A sketch that gives the synthesis nothing to follow: no feature line and no
// relief (a blank image, a flat DEM, poly-lines without a segment inside).
void refuseEmptySketch(const AnalysedSketch& sketch)
{
  const bool lines = !sketch.graph.chains.empty();
  bool relief = false;
  if (sketch.hasHeights)
  {
    const HeightRange r = computeHeightRange(sketch.heights);
    relief = r.validCells > 0 && r.max > r.min;
  }
  if (lines || relief)
  {
    return;
  }
  if (sketch.kind == "DEM")
  {
    throw Error("The DEM used as the sketch is flat: it has no landform to follow; give a DEM "
                "with relief or a drawn sketch.");
  }
  if (sketch.kind == "poly-lines")
  {
    throw Error("The poly-lines draw nothing on the " + sizeText(sketch.width, sketch.height) +
      "-cell output (no segment longer than a cell lies inside it).");
  }
  throw Error("The sketch has nothing drawn (a single shade of grey): draw red ridge or blue "
              "valley strokes, or shade a grey sketch map.");
}

} // namespace

bool rasterIsDemTarget(int bands, bool eightBit)
{
  return bands == 1 && !eightBit;
}

SketchExtent rasterExtent(int pixelsX, int pixelsY)
{
  SketchExtent s;
  s.pixelsX = pixelsX;
  s.pixelsY = pixelsY;
  return s;
}

SketchExtent polylineExtent(const PolylineSketch& sketch)
{
  SketchExtent s;
  s.polylines = true;
  s.minX = s.minY = std::numeric_limits<double>::infinity();
  s.maxX = s.maxY = -std::numeric_limits<double>::infinity();
  for (const Polyline& line : sketch.lines)
  {
    for (const Point2& p : line.points)
    {
      if (!std::isfinite(p.x) || !std::isfinite(p.y))
      {
        throw Error("A poly-line point is not a finite number; the sketch is damaged.");
      }
      s.minX = std::min(s.minX, p.x);
      s.minY = std::min(s.minY, p.y);
      s.maxX = std::max(s.maxX, p.x);
      s.maxY = std::max(s.maxY, p.y);
    }
  }
  if (!(s.minX <= s.maxX))
  {
    throw Error("The poly-line sketch has no lines: give poly-line cells with a FeatureType "
                "cell array (+1 ridge, -1 valley).");
  }
  s.frameWidth = std::max(0.0, sketch.frameWidth);
  s.frameHeight = std::max(0.0, sketch.frameHeight);
  return s;
}

SketchExtent sketchExtent(const SketchInput& sketch)
{
  if (const auto* image = std::get_if<ColourImage>(&sketch))
  {
    return rasterExtent(image->width, image->height);
  }
  if (const auto* dem = std::get_if<Heightfield>(&sketch))
  {
    return rasterExtent(dem->width, dem->height);
  }
  return polylineExtent(std::get<PolylineSketch>(sketch));
}

OutputGrid outputGrid(const SketchExtent& sketch,
  const GridRequest& request,
  double exemplarCellX,
  double exemplarCellY,
  int patchSize,
  const SetupOptionNames& names)
{
  checkRequest(request, names);
  OutputGrid g;
  g.cellX = request.cellX > 0.0 ? request.cellX : exemplarCellX;
  g.cellY = request.cellY > 0.0 ? request.cellY : exemplarCellY;
  if (!(g.cellX > 0.0) || !(g.cellY > 0.0))
  {
    throw Error("The first exemplar has no positive cell size; give " + names.cell + ".");
  }
  if (request.width > 0)
  {
    g.width = request.width;
    g.height = request.height;
    if (sketch.polylines)
    {
      checkPolylinesInGrid(sketch, g, names);
    }
  }
  else if (sketch.polylines)
  {
    polylineSize(sketch, g, patchSize, names);
  }
  else
  {
    g.width = sketch.pixelsX;
    g.height = sketch.pixelsY;
  }
  if (g.width < patchSize || g.height < patchSize)
  {
    throw Error("The output (" + sizeText(g.width, g.height) +
      " cells) is smaller than one patch (" + std::to_string(patchSize) + "); give a larger " +
      names.size + " or reduce " + names.patch + ".");
  }
  return g;
}

double synthesisMemoryEstimate(int width,
  int height,
  const std::vector<std::size_t>& exemplarCells,
  bool openCl)
{
  double bytes = kBaseBytes + kBytesPerOutputCell * static_cast<double>(width) * height;
  const double perExemplarCell =
    kBytesPerExemplarCell + (openCl ? kOpenClBytesPerExemplarCell : 0.0);
  for (std::size_t cells : exemplarCells)
  {
    bytes += perExemplarCell * static_cast<double>(cells);
  }
  return bytes + (openCl ? kOpenClBaseBytes : 0.0);
}

AnalysedSketch analyseSketch(const SketchInput& sketch,
  const OutputGrid& grid,
  int patchSize,
  int rasterPatch)
{
  const int raster = rasterPatch > 0 ? rasterPatch : patchSize;
  if (const auto* image = std::get_if<ColourImage>(&sketch))
  {
    return analyseImage(*image, raster);
  }
  if (const auto* dem = std::get_if<Heightfield>(&sketch))
  {
    return analyseDem(*dem, raster);
  }
  return analysePolylines(std::get<PolylineSketch>(sketch), grid, patchSize);
}

std::vector<const Heightfield*> SynthesisSetup::exemplarPointers() const
{
  std::vector<const Heightfield*> out;
  for (const Heightfield& h : exemplars)
  {
    out.push_back(&h);
  }
  return out;
}

std::vector<const FeatureGraph*> SynthesisSetup::graphPointers() const
{
  std::vector<const FeatureGraph*> out;
  for (const FeatureGraph& g : graphs)
  {
    out.push_back(&g);
  }
  return out;
}

std::optional<std::string> finenessWarning(const SynthesisTarget& target, int patchSize, bool dem)
{
  const double finest = kFinestDrawnSpacingInPatches;
  const double spacing = lineSpacing(target);
  if (!(spacing > 0.0) || spacing >= finest * patchSize)
  {
    return std::nullopt;
  }
  const int serving = static_cast<int>(spacing / finest) / kPatchSizeStep * kPatchSizeStep;
  const std::string apart = std::to_string(static_cast<int>(std::lround(spacing)));
  const std::string what = dem ? "The target's ridges and valleys are about " + apart +
      " cells apart, finer than " + std::to_string(patchSize) + "-cell patches follow"
                               : "The sketch's strokes are about " + apart +
      " cells apart, closer than " + std::to_string(patchSize) + "-cell patches draw";
  const std::string remedy = serving >= kMinSynthesisPatch
    ? "give a patch of " + std::to_string(serving) + " cells (or a larger output) to follow them"
    : "give a larger output, or " + std::string(dem ? "a target" : "strokes") +
      " with more room between them";
  // A DEM target's finest lines only: its coarser ones, which make its shape,
  // the correction follows at any patch.
  const std::string faint = dem ? "the finest of them will read faintly" : "they will read faintly";
  return what + ": " + faint + "; " + remedy + ".";
}

SynthesisSetup prepareSynthesis(SetupInputs in)
{
  if (in.exemplars.empty())
  {
    throw Error("No exemplar: give at least one DEM to copy terrain from.");
  }
  if (!(in.landformRelief >= kMinLandformRelief && in.landformRelief <= kMaxLandformRelief))
  {
    throw Error("The landform relief must be from " + number(kMinLandformRelief) + " to " +
      number(kMaxLandformRelief) + " times the exemplars' own, not " + number(in.landformRelief) +
      ".");
  }
  checkPatchSize(in.patchSize, in.names.patch);
  reuseFreedWorkMemory(); // the filters' synthesis too, not only tsynth's
  SynthesisSetup s;
  s.patchSize = in.patchSize;
  s.seed = in.seed;
  s.grid = plannedGrid(in);
  checkMemory(in, s.grid, s);
  AnalysedSketch sketch = analyseSketch(in.sketch, s.grid, in.patchSize, in.rasterSketchPatch);
  checkCancellation(); // between the set-up's steps: a stop waits for one step at most
  refuseEmptySketch(sketch);
  s.sketchKind = sketch.kind;
  s.warnings = std::move(sketch.warnings);
  prepareExemplars(in, s);
  checkCancellation();
  // A given pool (the Candidate Builder's) replaces the one the preparation would build.
  PreparedExemplars prepared = in.pool != nullptr
    ? prepareExemplarsForGivenPool(s.exemplarPointers(), in.patchSize, in.cacheDirectory, s.cache)
    : prepareExemplarsCached(s.exemplarPointers(), in.patchSize, in.cacheDirectory, s.cache);
  s.graphs = std::move(prepared.graphs);
  s.pool = std::move(prepared.pool);
  if (in.pool != nullptr)
  {
    checkGivenPool(*in.pool, s.exemplarPointers(), in.patchSize);
    s.pool = in.pool;
  }
  if (!s.cache.problem.empty())
  {
    s.warnings.push_back("Exemplar cache: " + s.cache.problem + ".");
  }
  checkCancellation();
  const ExemplarStatistics& stats = prepared.statistics;
  const SketchHeights heights = !sketch.hasHeights ? SketchHeights::None
    : sketch.kind == "DEM"                         ? SketchHeights::Dem
                                                   : SketchHeights::Grey;
  s.landform = withReliefScaled(stats.landform, in.landformRelief);
  s.target = makeTarget(sketch.graph,
    sketch.width,
    sketch.height,
    sketch.hasHeights ? &sketch.heights : nullptr,
    s.grid.width,
    s.grid.height,
    s.grid.cellX,
    s.grid.cellY,
    stats,
    in.patchSize,
    heights,
    in.seed,
    in.landformRelief);
  if (const auto warning = finenessWarning(s.target, in.patchSize, heights == SketchHeights::Dem))
  {
    s.target.warnings.push_back(*warning);
  }
  returnFreedMemory(); // the target's making held the most; the placement holds less
  return s;
}

namespace
{

// Everything of a given pool that decides a match.
void hashPool(ContentHasher& h, const CandidatePool& p)
{
  h.value(p.patchSize);
  h.value(p.heightScale);
  for (const ExemplarInfo& e : p.exemplars)
  {
    h.value(e.width);
    h.value(e.height);
    h.value(e.heightsChecksum);
  }
  for (const std::vector<int>* v : { &p.exemplar, &p.variant, &p.kind, &p.type, &p.arms })
  {
    h.values(*v);
  }
  for (const std::vector<float>* v : { &p.centreX,
         &p.centreY,
         &p.angles,
         &p.along,
         &p.across,
         &p.noise,
         &p.descriptor,
         &p.landform })
  {
    h.values(*v);
  }
}

void hashSketch(ContentHasher& h, const SketchInput& sketch)
{
  h.value(sketch.index());
  if (const auto* image = std::get_if<ColourImage>(&sketch))
  {
    h.value(image->width);
    h.value(image->height);
    h.value(image->channels);
    h.values(image->data);
  }
  else if (const auto* dem = std::get_if<Heightfield>(&sketch))
  {
    hashHeightfield(h, *dem);
  }
  else
  {
    const auto& lines = std::get<PolylineSketch>(sketch);
    h.value(lines.frameWidth);
    h.value(lines.frameHeight);
    h.value(lines.lines.size());
    for (const Polyline& line : lines.lines)
    {
      h.value(line.type);
      h.value(line.points.size());
      for (const Point2& p : line.points)
      {
        h.value(p.x);
        h.value(p.y);
      }
      h.values(line.elevation);
    }
  }
}

} // namespace

OutputGrid plannedGrid(const SetupInputs& in)
{
  if (in.exemplars.empty())
  {
    throw Error("No exemplar: give at least one DEM to copy terrain from.");
  }
  checkPatchSize(in.patchSize, in.names.patch); // before the grid, which needs a patch
  const Heightfield& first = in.exemplars.front();
  return outputGrid(
    sketchExtent(in.sketch), in.grid, first.cellX, first.cellY, in.patchSize, in.names);
}

std::uint64_t synthesisRequestKey(const SetupInputs& in, const SynthesisOptions& o)
{
  ContentHasher h;
  h.value(in.exemplars.size());
  for (const Heightfield& e : in.exemplars)
  {
    hashHeightfield(h, e);
  }
  hashSketch(h, in.sketch);
  h.value(in.grid.width);
  h.value(in.grid.height);
  h.value(in.grid.cellX);
  h.value(in.grid.cellY);
  h.value(in.patchSize);
  h.value(in.seed);
  h.value(in.landformRelief);
  h.value(in.rasterSketchPatch);
  h.value(in.pool != nullptr);
  if (in.pool != nullptr)
  {
    hashPool(h, *in.pool);
  }
  h.value(o.patchSize);
  h.value(o.merge);
  h.value(o.fill);
  h.value(o.seed);
  h.value(o.k);
  h.value(o.fillK);
  h.value(o.fillSpacing);
  h.value(o.verticalOffset);
  h.value(o.repetitionPenalty);
  h.value(o.correctionScale);
  h.value(o.drainValleys);
  h.value(o.tileSize);
  h.value(o.placementLimit);
  h.value(o.drainage.has_value());
  h.value(o.drainage.value_or(PitRemovalMethod{}));
  h.values(o.regionLabels);
  h.value(o.regionExemplars.size());
  for (const std::vector<int>& exemplars : o.regionExemplars)
  {
    h.values(exemplars);
  }
  return h.digest();
}

namespace
{

// Throws tsynth::Error unless the options ask for what the set-up was
// prepared for (the pool, the target's valley outlets and the seed's streams
// would disagree).
void checkPreparedFor(const SynthesisSetup& setup, const SynthesisOptions& options)
{
  if (options.patchSize != setup.patchSize || options.seed != setup.seed)
  {
    throw Error("The synthesis was asked for " + std::to_string(options.patchSize) +
      "-cell patches and seed " + std::to_string(options.seed) +
      ", but its set-up was prepared for " + std::to_string(setup.patchSize) +
      "-cell patches and seed " + std::to_string(setup.seed) +
      ": prepare it again from the same request.");
  }
}

} // namespace

SynthesisResult synthesise(const SynthesisSetup& setup, SynthesisOptions options)
{
  checkPreparedFor(setup, options);
  options.pool = setup.pool;
  return synthesise(
    setup.target, setup.exemplarPointers(), setup.graphPointers(), std::move(options));
}

SynthesisResult synthesiseTakingPool(SynthesisSetup& setup, SynthesisOptions options)
{
  checkPreparedFor(setup, options);
  options.pool = std::move(setup.pool);
  return synthesise(
    setup.target, setup.exemplarPointers(), setup.graphPointers(), std::move(options));
}

} // namespace tsynth
