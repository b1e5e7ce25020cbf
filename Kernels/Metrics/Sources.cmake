set(TSYNTH_METRICS_SOURCES
  Metrics/LandformMetrics.cxx
  Metrics/Legibility.cxx
  Metrics/TerrainMetrics.cxx)
