#include "CommandLine.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace tsynth::cli
{

CommandLine::CommandLine(std::vector<std::string> args)
  : args_(std::move(args))
  , used_(args_.size(), false)
{
}

std::optional<std::string> CommandLine::take(const std::string& name, const std::string& alias)
{
  const std::vector<std::string> values = takeAll(name, alias);
  return values.empty() ? std::nullopt : std::make_optional(values.back()); // the last one given
}

std::vector<std::string> CommandLine::takeAll(const std::string& name, const std::string& alias)
{
  std::vector<std::string> values;
  for (std::size_t k = 0; k < args_.size(); ++k)
  {
    if (used_[k])
    {
      continue;
    }
    const std::string& a = args_[k];
    if (a == name || (!alias.empty() && a == alias))
    {
      if (k + 1 >= args_.size())
      {
        throw UsageError(name + " needs a value.");
      }
      used_[k] = used_[k + 1] = true;
      values.push_back(args_[k + 1]);
      ++k;
    }
    else if (a.rfind(name + "=", 0) == 0)
    {
      used_[k] = true;
      values.push_back(a.substr(name.size() + 1));
    }
  }
  return values;
}

bool CommandLine::takeFlag(const std::string& name)
{
  bool found = false;
  for (std::size_t k = 0; k < args_.size(); ++k)
  {
    if (!used_[k] && args_[k] == name)
    {
      used_[k] = true;
      found = true;
    }
  }
  return found;
}

std::optional<double> CommandLine::takeNumber(const std::string& name)
{
  const std::optional<std::string> text = take(name);
  if (!text)
  {
    return std::nullopt;
  }
  const std::optional<double> v = parseNumber(*text);
  if (!v)
  {
    throw UsageError(name + " expects a number, not \"" + *text + "\".");
  }
  return v;
}

bool CommandLine::gives(const std::string& name) const
{
  return std::any_of(args_.begin(),
    args_.end(),
    [&](const std::string& a) { return a == name || a.rfind(name + "=", 0) == 0; });
}

std::vector<std::string> CommandLine::positionals() const
{
  std::vector<std::string> out;
  for (std::size_t k = 0; k < args_.size(); ++k)
  {
    if (used_[k])
    {
      continue;
    }
    const std::string& a = args_[k];
    if (a.size() > 1 && a[0] == '-' && !parseNumber(a))
    {
      throw UsageError("Unknown option " + a + ".");
    }
    out.push_back(a);
  }
  return out;
}

std::optional<double> parseNumber(const std::string& text)
{
  if (text.empty())
  {
    return std::nullopt;
  }
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  // "nan", "inf" and overflowing values are no option's number: every range
  // check downstream would let NaN through.
  if (end == nullptr || *end != '\0' || !std::isfinite(v))
  {
    return std::nullopt;
  }
  return v;
}

} // namespace tsynth::cli
