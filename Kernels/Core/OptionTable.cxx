#include "OptionTable.h"

#include "Error.h"
#include "Memory.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <utility>

namespace tsynth
{

std::string Choices::list() const
{
  std::string text;
  for (std::size_t i = 0; i < count; ++i)
  {
    text += i == 0 ? "" : i + 1 == count ? " or " : ", ";
    text += words[i];
  }
  return text;
}

int Choices::valueOf(const std::string& word, const std::string& what) const
{
  for (std::size_t i = 0; i < count; ++i)
  {
    if (word == words[i])
    {
      return valueAt(i);
    }
  }
  throw Error(what + " must be " + list() + ", not \"" + word + "\".");
}

const char* Choices::wordOf(int value, const std::string& what) const
{
  for (std::size_t i = 0; i < count; ++i)
  {
    if (valueAt(i) == value)
    {
      return words[i];
    }
  }
  std::string taken;
  for (std::size_t i = 0; i < count; ++i)
  {
    const char* separator = i == 0 ? "" : i + 1 == count ? " or " : ", ";
    taken += separator + std::to_string(valueAt(i)) + " " + words[i];
  }
  throw Error(what + " " + std::to_string(value) + " is none of " + taken + ".");
}

namespace
{
// Enough for every bound and default in the tables to print as typed (1000000, not 1e+06).
constexpr int kShownDigits = 12;
} // namespace

std::string numberText(double value)
{
  std::ostringstream text;
  text << std::setprecision(kShownDigits) << value;
  return text.str();
}

std::string OptionRow::rangeText() const
{
  if (std::isinf(max))
  {
    return "at least " + numberText(min);
  }
  return "from " + numberText(min) + " to " + numberText(max);
}

void OptionRow::checkValue(double value, const std::string& name) const
{
  const bool whole = type != OptionType::Real;
  if (!(value >= min && value <= max) || (whole && value != std::floor(value)))
  {
    throw Error(name + " expects " + (whole ? "a whole number " : "a number ") + rangeText() +
      ", not " + numberText(value) + ".");
  }
}

OptionRow numberRow(const char* property,
  const char* flag,
  OptionType type,
  double defaultValue,
  double min,
  double max)
{
  OptionRow row;
  row.property = property;
  row.flag = flag;
  row.type = type;
  row.defaultValue = defaultValue;
  row.min = min;
  row.max = max;
  return row;
}

OptionRow choiceRow(const char* property,
  const char* flag,
  int defaultValue,
  const Choices& words,
  std::vector<std::string> labels)
{
  int smallest = words.valueAt(0);
  int largest = smallest;
  for (std::size_t i = 1; i < words.count; ++i)
  {
    smallest = std::min(smallest, words.valueAt(i));
    largest = std::max(largest, words.valueAt(i));
  }
  OptionRow row = numberRow(property, flag, OptionType::Choice, defaultValue, smallest, largest);
  row.choices = words;
  row.labels = std::move(labels);
  return row;
}

OptionRow switchRow(const char* property, const char* flag, bool defaultValue)
{
  return numberRow(property, flag, OptionType::Switch, defaultValue ? 1.0 : 0.0, 0.0, 1.0);
}

OptionRow memoryBudgetRow(double defaultBytes)
{
  return numberRow("MemoryBudget",
    "--max-memory",
    OptionType::Real,
    defaultBytes / kBytesPerGB,
    0.0,
    kMaxMemoryBudgetGB);
}

const OptionRow& optionRow(const std::vector<OptionRow>& rows, const std::string& property)
{
  for (const OptionRow& row : rows)
  {
    if (row.property == property)
    {
      return row;
    }
  }
  throw Error("No option is called " + property + ".");
}

} // namespace tsynth
