// tsynth pits (depression removal, flow accumulation and streams) and tsynth
// optimise (terrain optimisation, Scott & Dodgson 2021).
#pragma once

#include <string>
#include <vector>

namespace tsynth::cli
{

int runPits(std::vector<std::string> args);
int runOptimise(std::vector<std::string> args); // OptimiseCommand.cxx

} // namespace tsynth::cli
