add_executable(tsynth_bench_matching BenchMatching.cxx)
target_link_libraries(tsynth_bench_matching PRIVATE tsynth::kernels OpenMP::OpenMP_CXX)
target_compile_definitions(tsynth_bench_matching PRIVATE TSYNTH_BUNDLED_DATA="${TSYNTH_BUNDLED_DATA}")
target_compile_options(tsynth_bench_matching PRIVATE ${TSYNTH_WARNING_FLAGS})
# What the dense matcher holds, part by part, for the README's 4096^2 exemplars.
add_executable(tsynth_bench_matcher_memory BenchMatcherMemory.cxx)
target_link_libraries(tsynth_bench_matcher_memory PRIVATE tsynth::kernels OpenMP::OpenMP_CXX)
target_compile_definitions(tsynth_bench_matcher_memory PRIVATE TSYNTH_SHARED_DATA="${TSYNTH_SHARED_DATA}")
target_compile_options(tsynth_bench_matcher_memory PRIVATE ${TSYNTH_WARNING_FLAGS})
