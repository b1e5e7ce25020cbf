# Hydrology benchmark: depression filling against a plain priority-queue fill,
# D8 directions and flow accumulation on a 4096 x 4096 real terrain.
add_executable(tsynth_bench_hydrology BenchHydrology.cxx)
target_link_libraries(tsynth_bench_hydrology PRIVATE tsynth::kernels OpenMP::OpenMP_CXX)
target_compile_definitions(tsynth_bench_hydrology PRIVATE TSYNTH_BUNDLED_DATA="${TSYNTH_BUNDLED_DATA}")
target_compile_options(tsynth_bench_hydrology PRIVATE ${TSYNTH_WARNING_FLAGS})
