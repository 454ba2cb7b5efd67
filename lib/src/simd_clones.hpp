#pragma once
// Internal: function multi-versioning of the hot loops (GCC/Clang target_clones on x86-64; the
// loader picks the clone the CPU supports). SIGMATAU_NO_CLONES turns it off.
//
// SIGMATAU_SIMD_CLONES: AVX-512, AVX2 and the baseline. The AVX-512 clone may fuse a
// multiplication and an addition (one rounding instead of two), so a file using it turns
// floating-point contraction off before its includes (`#pragma STDC FP_CONTRACT OFF` for Clang,
// `#pragma GCC optimize("fp-contract=off")` for GCC): every clone then gives the same bits.
// SIGMATAU_AVX2_CLONES: AVX2 and the baseline, neither of which has FMA.

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && !defined(SIGMATAU_NO_CLONES)
#define SIGMATAU_SIMD_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#define SIGMATAU_AVX2_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define SIGMATAU_SIMD_CLONES
#define SIGMATAU_AVX2_CLONES
#endif
