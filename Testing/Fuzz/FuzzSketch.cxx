// Fuzz target: the sketch interpreter on small images. The first bytes give
// the image's width and height (2..64), its channels (1..4: grey, grey+alpha,
// RGB, RGBA) and the patch size it is read with; the rest are its pixels,
// repeated to fill the image. The features then become a synthesis target on
// a grid of one or two output cells per pixel.
#include "Core/Error.h"
#include "Features/Sketch.h"
#include "FuzzExemplar.h"
#include "FuzzSupport.h"

#include <vector>

namespace
{

constexpr int kMinSide = 2;
constexpr int kMaxSide = 64; // small: thinning and PPA stay fast
constexpr int kMaxPatch = 16;
constexpr int kMaxUpscale = 2;

tsynth::ColourImage decodeImage(tsynth::fuzz::Bytes& in)
{
  tsynth::ColourImage image;
  image.width = in.inRange(kMinSide, kMaxSide);
  image.height = in.inRange(kMinSide, kMaxSide);
  image.channels = in.inRange(1, 4);
  const std::size_t n = static_cast<std::size_t>(image.width) *
    static_cast<std::size_t>(image.height) * static_cast<std::size_t>(image.channels);
  image.data.assign(n, 0);
  const std::size_t have = in.left();
  for (std::size_t k = 0; have > 0 && k < n; ++k)
  {
    image.data[k] = in.rest()[k % have];
  }
  return image;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  tsynth::fuzz::Bytes in(data, size);
  tsynth::SketchOptions options;
  options.patchSize = in.inRange(1, kMaxPatch);
  options.controlRadius = 0.5 * options.patchSize;
  const int upscale = in.inRange(1, kMaxUpscale);
  const tsynth::ColourImage image = decodeImage(in);
  try
  {
    tsynth::SketchFeatures f = tsynth::sketchFeatures(image, options);
    const bool grey = f.kind == tsynth::SketchKind::Grey;
    const tsynth::Heightfield heights = grey ? tsynth::greyField(image) : tsynth::Heightfield();
    tsynth::makeTarget(f.graph,
      image.width,
      image.height,
      grey ? &heights : nullptr,
      upscale * image.width,
      upscale * image.height,
      tsynth::fuzz::kExemplarCell,
      tsynth::fuzz::kExemplarCell,
      tsynth::fuzz::exemplarStatisticsForFuzzing(),
      tsynth::fuzz::kFuzzPatch,
      grey ? tsynth::SketchHeights::Grey : tsynth::SketchHeights::None);
  }
  catch (const tsynth::Error&)
  {
    // Bad input, told as it should be.
  }
  return 0;
}
