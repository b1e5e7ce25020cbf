set(TSYNTH_METRICS_SOURCES
  Metrics/TerrainMetrics.cxx)
