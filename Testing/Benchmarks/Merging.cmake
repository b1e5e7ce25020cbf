# Merging benchmark: our grid max-flow against Kolmogorov's maxflow library and
# Boost's boykov_kolmogorov_max_flow, Poisson solves and patch blending.
pkg_check_modules(MAXFLOW REQUIRED IMPORTED_TARGET maxflow)
add_executable(tsynth_bench_merging BenchMerging.cxx)
target_link_libraries(tsynth_bench_merging PRIVATE
  tsynth::kernels Boost::headers PkgConfig::MAXFLOW)
target_compile_definitions(tsynth_bench_merging PRIVATE TSYNTH_BUNDLED_DATA="${TSYNTH_BUNDLED_DATA}")
target_compile_options(tsynth_bench_merging PRIVATE ${TSYNTH_WARNING_FLAGS})
