// tsynth pits: depression removal, flow accumulation and streams.
#pragma once

#include <string>
#include <vector>

namespace tsynth::cli
{

int runPits(std::vector<std::string> args);

} // namespace tsynth::cli
