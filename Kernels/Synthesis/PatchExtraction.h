// A chosen candidate made into the patch the merger takes: cut from its
// exemplar as its variant sees it, the cells it owns whatever the seam (its
// core), and the vertical shift that fits it to what it will overlap. The
// synthesis' placement (PatchPlacement.h) prepares every trial with these.
// In ParaView: vtkTerrainPatchExtractor (Terrain Patch Extractor), in Filters/.
#pragma once

#include "../Core/Heightfield.h"
#include "../Core/OptionTable.h"
#include "../Features/ChainPointGrid.h"
#include "../Matching/PatchMatcher.h"

#include <cstdint>
#include <vector>

namespace tsynth
{

// The patchSize^2 patch a candidate names: its exemplar seen through its
// variant (`oriented`, orientExemplar's, with the exemplar's centre at
// (orientedCentreX, orientedCentreY)), around the candidate's centre. Cells
// off the exemplar or on its nodata are invalid. Cell size: `oriented`'s.
Heightfield extractPatch(const Heightfield& oriented,
  double orientedCentreX,
  double orientedCentreY,
  int exemplarWidth,
  int exemplarHeight,
  const PatchCandidate& candidate,
  int patchSize);

// ... from the exemplar itself, oriented here (for one patch; a loop over many
// candidates reads the matcher's oriented copies, DenseMatcher::oriented).
Heightfield extractPatch(const Heightfield& exemplar,
  const PatchCandidate& candidate,
  int patchSize);

// What a patch's vertical shift is fitted to, on the output grid.
struct OffsetFitGrid
{
  const Heightfield& terrain;              // the output so far
  const std::vector<std::uint8_t>& filled; // 1 on the cells patches wrote
  // The target through the landform term's low-pass and the confidence in it
  // per cell (both empty: no target to lean on).
  const Heightfield& lowTarget;
  const std::vector<float>& confidence;
};

// The shift that makes the patch placed at (x0, y0) continue what it
// overlaps: least squares over the filled cells (weight 1 each) and, on the
// empty part, the low-passed target (weight kTargetPull times its
// confidence). Where the overlap is under kMinOverlapForOffset of the patch,
// the mean difference to the low-passed target decides (0 with no target).
float fitPatchOffset(const Heightfield& patch, int x0, int y0, const OffsetFitGrid& grid);

// The cells (patchSize^2, row-major, 1: owned) a feature patch placed at
// (x0, y0) owns whatever the seam: a disc of kCoreDiscInPatches round its
// centre, and the sketched line's cells (`line` on the output grid, 1 on the
// line; may be empty) within kLineOffsetReachInPatches of it. The synthesis
// adds the candidate's own line (PatchPlacement).
std::vector<std::uint8_t> featureCore(const std::vector<std::uint8_t>& line,
  int outputWidth,
  int outputHeight,
  int x0,
  int y0,
  int patchSize);

// The cells a fill patch leaves as they are, where already filled: the
// sketched lines' (1 in `line`, on the output grid) and, in a tile, those the
// tiles before settled (1 in `frozen`; empty: none).
struct KeptCells
{
  const std::vector<std::uint8_t>& line;
  const std::vector<std::uint8_t>& frozen;
  const std::vector<std::uint8_t>& filled;
  int width; // the output grid's
  int height;
};

// The patch placed at (x0, y0) made invalid (NaN) on the kept cells under it:
// a fill patch never overwrites a line the feature patches laid, and its seam
// goes round them. The synthesis does this to every fill patch it tries.
void protectKeptCells(Heightfield& patch, int x0, int y0, const KeptCells& kept);

// A feature patch owns a disc of this radius (in patches) round its centre ...
constexpr double kCoreDiscInPatches = 0.125;
// ... and its lines (the drawn one and its own) this far from the centre; so
// far Placement::lineOffset looks at them.
constexpr double kLineOffsetReachInPatches = 0.25;

// The sketched lines' cells: this far (cells) each side of a drawn line. A
// feature patch's own line gets a strip as wide in its core.
constexpr float kLineHalfWidth = 3.0f;

// A feature candidate's own ridge or valley (of `type`, from its exemplar's
// `lines`) within kLineOffsetReachInPatches of its centre, as offsets (cells)
// from the placed patch's centre: the exemplar's offsets turned back by the
// candidate's variant.
std::vector<Point2> ownLineOffsets(const ChainPointGrid& lines,
  FeatureType type,
  const PatchCandidate& candidate,
  int patchSize);

// Adds to a feature patch's core (patchSize^2, row-major) a strip
// kLineHalfWidth each side along its own line (ownLineOffsets): where the
// candidate's crest strays from the drawn line the patch owns both, so the
// crest stays one line, not two.
void addOwnLineStrip(std::vector<std::uint8_t>& core,
  const std::vector<Point2>& ownLine,
  int patchSize);

// The Terrain Patch Extractor's options as a table: Rank (the row of the
// matcher's table to cut, 0 the best; at least 0) and VerticalOffset (fit the
// patch's shift, fitPatchOffset: on, as the synthesis does).
const std::vector<OptionRow>& patchExtractionOptionRows();

} // namespace tsynth
