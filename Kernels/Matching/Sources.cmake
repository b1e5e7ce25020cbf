set(TSYNTH_MATCHING_SOURCES
  Matching/CandidatePool.cxx
  Matching/DenseSearch.cxx
  Matching/FeatureCost.cxx
  Matching/FeatureRanking.cxx
  Matching/LandformTerm.cxx
  Matching/NoiseVariance.cxx
  Matching/OpenClMatcher.cxx
  Matching/PatchMatcher.cxx
  Matching/SiteMatch.cxx
  Matching/Orientation.cxx)

# The OpenCL kernels are embedded in the library as strings.
set(_tsynth_cl_dir "${CMAKE_CURRENT_SOURCE_DIR}/Matching/OpenCL")
file(READ "${_tsynth_cl_dir}/FeatureCost.cl" TSYNTH_CL_FEATURE_COST)
file(READ "${_tsynth_cl_dir}/DenseSsd.cl" TSYNTH_CL_DENSE_SSD)
configure_file("${_tsynth_cl_dir}/OpenClSources.h.in"
  "${CMAKE_CURRENT_BINARY_DIR}/Matching/OpenClSources.h" @ONLY)
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS
  "${_tsynth_cl_dir}/FeatureCost.cl" "${_tsynth_cl_dir}/DenseSsd.cl"
  "${_tsynth_cl_dir}/OpenClSources.h.in")
target_include_directories(tsynth_kernels PRIVATE "${CMAKE_CURRENT_BINARY_DIR}")
