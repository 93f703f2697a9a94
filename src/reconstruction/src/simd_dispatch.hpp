#pragma once
// BINPICK_SIMD_PASS marks a hot loop function to be compiled twice on x86-64 with GCC: for the
// SSE2 baseline and for AVX2 + FMA (x86-64-v3); the loader picks by the CPU, so one binary runs
// everywhere and uses eight floats (sixteen 16-bit integers) per instruction where it can. FMA
// rounds differently: float results may differ between such CPUs in their last bits (never
// between thread counts on one machine). Not under ThreadSanitizer: the loader runs the clones'
// resolver before TSan's runtime is up, and the instrumented resolver crashes the program.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(__SANITIZE_THREAD__)
#define BINPICK_SIMD_PASS __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define BINPICK_SIMD_PASS
#endif
