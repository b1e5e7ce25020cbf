#!/usr/bin/env bash
# The project's own code (kernels, filters module, tsynth) built with AddressSanitizer, LeakSanitizer
# and UndefinedBehaviorSanitizer (TSYNTH_SANITIZE, -O1 -g) in "${TSYNTH_BUILD_DIR:-build}-asan", then
# run with CTest: the kernels' and the filters' GoogleTests, and the Python tests that only run tsynth
# (python.cli, python.bad_inputs, python.determinism). VTK, ParaView, GDAL and PoCL stay uninstrumented.
# Not here: the pvpython tests (pvpython cannot load an instrumented plugin), python.synth (about 11 min
# instrumented; its kernels are in the GoogleTests and bad_inputs runs full syntheses), python.memory
# (measures peaks), the examples, the benchmarks and the fuzz replays. Any report fails its test.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${TSYNTH_BUILD_DIR:-$root/build}-asan"
bash "$root/scripts/install-deps.sh"
# A folder configured by the earlier version of this script is a kernels-only tree: widened here.
if [ ! -f "$build/build.ninja" ] || grep -q '^TSYNTH_KERNELS_ONLY:BOOL=ON' "$build/CMakeCache.txt"; then
  # -O1 -g: readable stacks at a fraction of -O0's run time. Debian's python3 has numpy and GDAL.
  cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g" \
    -DTSYNTH_KERNELS_ONLY=OFF -DTSYNTH_SANITIZE=ON -DPython3_EXECUTABLE=/usr/bin/python3
fi
# Only what the tests below run: not the plugin, its Python module, the benchmarks or the fuzz replays.
targets=(tsynth tsynth_filter_tests tsynth_kernel_tests tsynth_distance_tests tsynth_hydrology_tests
  tsynth_matching_tests tsynth_merging_tests tsynth_optimisation_tests)
cmake --build "$build" -j "$(nproc)" --target "${targets[@]}"
tests='^(kernels|distance|hydrology|matching|merging|optimisation|filters)\.'
# The command line's tests, each tsynth run with the leak check. Their synth runs use OpenCL, and now
# and then LeakSanitizer's own tracer crashes at exit while PoCL's pthread device threads live
# ("Tracer caught signal 11: ... LeakSanitizer has encountered a fatal error", python.bad_inputs in one
# of two fresh-clone runs): such a test gets a second run. A real leak or sanitizer error is
# deterministic and fails both.
cli_tests='^python\.(cli|bad_inputs|determinism)$'

# Leaks are reported too (LeakSanitizer, part of ASan); use after return and initialisation order
# are checked as well. UBSan prints the stack of the first report, which stops the program.
export ASAN_OPTIONS="detect_leaks=1:detect_stack_use_after_return=1:check_initialization_order=1:strict_init_order=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# Leaks inside other projects' libraries, each listed with what leaks (none of the project's own);
# their tally is not printed, so the one-sentence checks of stderr still hold.
export LSAN_OPTIONS="suppressions=$root/Testing/lsan.supp:print_suppressions=0${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
# Tests whose timing an instrumented tsynth cannot meet skip themselves (Testing/Python/harness.py).
export TSYNTH_TEST_INSTRUMENTED=1
# Mesa unloads its GL driver when VTK closes the display; test_cli's 3D render preloads it so that
# LeakSanitizer still sees the driver's globals at exit (gl_preload_environment in harness.py).
gl_driver="/usr/lib/$(gcc -print-multiarch)/dri/swrast_dri.so"
if [ -f "$gl_driver" ]; then
  export TSYNTH_TEST_GL_PRELOAD="$gl_driver"
fi
cd "$build"
# The OpenCL GoogleTests run without the leak check: in this tree LeakSanitizer's tracer crashes at
# exit while PoCL's pthread device threads live ("Tracer caught signal 11", every OpenCL test, in both
# runs of a fresh clone), and PoCL's basic device leaks its own buffers. ASan and UBSan still check them.
opencl='^matching\.OpenCL\.'
status=0
ctest -j "$(nproc)" --output-on-failure --timeout 900 -R "$tests" -E "$opencl" || status=$?
ctest -j "$(nproc)" --output-on-failure --timeout 900 -R "$cli_tests" --repeat until-pass:2 || status=$?
ASAN_OPTIONS="${ASAN_OPTIONS/detect_leaks=1/detect_leaks=0}" \
  ctest -j "$(nproc)" --output-on-failure --timeout 900 -R "$opencl" || status=$?
exit "$status"
