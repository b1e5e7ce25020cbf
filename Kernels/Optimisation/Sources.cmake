# Terrain optimisation (Scott & Dodgson 2021): multi-resolution PatchMatch
# texture optimisation with pit removal.
set(TSYNTH_OPTIMISATION_SOURCES
  Optimisation/OptimisationGuide.cxx
  Optimisation/PatchMatch.cxx
  Optimisation/Pyramid.cxx
  Optimisation/TerrainOptimisation.cxx)
