# Surface drainage: depression filling, D8 flow directions and accumulation.
set(TSYNTH_HYDROLOGY_SOURCES
  Hydrology/Flow.cxx)
