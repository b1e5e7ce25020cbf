// An algorithm's options written once, for every front end: the words an
// enumeration is typed as, and a row per option giving its filter property, its
// tsynth option, its default, the values it takes and, for an enumeration, its
// words and the labels ParaView shows. The command line and the filters read the
// rows; Testing/Cxx/TestFilterOptions.cxx checks the plugin XML against them.
// Synthesis' rows: Synthesis/SynthesisRequest.h.
#pragma once

#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace tsynth
{

// An enumeration's words, in the order ParaView lists them: word i stands for
// value i (the filters' property value i and the plugin XML's Entry value i),
// or for values[i] where the values are not 0, 1, 2 ... (a feature type's +1
// ridge and -1 valley).
struct Choices
{
  const char* const* words = nullptr;
  std::size_t count = 0;
  const int* values = nullptr; // by position; nullptr: each word's position

  // The value of the i-th word.
  int valueAt(std::size_t i) const { return values != nullptr ? values[i] : static_cast<int>(i); }

  // "cut, poisson, shepard or new".
  std::string list() const;
  // The value `word` stands for. Throws tsynth::Error "<what> must be cut,
  // poisson, shepard or new, not "x"." for any other word.
  int valueOf(const std::string& word, const std::string& what) const;
  // The word of `value`. Throws tsynth::Error naming `what` and the values taken
  // for a value no word stands for (a property set by number in a script).
  const char* wordOf(int value, const std::string& what) const;
};

template<std::size_t N>
constexpr Choices choicesOf(const char* const (&words)[N])
{
  return { words, N, nullptr };
}

// Words that stand for the values beside them, not for their positions.
template<std::size_t N>
constexpr Choices choicesOf(const char* const (&words)[N], const int (&values)[N])
{
  return { words, N, values };
}

// The enumeration value `value` (a filter property) stands for, checked.
template<class Enum>
Enum choiceOf(const Choices& choices, int value, const std::string& what)
{
  choices.wordOf(value, what); // throws for a value outside the words
  return static_cast<Enum>(value);
}

enum class OptionType
{
  Integer,
  Real,
  Switch, // on or off: the property's 1 or 0
  Choice  // an enumeration: the property's value is the word's position
};

constexpr double kUnbounded = std::numeric_limits<double>::infinity();

struct OptionRow
{
  std::string property; // the filter's property, as the plugin XML names it
  std::string flag;     // the tsynth option that sets the same thing ("" none)
  OptionType type = OptionType::Real;
  double defaultValue = 0.0; // as the property holds it (a Choice: the value)
  // A pair's second default (LO,HI options); none: every element takes defaultValue.
  std::optional<double> secondDefault;
  double min = -kUnbounded; // the property's range; +-kUnbounded: none that side
  double max = kUnbounded;
  Choices choices;                 // a Choice's tsynth words, by value
  std::vector<std::string> labels; // a Choice's entries in ParaView, by value

  // Throws tsynth::Error "<name> expects a number from A to B." (or "a whole
  // number", or "at least A") for a value outside the range or, for an Integer,
  // not whole.
  void checkValue(double value, const std::string& name) const;
  // The range in words: "from 0 to 100", "at least 0".
  std::string rangeText() const;
};

// A bound or default as messages and help print it: "0.5", "1000000".
std::string numberText(double value);

// Rows of each type, for an algorithm's table.
OptionRow numberRow(const char* property,
  const char* flag,
  OptionType type, // Integer or Real
  double defaultValue,
  double min,
  double max);
// Its range is the words' smallest value to their largest.
OptionRow choiceRow(const char* property,
  const char* flag,
  int defaultValue,
  const Choices& words,
  std::vector<std::string> labels);
OptionRow switchRow(const char* property, const char* flag, bool defaultValue);
// Every front end's memory budget: MemoryBudget in GB, --max-memory, 0 to kMaxMemoryBudgetGB.
OptionRow memoryBudgetRow(double defaultBytes);

// The row of `property`; throws tsynth::Error if there is none (a programming error).
const OptionRow& optionRow(const std::vector<OptionRow>& rows, const std::string& property);

} // namespace tsynth
