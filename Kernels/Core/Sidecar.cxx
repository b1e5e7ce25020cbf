#include "Sidecar.h"

#include "Error.h"
#include "OutputFile.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace tsynth
{

std::optional<ZUnit> parseZUnit(const std::string& text)
{
  std::string t = text;
  std::transform(t.begin(),
    t.end(),
    t.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (t == "m" || t == "metre" || t == "metres" || t == "meter" || t == "meters")
  {
    return ZUnit::Metres;
  }
  if (t == "ft" || t == "foot" || t == "feet" || t == "us-ft")
  {
    return ZUnit::Feet;
  }
  if (t == "auto")
  {
    return ZUnit::Auto;
  }
  return std::nullopt;
}

const char* zUnitName(ZUnit unit)
{
  switch (unit)
  {
    case ZUnit::Metres:
      return "m";
    case ZUnit::Feet:
      return "ft";
    case ZUnit::Auto:
      break;
  }
  return "auto";
}

std::string sidecarPathFor(const std::string& rasterPath)
{
  std::filesystem::path p(rasterPath);
  p.replace_extension(".json");
  return p.string();
}

namespace
{

double positiveNumber(const nlohmann::json& v, const std::string& key, const std::string& path)
{
  if (!v.is_number() || !(v.get<double>() > 0.0))
  {
    throw Error("Sidecar " + path + ": \"" + key + "\" must be a positive number of metres.");
  }
  return v.get<double>();
}

double number(const nlohmann::json& v, const std::string& key, const std::string& path)
{
  if (!v.is_number())
  {
    throw Error("Sidecar " + path + ": \"" + key + "\" must be a number.");
  }
  return v.get<double>();
}

} // namespace

Sidecar readSidecar(const std::string& path)
{
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
  {
    // A folder opens as a stream and fails only when read, with a library message.
    throw Error("Cannot read sidecar " + path + ": it is not a file; remove it.");
  }
  std::ifstream in(path);
  if (!in)
  {
    throw Error("Cannot read sidecar " + path + ".");
  }
  nlohmann::json doc;
  try
  {
    doc = nlohmann::json::parse(in);
  }
  catch (const nlohmann::json::parse_error& e)
  {
    throw Error("Sidecar " + path + " is not valid JSON (byte " + std::to_string(e.byte) +
      "); fix it or remove it.");
  }
  catch (const nlohmann::json::out_of_range&)
  {
    // The parser's only other complaint: a number beyond a double (1e999).
    throw Error("Sidecar " + path +
      " holds a number too large for a double (over 1.8e308); fix it or remove it.");
  }
  if (!doc.is_object())
  {
    throw Error("Sidecar " + path + " must hold a JSON object such as {\"z_unit\": \"m\"}.");
  }

  Sidecar s;
  if (doc.contains("z_unit"))
  {
    const auto& v = doc["z_unit"];
    std::optional<ZUnit> unit = v.is_string() ? parseZUnit(v.get<std::string>()) : std::nullopt;
    if (!unit || *unit == ZUnit::Auto)
    {
      throw Error("Sidecar " + path + ": \"z_unit\" must be \"m\" or \"ft\".");
    }
    s.zUnit = unit;
  }
  if (doc.contains("cell_size_m"))
  {
    const auto& v = doc["cell_size_m"];
    if (v.is_array())
    {
      if (v.size() != 2)
      {
        throw Error("Sidecar " + path + ": \"cell_size_m\" must be a number or [x, y].");
      }
      s.cellX = positiveNumber(v[0], "cell_size_m", path);
      s.cellY = positiveNumber(v[1], "cell_size_m", path);
    }
    else
    {
      s.cellX = s.cellY = positiveNumber(v, "cell_size_m", path);
    }
  }
  if (doc.contains("z_min") != doc.contains("z_max"))
  {
    throw Error("Sidecar " + path + ": \"z_min\" and \"z_max\" must be given together.");
  }
  if (doc.contains("z_min"))
  {
    s.zMin = number(doc["z_min"], "z_min", path);
    s.zMax = number(doc["z_max"], "z_max", path);
    if (!(*s.zMax > *s.zMin))
    {
      throw Error("Sidecar " + path + ": \"z_max\" must be greater than \"z_min\".");
    }
  }
  if (doc.contains("nodata"))
  {
    s.nodata = number(doc["nodata"], "nodata", path);
  }
  return s;
}

void writeSidecar(const std::string& path, const Sidecar& s)
{
  // An object even without keys: a default ordered_json would be written as `null`,
  // which readSidecar refuses.
  nlohmann::ordered_json doc = nlohmann::ordered_json::object();
  if (s.zUnit)
  {
    doc["z_unit"] = zUnitName(*s.zUnit);
  }
  if (s.cellX && s.cellY)
  {
    if (*s.cellX == *s.cellY)
    {
      doc["cell_size_m"] = *s.cellX;
    }
    else
    {
      doc["cell_size_m"] = { *s.cellX, *s.cellY };
    }
  }
  if (s.zMin && s.zMax)
  {
    doc["z_min"] = *s.zMin;
    doc["z_max"] = *s.zMax;
  }
  if (s.nodata)
  {
    doc["nodata"] = *s.nodata;
  }
  OutputFile file(path);
  file.write(doc.dump(2) + "\n");
  file.commit();
}

} // namespace tsynth
