set(TSYNTH_SYNTHESIS_SOURCES
  Synthesis/Regions.cxx
  Synthesis/Setup.cxx
  Synthesis/Synthesizer.cxx
  Synthesis/Target.cxx)
