# In the order of the former TestMatching.cxx: PatchMatcher's last test sets OCL_ICD_VENDORS for
# the rest of the process, after the tests that use OpenCL.
add_executable(tsynth_matching_tests
  Matching/TestOrientation.cxx
  Matching/TestLandformTerm.cxx
  Matching/TestNoiseVariance.cxx
  Matching/TestFeatureCost.cxx
  Matching/TestFeatureRanking.cxx
  Matching/TestCandidatePool.cxx
  Matching/TestDenseSearch.cxx
  Matching/TestOpenClMatcher.cxx
  Matching/TestPatchMatcher.cxx
  Matching/TestSiteMatch.cxx)
target_link_libraries(tsynth_matching_tests PRIVATE
  tsynth::kernels GDAL::GDAL GTest::gtest GTest::gtest_main)
target_compile_definitions(tsynth_matching_tests PRIVATE ${data_definitions})
target_include_directories(tsynth_matching_tests PRIVATE "${CMAKE_CURRENT_SOURCE_DIR}")
target_compile_options(tsynth_matching_tests PRIVATE ${TSYNTH_WARNING_FLAGS})
gtest_discover_tests(tsynth_matching_tests
  TEST_PREFIX "matching."
  WORKING_DIRECTORY "${CMAKE_CURRENT_BINARY_DIR}"
  DISCOVERY_TIMEOUT 60)
