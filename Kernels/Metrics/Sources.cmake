set(TSYNTH_METRICS_SOURCES
  Metrics/LandformMetrics.cxx
  Metrics/TerrainMetrics.cxx)
