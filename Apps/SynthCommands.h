// tsynth synth and tsynth evaluate: the synthesis pipeline and its quality figures.
#pragma once

#include <string>
#include <vector>

namespace tsynth::cli
{

int runSynth(std::vector<std::string> args);
int runEvaluate(std::vector<std::string> args);

} // namespace tsynth::cli
