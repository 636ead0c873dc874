// Functions that process many lanes at once (a crowd's legs or controllers) are compiled for
// several x86-64 levels and the widest one the machine has is chosen when the library loads
// (GCC function multi-versioning). The arithmetic is the same IEEE operations in every version,
// with no fused multiply-add (the project's -ffp-contract=off), so every version gives the same
// bits; only the width of the vectors differs.
#pragma once

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define FUZZYGAIT_VECTOR_TARGETS \
  __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define FUZZYGAIT_VECTOR_TARGETS
#endif
