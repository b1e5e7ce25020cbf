// The one exception type the kernels throw: its message is a sentence a user can act on.
#pragma once

#include <stdexcept>
#include <string>

namespace tsynth
{

class Error : public std::runtime_error
{
public:
  explicit Error(const std::string& message)
    : std::runtime_error(message)
  {
  }
};

// A long computation stopped because its caller asked it to (a progress
// callback returned false: ParaView's abort, Ctrl-C in the command line).
class Cancelled : public Error
{
public:
  Cancelled()
    : Error("Cancelled.")
  {
  }
};

} // namespace tsynth
