# Patch merging: graph-cut seams, Poisson solvers, blending.
set(TSYNTH_MERGING_SOURCES
  Merging/GridMaxFlow.cxx
  Merging/SeamCut.cxx
  Merging/Poisson.cxx
  Merging/PatchMerger.cxx)
# The Poisson DST solver runs in double precision.
pkg_check_modules(FFTW3 REQUIRED IMPORTED_TARGET fftw3)
target_link_libraries(tsynth_kernels PRIVATE PkgConfig::FFTW3)
