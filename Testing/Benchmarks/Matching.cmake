add_executable(tsynth_bench_matching BenchMatching.cxx)
target_link_libraries(tsynth_bench_matching PRIVATE tsynth::kernels OpenMP::OpenMP_CXX)
target_compile_definitions(tsynth_bench_matching PRIVATE TSYNTH_BUNDLED_DATA="${TSYNTH_BUNDLED_DATA}")
target_compile_options(tsynth_bench_matching PRIVATE ${TSYNTH_WARNING_FLAGS})
