# Distance-based synthesis kernels (Rusnell 2009): lattice, generators, cost
# scaling, bounded searches and blending.
add_executable(tsynth_distance_tests
  Distance/TestDistanceSynthesis.cxx
  Distance/TestCostScaling.cxx
  Distance/TestDistanceSources.cxx
  Distance/TestGenerators.cxx
  Distance/TestLattice.cxx)
target_link_libraries(tsynth_distance_tests PRIVATE
  tsynth::kernels OpenMP::OpenMP_CXX GTest::gtest GTest::gtest_main)
target_include_directories(tsynth_distance_tests PRIVATE "${CMAKE_CURRENT_SOURCE_DIR}")
target_compile_options(tsynth_distance_tests PRIVATE ${TSYNTH_WARNING_FLAGS})
gtest_discover_tests(tsynth_distance_tests
  TEST_PREFIX "distance."
  WORKING_DIRECTORY "${CMAKE_CURRENT_BINARY_DIR}"
  DISCOVERY_TIMEOUT 60)
