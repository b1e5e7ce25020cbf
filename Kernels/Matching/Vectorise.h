// Hot loops built for several instruction sets, the best picked at load time:
// the library is built for baseline x86-64 (SSE2), while PoCL compiles the
// OpenCL kernels for the host (AVX-512 here), so the CPU backend would
// otherwise do 4 lanes at a time where OpenCL does 16. Results are the same
// bits in every clone: the sums keep their order and contraction to FMA is off
// (-ffp-contract=off on the kernels library).
#pragma once

#if defined(__GNUC__) && defined(__x86_64__) && !defined(__clang__)
#define TSYNTH_VECTOR_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define TSYNTH_VECTOR_CLONES
#endif

// For the helpers of a cloned function: built into each clone, with its
// instruction set, rather than once for the baseline and called.
#if defined(__GNUC__)
#define TSYNTH_INLINE_IN_CLONES __attribute__((always_inline)) inline
#else
#define TSYNTH_INLINE_IN_CLONES inline
#endif
