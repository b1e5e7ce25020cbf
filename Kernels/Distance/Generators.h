// The generator nodes of distance-based synthesis (Rusnell 2009, §3, §4):
// features (connected strokes, poly-lines or points), each a set of lattice
// cells with an initial cost (smaller = higher) and a profile id; default
// costs from fBm (Musgrave's algorithm over Perlin noise); crater-like
// regions enclosed by ring strokes.
#pragma once

#include "../Core/HeightfieldIO.h"
#include "../Features/FeatureGraph.h"

#include <cstddef>
#include <cstdint>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

namespace tsynth
{

constexpr int kNoProfile = -1; // w_s = 1: the shape comes from the edge weights alone

struct GeneratorNode
{
  std::int32_t cell = 0;                                // row-major, row 0 south
  float cost = std::numeric_limits<float>::quiet_NaN(); // NaN: take the fBm default
  std::int32_t profile = kNoProfile;                    // index into the profiles
};

// One feature (a stroke, a poly-line, a point): its id is its index.
struct DistanceFeature
{
  std::vector<GeneratorNode> nodes;
};

// Cells where one feature alone shapes the terrain with its own profile (a crater
// or cinder-cone interior): searches from inside use `profile`, and no other
// feature enters or blends there.
struct DistanceRegion
{
  std::vector<std::int32_t> cells;
  std::int32_t feature = 0;
  std::int32_t profile = kNoProfile;
};

// How stroke pixels get their profile.
enum class ProfileAssignment
{
  ByColour, // distinct ridge colours, ordered by (R, G, B) value, take profiles 0, 1, ... (mod
            // count)
  ByFeature // feature id mod profile count (the thesis's p_id = f_id mod 3)
};
// The assignments' words, by value (Core/OptionTable.h).
inline constexpr const char* kProfileAssignmentWords[] = { "colour", "feature" };
static_assert(
  std::size(kProfileAssignmentWords) == static_cast<std::size_t>(ProfileAssignment::ByFeature) + 1);

struct StrokeGenerators
{
  std::vector<DistanceFeature> features;
  int colours = 0;      // distinct ridge colours seen
  int valleyPixels = 0; // blue strokes, which distance synthesis does not use
};

// Ridge-coloured pixels of a stroke map (DESIGN.md: R >= 200, G <= 80, B <= 80)
// are generators; each 8-connected component is a feature, numbered in scan
// order from the south-west. With `labels` (same size; grey value k = profile
// k) the label decides each pixel's profile; otherwise `assignment` does.
// profileCount 0 gives every node kNoProfile. Costs are left NaN (fBm).
// Throws tsynth::Error if the labels differ in size, name a profile that does
// not exist, or no pixel is a ridge stroke.
StrokeGenerators generatorsFromStrokes(const ColourImage& strokes,
  int profileCount,
  ProfileAssignment assignment,
  const ColourImage* labels = nullptr);

// A poly-line (one point: a point generator) in cell coordinates, with optional
// costs per point (empty, or one per point; NaN = fBm) and a profile
// (kNoProfile: feature id mod profile count).
struct GeneratorLine
{
  std::vector<Point2> points;
  std::vector<float> costs;
  int profile = kNoProfile;
};

// Each line becomes a feature: its cells sampled at most half a cell apart,
// costs interpolated along segments; cells outside the grid are dropped.
// Lines of any length or position cost no more than the grid's own size (only
// the part on the grid is sampled). Throws tsynth::Error for a profile id out of
// range, costs of the wrong count, or a point that is not a finite number.
std::vector<DistanceFeature> generatorsFromLines(const std::vector<GeneratorLine>& lines,
  int width,
  int height,
  int profileCount);

struct FbmOptions
{
  double h = 3.0;          // H: how fast octave amplitudes fall (lacunarity^-H per octave)
  double lacunarity = 2.0; // frequency step between octaves
  int octaves = 2;         // number of noise terms (octave i = 0 .. octaves-1)
  double domain = 4.0;     // noise cells across the field (the thesis's 4 x 4 grid at 512^2)
  double scale = 30.0;     // cost of the highest normalised value (thesis: x 30)
  double low = 0.0;        // eq. 4.1: costs span [low, high] x scale ...
  double high = 1.0;       // ... of the fBm normalised to [0, 1] over the field
};

// fBm of seeded Perlin gradient noise at every cell (cell centres, the domain
// stretched over each axis), normalised to [0, 1] over the field and mapped to
// costs by eq. 4.1. Throws tsynth::Error for octaves < 1, lacunarity <= 1,
// domain <= 0, scale < 0 or low > high.
std::vector<float> fbmCosts(int width, int height, const FbmOptions& options, std::uint64_t seed);

// The cells each feature encloses (not reachable from outside its bounding box
// by 4-connected steps that avoid its cells): rings, closed strokes. Features
// that enclose nothing give no region.
std::vector<DistanceRegion> enclosedRegions(const std::vector<DistanceFeature>& features,
  int width,
  int height,
  int profile);

} // namespace tsynth
