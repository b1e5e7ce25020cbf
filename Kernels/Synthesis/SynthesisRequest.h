// Everything a user asks of a synthesis, in one struct that `tsynth synth` and
// the Terrain Synthesis filter each fill once, and the table of those options:
// for each, the filter property, the tsynth option, the default (read from this
// struct's own initialisers), the values taken and an enumeration's words and
// labels. The set-up's inputs and the synthesiser's options are both derived
// from the request, so the patch size and the seed travel as one value each.
// In ParaView: vtkTerrainSynthesis (Terrain Synthesis), in Filters/; on the
// command line: tsynth synth (Apps/SynthCommand.cxx).
#pragma once

#include "../Core/OptionTable.h"
#include "OptionLimits.h"
#include "Setup.h"
#include "Synthesiser.h"

#include <optional>
#include <string>
#include <vector>

namespace tsynth
{

// The options' bounds: Core/PatchSize.h and OptionLimits.h.

// A request's patch size of 0: the patch is chosen for the sketch
// (resolvePatchSize), as it is when neither --patch nor Patch Size is given.
constexpr int kAutomaticPatch = 0;
// The patch chosen for a DEM used as the target. Real DEMs' ridges and valleys
// lie 8 to 15 cells apart (Norway's fjords, Alaska's valleys, the Appalachian
// ridges, at 648 x 648), finer than 80-cell patches follow: from Colorado, the
// result matched the target at 8 cells and coarser (band-pass correlation
// 0.93-0.95) but not finer, and its hillshade showed the fjords and valleys
// faintly. With 32-cell patches it matched at 4 cells too (0.95-0.97) and they
// read (hillshades side by side, Examples/legibility); 16-cell patches, which
// the fineness warning names for Norway, took six times as long (67 s against
// 11 s) for no more that the eye sees.
constexpr int kDefaultDemTargetPatch = 32;

// The patch a synthesis of this sketch uses when asked for `requested`:
// `requested` itself, or for kAutomaticPatch kDefaultDemTargetPatch when the
// sketch is a DEM used as the target and kDefaultSynthesisPatch otherwise.
int patchSizeFor(int requested, const SketchInput& sketch);

struct SynthesisRequest
{
  // Patch size, seed, backend, merge, fill order, drainage, vertical offset,
  // repetition penalty and tile size: each here once (the set-up reads the patch
  // size and the seed from here too). The patch size starts as
  // kAutomaticPatch: resolvePatchSize fixes it once the sketch is read.
  SynthesisOptions options = automaticOptions();
  GridRequest grid;
  double landformRelief = kDefaultLandformRelief;
  double memoryBudgetGB = 0.0; // 0: defaultMemoryBudget()
  // The exemplar cache (ExemplarCache.h): on by default, in cacheDirectory or,
  // when that is empty, defaultExemplarCacheDirectory().
  bool useExemplarCache = true;
  std::string cacheDirectory;

private:
  static SynthesisOptions automaticOptions()
  {
    SynthesisOptions o;
    o.patchSize = kAutomaticPatch;
    return o;
  }
};

// Fixes a request's automatic patch size (patchSizeFor) for the sketch read,
// and checks the options that depend on it (the tile size), before anything
// uses it. Throws tsynth::Error, naming the options by `names`.
void resolvePatchSize(SynthesisRequest& request,
  const SketchInput& sketch,
  const SetupOptionNames& names);

// The set-up's inputs of a request: its grid, patch size, seed, relief, memory
// budget (in bytes), cache directory and whether the matcher runs on OpenCL, with
// the files read and the names the front end gives its options.
SetupInputs setupInputs(const SynthesisRequest& request,
  std::vector<Heightfield> exemplars,
  std::vector<std::string> exemplarNames,
  SketchInput sketch,
  SetupOptionNames optionNames);

// The synthesis options a front end offers, with their defaults as a default
// SynthesisRequest holds them. Choice properties number their words as the
// kernels' enumerations do; Drainage is "off" then the pit-removal methods.
const std::vector<OptionRow>& synthesisOptionRows();
const OptionRow& synthesisOption(const std::string& property);

// Drainage's words and values: offOrMethodChoices (Hydrology/PitRemoval.h).

} // namespace tsynth
