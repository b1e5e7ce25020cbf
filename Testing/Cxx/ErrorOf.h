// The sentence a call throws: what the tests of bad input compare.
#pragma once

#include "Core/Error.h"

#include <string>

namespace tsynth::test
{

// The message of the tsynth::Error `f` throws; "" if it throws none.
template<typename F>
std::string errorOf(F&& f)
{
  try
  {
    f();
  }
  catch (const Error& e)
  {
    return e.what();
  }
  return "";
}

} // namespace tsynth::test
