# TSYNTH_FUZZ=ON: the whole build is instrumented for libFuzzer (coverage) with
# AddressSanitizer and UndefinedBehaviorSanitizer, and Testing/Fuzz adds one
# libFuzzer binary per target (tsynth_fuzz_<target>, all of them: the
# tsynth_fuzzers target). Clang only; see Testing/Fuzz/README.md.
if (NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang" OR NOT CMAKE_C_COMPILER_ID MATCHES "Clang")
  message(FATAL_ERROR "TSYNTH_FUZZ=ON needs clang, which has libFuzzer; this is "
    "${CMAKE_CXX_COMPILER_ID}. Configure a separate build folder with "
    "-DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DTSYNTH_FUZZ=ON.")
endif ()

set(TSYNTH_SANITIZERS "address,undefined")
include(CheckCXXSourceCompiles)
set(CMAKE_REQUIRED_FLAGS "-fsanitize=fuzzer,${TSYNTH_SANITIZERS}")
check_cxx_source_compiles([[
#include <cstddef>
#include <cstdint>
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t*, std::size_t) { return 0; }
]] TSYNTH_HAVE_LIBFUZZER)
unset(CMAKE_REQUIRED_FLAGS)
if (NOT TSYNTH_HAVE_LIBFUZZER)
  message(FATAL_ERROR "clang cannot link -fsanitize=fuzzer,${TSYNTH_SANITIZERS}: install "
    "clang's runtime libraries (Debian: apt-get install libclang-rt-14-dev).")
endif ()

# Every object gets coverage and the sanitizers; only the fuzz binaries link
# libFuzzer's main (-fsanitize=fuzzer in Testing/Fuzz). Undefined behaviour
# stops the run, so the fuzzer reports it as a crash.
add_compile_options("-fsanitize=fuzzer-no-link,${TSYNTH_SANITIZERS}"
  -fno-sanitize-recover=all -fno-omit-frame-pointer -g)
add_link_options("-fsanitize=${TSYNTH_SANITIZERS}")
