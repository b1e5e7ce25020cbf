#include "Heightfield.h"

#include "ContentHash.h"
#include "Error.h"
#include "Grid.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

namespace tsynth
{

Heightfield::Heightfield(int w, int h, float value)
  : width(w)
  , height(h)
  , z(cellCount(w, h), value)
{
}

void hashHeightfield(ContentHasher& h, const Heightfield& f)
{
  h.value(f.width);
  h.value(f.height);
  h.value(f.cellX);
  h.value(f.cellY);
  h.values(f.z);
  h.values(f.valid);
}

std::size_t Heightfield::validCount() const
{
  if (valid.empty())
  {
    return z.size();
  }
  std::size_t n = 0;
  for (std::uint8_t v : valid)
  {
    n += v != 0 ? 1 : 0;
  }
  return n;
}

HeightRange computeHeightRange(const Heightfield& hf)
{
  HeightRange r;
  float lo = std::numeric_limits<float>::infinity();
  float hi = -std::numeric_limits<float>::infinity();
  double sum = 0.0;
  for (std::size_t k = 0; k < hf.z.size(); ++k)
  {
    if (!hf.isValid(k))
    {
      continue;
    }
    const float v = hf.z[k];
    lo = std::min(lo, v);
    hi = std::max(hi, v);
    sum += v;
    ++r.validCells;
  }
  if (r.validCells > 0)
  {
    r.min = lo;
    r.max = hi;
    r.mean = sum / static_cast<double>(r.validCells);
  }
  return r;
}

void normaliseMask(Heightfield& hf)
{
  bool anyInvalid = false;
  for (std::size_t k = 0; k < hf.z.size(); ++k)
  {
    if (!std::isfinite(hf.z[k]) || !hf.isValid(k))
    {
      anyInvalid = true;
      break;
    }
  }
  if (!anyInvalid)
  {
    hf.valid.clear();
    return;
  }
  hf.valid.resize(hf.z.size(), 1);
  for (std::size_t k = 0; k < hf.z.size(); ++k)
  {
    if (!std::isfinite(hf.z[k]) || hf.valid[k] == 0)
    {
      hf.valid[k] = 0;
      hf.z[k] = std::numeric_limits<float>::quiet_NaN();
    }
  }
}

double percentile(std::vector<float> values, double p)
{
  if (values.empty())
  {
    return 0.0;
  }
  const std::size_t k = std::min(
    values.size() - 1, static_cast<std::size_t>(p * static_cast<double>(values.size() - 1)));
  std::nth_element(values.begin(), values.begin() + static_cast<long>(k), values.end());
  return values[k];
}

void checkPlausibleHeights(const Heightfield& hf, const std::string& name)
{
  std::size_t beyond = 0;
  float example = 0.0f;
  for (std::size_t k = 0; k < hf.size(); ++k)
  {
    if (hf.isValid(k) && std::abs(hf.z[k]) > kMaxPlausibleHeight)
    {
      example = beyond == 0 ? hf.z[k] : example;
      ++beyond;
    }
  }
  if (beyond == 0)
  {
    return;
  }
  std::ostringstream value; // exact, so that the sidecar's value matches the cells
  value << std::setprecision(std::numeric_limits<float>::max_digits10) << example;
  std::ostringstream o;
  o << name << " has " << beyond << " heights beyond +-" << kMaxPlausibleHeight << " m (such as "
    << value.str() << "), probably an undeclared nodata value: declare it in the file or in a "
    << "sidecar (\"nodata\": " << value.str() << ").";
  throw Error(o.str());
}

bool hasValidWindow(const Heightfield& hf, int side)
{
  if (side <= 0 || hf.width < side || hf.height < side)
  {
    return false;
  }
  if (!hf.hasMask())
  {
    return true;
  }
  // Runs of valid cells: down each column, then along each row of "column run >= side".
  const auto w = static_cast<std::size_t>(hf.width);
  std::vector<int> columnRun(w, 0);
  for (int j = 0; j < hf.height; ++j)
  {
    int rowRun = 0;
    for (int i = 0; i < hf.width; ++i)
    {
      int& run = columnRun[static_cast<std::size_t>(i)];
      run = hf.isValid(i, j) ? run + 1 : 0;
      rowRun = run >= side ? rowRun + 1 : 0;
      if (rowRun >= side)
      {
        return true;
      }
    }
  }
  return false;
}

void checkWritableHeights(const Heightfield& hf, const std::string& path)
{
  for (std::size_t k = 0; k < hf.size(); ++k)
  {
    if (hf.isValid(k) && !(std::abs(hf.z[k]) <= kMaxPlausibleHeight))
    {
      std::ostringstream o;
      o << "Cannot write " << path << ": its heights reach " << hf.z[k] << " m, beyond the +-"
        << kMaxPlausibleHeight << " m that any terrain (and tsynth's reader) holds; "
        << "lower the height scale.";
      throw Error(o.str());
    }
  }
}

} // namespace tsynth
