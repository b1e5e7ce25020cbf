// Settings the C library and OpenMP read once, when a program starts, that
// `tsynth synth` wants (RuntimeSettings.cxx says which and why). They must be
// in the environment before the program loads: the launcher (Launcher.cxx)
// sets them and then starts tsynth-main, so synth starts once, not twice.
// Plain C++ and the C library only: the launcher must load in a millisecond.
#pragma once

namespace tsynth::cli
{

// Puts synth's settings in the environment, leaving alone any the user set;
// true if it changed anything (a program already running must then re-run
// itself for them to take effect).
bool setSynthRuntimeSettings();

} // namespace tsynth::cli
