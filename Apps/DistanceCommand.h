// tsynth distance: distance-based terrain synthesis (Rusnell 2009) from a
// stroke map or poly-lines, with no exemplar.
#pragma once

#include <string>
#include <vector>

namespace tsynth::cli
{

int runDistance(std::vector<std::string> args);

} // namespace tsynth::cli
