#pragma once
// The per-cell loops of the hydro step, compiled twice where the compiler can: for the baseline
// x86-64 (SSE2, two doubles per instruction) and for AVX2 (four), the second chosen when the
// program loads on a CPU that has it (GCC's target_clones, an ifunc resolver per function). The
// results are bitwise the same either way: the loops compute each element with the same IEEE
// operations in the same order whatever the vector width (no reassociation, and AVX2 brings no
// fused multiply-add).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define GRANVV_WIDE_LOOPS __attribute__((target_clones("avx2", "default")))
#else
#define GRANVV_WIDE_LOOPS
#endif
