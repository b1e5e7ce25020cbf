# Surface drainage: depression filling, breaching and the hybrid, D8 flow
# directions and accumulation.
set(TSYNTH_HYDROLOGY_SOURCES
  Hydrology/Breach.cxx
  Hydrology/Flow.cxx
  Hydrology/MultiscalePitRemoval.cxx
  Hydrology/PitRemoval.cxx)
