# Terrain optimisation benchmark: a 1024^2 terrain from a 648^2 source with a
# guide made as in Scott & Dodgson 2021, per-level figures and same-run ratios.
add_executable(tsynth_bench_optimisation BenchOptimisation.cxx)
target_link_libraries(tsynth_bench_optimisation PRIVATE tsynth::kernels OpenMP::OpenMP_CXX)
target_compile_definitions(tsynth_bench_optimisation PRIVATE TSYNTH_BUNDLED_DATA="${TSYNTH_BUNDLED_DATA}")
target_compile_options(tsynth_bench_optimisation PRIVATE ${TSYNTH_WARNING_FLAGS})
