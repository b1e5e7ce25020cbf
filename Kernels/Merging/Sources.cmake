# Patch merging: graph-cut seams, Poisson solvers, blending.
set(TSYNTH_MERGING_SOURCES
  Merging/GridMaxFlow.cxx
  Merging/SeamCut.cxx
  Merging/Poisson.cxx
  Merging/PoissonEditing.cxx
  Merging/PatchMerger.cxx)
# The Poisson DST solver runs in double precision.
pkg_check_modules(FFTW3 REQUIRED IMPORTED_TARGET fftw3)
target_link_libraries(tsynth_kernels PRIVATE PkgConfig::FFTW3)
# The blending and Poisson loops call sqrt on values known to be >= 0; without
# errno they vectorise. Results are unchanged (IEEE sqrt is exact either way).
if (CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
  set_source_files_properties(Merging/PatchMerger.cxx PROPERTIES COMPILE_OPTIONS -fno-math-errno)
endif ()
