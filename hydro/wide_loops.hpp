#pragma once
// The per-cell loops of the hydro step, compiled three times where the compiler can: for the
// baseline x86-64 (SSE2, two doubles per instruction), for AVX2 (four) and for AVX-512F (eight),
// the widest the CPU has chosen when the program loads (GCC's target_clones, an ifunc resolver
// per function). The results are bitwise the same either way: the loops compute each element with
// the same IEEE operations in the same order whatever the vector width (no reassociation), and
// the hydro is compiled with -ffp-contract=off, so that the AVX-512 copy, whose ISA brings fused
// multiply-add, does not fuse a product and a sum into one rounding (hydro/CMakeLists.txt).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define GRANVV_WIDE_LOOPS __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define GRANVV_WIDE_LOOPS
#endif
