# Distance-based synthesis benchmark (Rusnell 2009): 512^2 with 100 features and
# 1536^2 with 15,000; radix heap vs std::priority_queue, 2 threads vs 1.
add_executable(tsynth_bench_distance BenchDistance.cxx)
target_link_libraries(tsynth_bench_distance PRIVATE tsynth::kernels OpenMP::OpenMP_CXX)
target_compile_options(tsynth_bench_distance PRIVATE ${TSYNTH_WARNING_FLAGS})
# The exact distance transform at 4096^2 (distances alone, and with the nearest
# seeds): time and peak memory; link against another build's library to compare.
add_executable(tsynth_bench_distance_field BenchDistanceField.cxx)
target_link_libraries(tsynth_bench_distance_field PRIVATE tsynth::kernels OpenMP::OpenMP_CXX)
target_compile_options(tsynth_bench_distance_field PRIVATE ${TSYNTH_WARNING_FLAGS})
