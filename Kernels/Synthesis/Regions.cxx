#include "Regions.h"

#include "../Core/Error.h"
#include "../Core/Grid.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace tsynth
{
namespace
{

bool parseWhole(const std::string& text, int& value)
{
  char* end = nullptr;
  const long v = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || end == nullptr || *end != '\0' || v < 0 || v > 1000000)
  {
    return false;
  }
  value = static_cast<int>(v);
  return true;
}

} // namespace

void assignRegions(SynthesisOptions& o,
  const Heightfield& labels,
  const std::vector<std::string>& maps,
  int width,
  int height,
  std::size_t exemplars)
{
  o.regionLabels.assign(cellCount(width, height), -1);
  int maxLabel = -1;
  for (int j = 0; j < height; ++j)
  {
    for (int i = 0; i < width; ++i)
    {
      const int si =
        std::min(labels.width - 1, static_cast<int>(static_cast<double>(i) * labels.width / width));
      const int sj = std::min(
        labels.height - 1, static_cast<int>(static_cast<double>(j) * labels.height / height));
      const int label =
        labels.isValid(si, sj) ? static_cast<int>(std::lround(labels.at(si, sj))) : -1;
      o.regionLabels[rowMajor(i, j, width)] = label;
      maxLabel = std::max(maxLabel, label);
    }
  }
  o.regionExemplars.assign(static_cast<std::size_t>(std::max(0, maxLabel + 1)), {});
  for (const std::string& m : maps)
  {
    const std::size_t eq = m.find('=');
    int label = -1;
    if (eq == std::string::npos || !parseWhole(m.substr(0, eq), label) || label > maxLabel)
    {
      throw Error(
        "A region map must read LABEL=E1,E2 with a label present in the region image, not \"" + m +
        "\".");
    }
    std::stringstream list(m.substr(eq + 1));
    std::string item;
    while (std::getline(list, item, ','))
    {
      int e = -1;
      if (!parseWhole(item, e) || static_cast<std::size_t>(e) >= exemplars)
      {
        throw Error("Region map " + m + ": exemplar numbers run from 0 to " +
          std::to_string(exemplars - 1) + ".");
      }
      o.regionExemplars[static_cast<std::size_t>(label)].push_back(e);
    }
  }
  for (int l = 0; l <= maxLabel; ++l)
  {
    auto& list = o.regionExemplars[static_cast<std::size_t>(l)];
    const bool used =
      std::find(o.regionLabels.begin(), o.regionLabels.end(), l) != o.regionLabels.end();
    if (list.empty() && used)
    {
      if (static_cast<std::size_t>(l) >= exemplars)
      {
        throw Error("Region label " + std::to_string(l) + " has no exemplar: map it (" +
          std::to_string(l) + "=E) or give more exemplars.");
      }
      list.push_back(l);
    }
  }
}

} // namespace tsynth
