// TSRIR_AVX2_CLONES: a function compiled twice, for AVX2 and for the baseline x86-64, the one to run
// chosen once at load time by the CPU (GCC/Clang target_clones, an ifunc: x86-64 Linux with glibc).
// Elsewhere (aarch64, macOS, other compilers) it is nothing and the function is compiled once for
// the target: the attribute names x86 features, which other targets reject. Both clones perform
// the same operations in the same order without FMA (the avx2 target does not enable it), so they
// give the same values to the bit (tests/dsp, tests/metrics).
#pragma once

#if defined(__x86_64__) && defined(__linux__) && (defined(__GNUC__) || defined(__clang__))
#define TSRIR_AVX2_CLONES __attribute__((target_clones("avx2", "default")))
// TSRIR_WIDE_CLONES adds an AVX-512F clone (eight doubles a vector) to those two. AVX-512F has
// fused multiply-adds of its own, and GCC would fuse a * b + c there (rounding once instead of
// twice): fp-contract=off keeps every clone's values the same to the bit.
// GCC only (Clang has no optimize attribute): elsewhere it is TSRIR_AVX2_CLONES. The same holds for
// TSRIR_AVX512_TARGET, a function compiled for AVX-512F alone (its caller checks the CPU).
#if defined(__GNUC__) && !defined(__clang__)
#define TSRIR_WIDE_CLONES __attribute__((target_clones("avx512f", "avx2", "default"), optimize("fp-contract=off")))
#define TSRIR_AVX512_TARGET __attribute__((target("avx512f"), optimize("fp-contract=off")))
#define TSRIR_HAVE_AVX512_TARGET 1
#else
#define TSRIR_WIDE_CLONES TSRIR_AVX2_CLONES
#define TSRIR_HAVE_AVX512_TARGET 0
#endif
#else
#define TSRIR_AVX2_CLONES
#define TSRIR_WIDE_CLONES
#define TSRIR_HAVE_AVX512_TARGET 0
#endif
