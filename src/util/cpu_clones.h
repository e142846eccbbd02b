// TSRIR_AVX2_CLONES: a function compiled twice, for AVX2 and for the baseline x86-64, the one to run
// chosen once at load time by the CPU (GCC/Clang target_clones, an ifunc: x86-64 Linux with glibc).
// Elsewhere (aarch64, macOS, other compilers) it is nothing and the function is compiled once for
// the target: the attribute names x86 features, which other targets reject. Both clones perform
// the same operations in the same order without FMA (the avx2 target does not enable it), so they
// give the same values to the bit (tests/dsp, tests/metrics).
#pragma once

#if defined(__x86_64__) && defined(__linux__) && (defined(__GNUC__) || defined(__clang__))
#define TSRIR_AVX2_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define TSRIR_AVX2_CLONES
#endif
