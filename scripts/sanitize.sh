#!/usr/bin/env bash
# The kernels and their GoogleTests built with AddressSanitizer and UndefinedBehaviorSanitizer
# (TSYNTH_KERNELS_ONLY, TSYNTH_SANITIZE) in "${TSYNTH_BUILD_DIR:-build}-asan", then run with CTest.
# Any report fails its test. No ParaView is needed for this tree.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${TSYNTH_BUILD_DIR:-$root/build}-asan"
bash "$root/scripts/install-deps.sh"
if [ ! -f "$build/build.ninja" ]; then
  # -O1 -g: readable stacks at a fraction of -O0's run time.
  cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g" \
    -DTSYNTH_KERNELS_ONLY=ON -DTSYNTH_SANITIZE=ON
fi
cmake --build "$build" -j "$(nproc)"
# Leaks are reported too (LeakSanitizer, part of ASan); use after return and initialisation order
# are checked as well. UBSan prints the stack of the first report, which stops the program.
export ASAN_OPTIONS="detect_leaks=1:detect_stack_use_after_return=1:check_initialization_order=1:strict_init_order=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
cd "$build"
ctest -j "$(nproc)" --output-on-failure --timeout 900
