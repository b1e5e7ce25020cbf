# Terrain optimisation (Scott & Dodgson 2021): pyramids, oriented PatchMatch,
# the EM loop with pit removal, determinism and input checks.
add_executable(tsynth_optimisation_tests
  Optimisation/TestOptimisationGuide.cxx
  Optimisation/TestPatchMatch.cxx
  Optimisation/TestPyramid.cxx
  Optimisation/TestTerrainOptimisation.cxx)
target_link_libraries(tsynth_optimisation_tests PRIVATE
  tsynth::kernels GDAL::GDAL OpenMP::OpenMP_CXX GTest::gtest GTest::gtest_main)
target_compile_definitions(tsynth_optimisation_tests PRIVATE ${data_definitions})
target_include_directories(tsynth_optimisation_tests PRIVATE "${CMAKE_CURRENT_SOURCE_DIR}")
target_compile_options(tsynth_optimisation_tests PRIVATE ${TSYNTH_WARNING_FLAGS})
gtest_discover_tests(tsynth_optimisation_tests
  TEST_PREFIX "optimisation."
  WORKING_DIRECTORY "${CMAKE_CURRENT_BINARY_DIR}"
  DISCOVERY_TIMEOUT 60)
