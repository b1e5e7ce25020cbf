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

} // namespace tsynth
