add_executable(tsynth_matching_tests TestMatching.cxx)
target_link_libraries(tsynth_matching_tests PRIVATE
  tsynth::kernels GDAL::GDAL GTest::gtest GTest::gtest_main)
target_compile_definitions(tsynth_matching_tests PRIVATE ${data_definitions})
target_compile_options(tsynth_matching_tests PRIVATE ${TSYNTH_WARNING_FLAGS})
gtest_discover_tests(tsynth_matching_tests
  TEST_PREFIX "matching."
  WORKING_DIRECTORY "${CMAKE_CURRENT_BINARY_DIR}"
  DISCOVERY_TIMEOUT 60)
