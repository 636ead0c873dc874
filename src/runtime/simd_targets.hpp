// Batches over many lanes (a crowd's legs' sines and cosines) are compiled for several x86-64
// levels, and the widest the machine has is chosen when the library loads (GCC's function
// multi-versioning, which needs ELF and glibc's ifunc). The arithmetic is the same IEEE operations
// in every version, with no fused multiply-add (the project's -ffp-contract=off), so every version
// gives the same bits; only the vectors' width differs. Elsewhere (clang, other systems) the one
// baseline version.
#pragma once

#include <cstddef>  // defines __GLIBC__ through the C library's headers

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && defined(__ELF__) && \
    defined(__GLIBC__)
#define FUZZYGAIT_VECTOR_TARGETS \
  __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define FUZZYGAIT_VECTOR_TARGETS
#endif
