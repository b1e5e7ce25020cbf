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

struct SynthesisRequest
{
  // Patch size, seed, backend, merge, fill order, drainage, vertical offset,
  // repetition penalty and tile size: each here once (the set-up reads the patch
  // size and the seed from here too).
  SynthesisOptions options;
  GridRequest grid;
  double landformRelief = kDefaultLandformRelief;
  double memoryBudgetGB = 0.0; // 0: defaultMemoryBudget()
  // The exemplar cache (ExemplarCache.h): on by default, in cacheDirectory or,
  // when that is empty, defaultExemplarCacheDirectory().
  bool useExemplarCache = true;
  std::string cacheDirectory;
};

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
