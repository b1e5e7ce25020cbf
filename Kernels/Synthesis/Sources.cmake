set(TSYNTH_SYNTHESIS_SOURCES
  Synthesis/Synthesizer.cxx
  Synthesis/Target.cxx)
