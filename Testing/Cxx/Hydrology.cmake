# Hydrology kernels: depression filling, breaching and the hybrid, the pyramid pit
# removal, D8 directions, flow accumulation.
add_executable(tsynth_hydrology_tests
  Hydrology/TestRadixHeap.cxx
  Hydrology/TestBreach.cxx
  Hydrology/TestFlow.cxx
  Hydrology/TestPitRemoval.cxx
  Hydrology/TestMultiscalePitRemoval.cxx)
target_link_libraries(tsynth_hydrology_tests PRIVATE
  tsynth::kernels GDAL::GDAL OpenMP::OpenMP_CXX GTest::gtest GTest::gtest_main)
target_compile_definitions(tsynth_hydrology_tests PRIVATE ${data_definitions})
target_include_directories(tsynth_hydrology_tests PRIVATE "${CMAKE_CURRENT_SOURCE_DIR}")
target_compile_options(tsynth_hydrology_tests PRIVATE ${TSYNTH_WARNING_FLAGS})
gtest_discover_tests(tsynth_hydrology_tests
  TEST_PREFIX "hydrology."
  WORKING_DIRECTORY "${CMAKE_CURRENT_BINARY_DIR}"
  DISCOVERY_TIMEOUT 60)
