#include "DistanceSources.h"

#include "../Core/Error.h"
#include "../Synthesis/Setup.h"

#include <string>

namespace tsynth
{
namespace
{

void requireSameSize(const ColourImage& image, int width, int height, const char* what)
{
  if (image.width != width || image.height != height)
  {
    throw Error(std::string("The ") + what + " is " + std::to_string(image.width) + "x" +
      std::to_string(image.height) + " but the generators' grid is " + std::to_string(width) + "x" +
      std::to_string(height) + "; give one of the same size.");
  }
}

} // namespace

DistanceInputs assembleDistanceInputs(const DistanceSources& s, std::vector<std::string>& warnings)
{
  DistanceInputs in;
  in.profiles = s.profiles;
  const int profileCount = static_cast<int>(s.profiles.size());
  if (s.strokes != nullptr)
  {
    in.width = s.strokes->width;
    in.height = s.strokes->height;
    StrokeGenerators g = generatorsFromStrokes(*s.strokes, profileCount, s.assignment, s.labels);
    if (g.valleyPixels > 0)
    {
      warnings.push_back(std::to_string(g.valleyPixels) +
        " blue valley pixels are ignored: distance synthesis makes valleys between ridge strokes.");
    }
    if (profileCount > 0 && g.colours > profileCount &&
      s.assignment == ProfileAssignment::ByColour && s.labels == nullptr)
    {
      warnings.push_back(std::to_string(g.colours) + " ridge colours share " +
        std::to_string(profileCount) + " profiles (colour index mod the profile count).");
    }
    in.features = std::move(g.features);
  }
  else if (s.lines != nullptr)
  {
    if (s.width < 1 || s.height < 1)
    {
      throw Error("Poly-line generators need a grid of two positive numbers of cells (OutputSize, "
                  "--size), not " +
        std::to_string(s.width) + " x " + std::to_string(s.height) + ".");
    }
    in.width = s.width;
    in.height = s.height;
    in.features = generatorsFromLines(*s.lines, s.width, s.height, profileCount);
  }
  else
  {
    throw Error("There are no generators: give a stroke map or poly-lines.");
  }
  if (s.regionProfile != kNoProfile)
  {
    if (s.regionProfile < 0 || s.regionProfile >= profileCount)
    {
      throw Error("The region profile " + std::to_string(s.regionProfile) +
        " does not exist; there are " + std::to_string(profileCount) + " profiles.");
    }
    in.regions = enclosedRegions(in.features, in.width, in.height, s.regionProfile);
    if (in.regions.empty())
    {
      warnings.push_back("No stroke encloses any cells, so the region profile is not used.");
    }
  }
  if (s.edgeWeights != nullptr)
  {
    requireSameSize(*s.edgeWeights, in.width, in.height, "edge-weight image");
    in.nodeWeights = greyToWeights(s.edgeWeights->data.data(),
      in.width,
      in.height,
      s.edgeWeights->channels,
      s.edgeLow,
      s.edgeHigh);
  }
  return in;
}

const std::vector<OptionRow>& distanceOptionRows()
{
  static const std::vector<OptionRow> rows = []
  {
    const DistanceOptions d;
    const DistanceSources s;
    using T = OptionType;
    const double least = kLeastPositiveSetting;
    OptionRow fbmRange =
      numberRow("FbmRange", "--fbm-range", T::Real, d.fbm.low, -kFbmRangeLimit, kFbmRangeLimit);
    fbmRange.secondDefault = d.fbm.high;
    return std::vector<OptionRow>{
      numberRow("OutputSize", "--size", T::Integer, kDefaultDistanceGrid, 1, kMaxOutputSide),
      numberRow("CellSize", "--cell", T::Real, d.cellSize, least, kUnbounded),
      numberRow("HeightScale", "--height-scale", T::Real, d.heightScale, least, kUnbounded),
      numberRow("Seed", "--seed", T::Integer, static_cast<double>(d.seed), 0.0, kUnbounded),
      numberRow("MeanWeight", "--mu", T::Real, d.meanWeight, least, kMaxMeanWeight),
      numberRow("Roughness", "--r", T::Real, d.roughness, 0.0, kMaxMeanWeight),
      switchRow("Sqrt2Diagonals", "--chessboard", d.sqrt2Diagonals),
      numberRow("SeaLevelScale", "--s", T::Real, d.seaLevelScale, 0.0, kMaxSeaLevelScale),
      numberRow("BlendBias", "--b", T::Real, d.blendBias, 0.0, kMaxBlendBias),
      numberRow("ProfileScale", "--profile-scale", T::Real, d.profileScale, least, kUnbounded),
      choiceRow("ProfileAssignment",
        "--assign",
        static_cast<int>(s.assignment),
        choicesOf(kProfileAssignmentWords),
        { "By colour", "By feature" }),
      numberRow(
        "RegionProfile", "--region-profile", T::Integer, s.regionProfile, kNoProfile, kUnbounded),
      numberRow("ProfileBins", "--bins", T::Integer, d.profileBins, 2, kMaxProfileBins),
      numberRow("FbmH", "--fbm-h", T::Real, d.fbm.h, 0.0, kMaxFbmH),
      numberRow(
        "FbmLacunarity", "--lacunarity", T::Real, d.fbm.lacunarity, kLeastLacunarity, kUnbounded),
      numberRow("FbmOctaves", "--octaves", T::Integer, d.fbm.octaves, 1, kMaxFbmOctaves),
      numberRow("FbmDomain", "--domain", T::Real, d.fbm.domain, least, kUnbounded),
      numberRow("FbmScale", "--fbm-scale", T::Real, d.fbm.scale, 0.0, kUnbounded),
      fbmRange,
      numberRow("RidgeCount", "--ridges", T::Integer, d.ridgeCount, 0, kMaxRidgeCount),
      numberRow("RidgeFraction", "--ridge-fraction", T::Real, d.ridgeFraction, least, 1.0),
      choiceRow("RidgeCost",
        "--ridge-cost",
        static_cast<int>(d.ridgeCost),
        choicesOf(kRidgeCostWords),
        { "Share of the rise", "Share of the cost" }),
      numberRow("SeaLevelEpsilon", "--eps-s", T::Real, d.seaLevelEpsilon, 0.0, kUnbounded),
      numberRow("ApproximateFraction", "--p-f", T::Real, d.approximateFraction, 0.0, 1.0),
      numberRow("MinScaling", "--min-ts", T::Real, d.minScaling, kLeastMinScaling, kUnbounded),
      switchRow("ApproximateOnly", "--approximate", d.approximateOnly),
      memoryBudgetRow(d.memoryBudget),
    };
  }();
  return rows;
}

} // namespace tsynth
