// A small argument reader for tsynth's sub-commands: options may come in any
// order, as "--name value" or "--name=value"; anything left over is an error.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace tsynth::cli
{

// Wrong usage: reported with a pointer to --help and exit code 2.
class UsageError : public std::runtime_error
{
public:
  explicit UsageError(const std::string& message)
    : std::runtime_error(message)
  {
  }
};

class CommandLine
{
public:
  explicit CommandLine(std::vector<std::string> args);

  // Takes "--name V" / "--name=V" (or a short alias such as "-o"); nullopt if absent,
  // the last value if given more than once.
  std::optional<std::string> take(const std::string& name, const std::string& alias = "");
  // Takes every value of a repeatable option ("--exemplar A --exemplar B"), in order.
  std::vector<std::string> takeAll(const std::string& name, const std::string& alias = "");
  // Takes a bare flag such as "--3d".
  bool takeFlag(const std::string& name);
  // Numeric options, with a clear message when the value is not a number.
  std::optional<double> takeNumber(const std::string& name);
  // Whether "--name V" or "--name=V" is among the arguments, taken or not.
  bool gives(const std::string& name) const;
  // Returns the positional arguments; throws UsageError for an unknown option.
  std::vector<std::string> positionals() const;

private:
  std::vector<std::string> args_;
  std::vector<bool> used_;
};

// Parses "123.5" strictly (the whole text must be a finite number).
std::optional<double> parseNumber(const std::string& text);

} // namespace tsynth::cli
