# Patch merging kernels: graph cut, Poisson solvers, blending.
add_executable(tsynth_merging_tests
  Merging/TestGridMaxFlow.cxx
  Merging/TestSeamCut.cxx
  Merging/TestPoisson.cxx
  Merging/TestPoissonEditing.cxx
  Merging/TestPatchMerger.cxx)
target_link_libraries(tsynth_merging_tests PRIVATE
  tsynth::kernels GDAL::GDAL Boost::headers Eigen3::Eigen GTest::gtest GTest::gtest_main)
target_compile_definitions(tsynth_merging_tests PRIVATE ${data_definitions})
target_include_directories(tsynth_merging_tests PRIVATE "${CMAKE_CURRENT_SOURCE_DIR}")
target_compile_options(tsynth_merging_tests PRIVATE ${TSYNTH_WARNING_FLAGS})
gtest_discover_tests(tsynth_merging_tests
  TEST_PREFIX "merging."
  WORKING_DIRECTORY "${CMAKE_CURRENT_BINARY_DIR}"
  DISCOVERY_TIMEOUT 60)
