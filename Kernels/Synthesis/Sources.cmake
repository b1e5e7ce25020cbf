set(TSYNTH_SYNTHESIS_SOURCES
  Synthesis/Finishing.cxx
  Synthesis/Landform.cxx
  Synthesis/PatchColours.cxx
  Synthesis/Regions.cxx
  Synthesis/Setup.cxx
  Synthesis/Synthesizer.cxx
  Synthesis/Target.cxx)
