// Mathematical constants, written once.
#pragma once

namespace tsynth
{

constexpr double kPi = 3.14159265358979323846;
constexpr double kTwoPi = 2.0 * kPi;

} // namespace tsynth
