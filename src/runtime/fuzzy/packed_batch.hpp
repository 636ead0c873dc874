// PackedPartition's batch evaluation, a crowd's characters through one controller at once, and
// how this machine runs it: in the widest vectors it has (AVX-512F, AVX2), else one call at a time.
// Internal to fuzzygait (not installed).
#pragma once

#include <cstddef>

#include "fuzzygait/fuzzy/partition.hpp"
#include "runtime/fuzzy/packed_lanes.hpp"

namespace fuzzygait::fuzzy::detail {

// The lanes of the widest vector the batch may use.
inline constexpr std::size_t kMaxBatchVectorLanes = 8;

// The lanes of the widest vector the batch uses on this machine: 8 (AVX-512F), 4 (AVX2) or 1 (no
// vectors, one call at a time).
std::size_t batch_vector_lanes();

// How many lanes to give the batch for n: n rounded up to a multiple of batch_vector_lanes() (the
// last few lanes would otherwise go one by one, at more cost than a padded vector whose extra
// outputs the caller leaves unread). A caller may pass this only where its arrays have room for
// it.
inline std::size_t padded_lanes(std::size_t n) {
  const std::size_t width = batch_vector_lanes();
  return (n + width - 1) / width * width;
}

// out[i] = p.evaluate(x0[i], x1[i]) for i < n, bit for bit: whole vectors in lanes (the widest
// first), the rest (and all of it without vectors) by the scalar evaluate(). x1 is not read for a
// one-input controller (it may then be null).
void evaluate_batch(const PackedPartition& p, const double* x0, const double* x1, double* out,
                    std::size_t n);

// The packed data as the lane kernel reads it.
struct PackedPartitionAccess {
  static PackedView view(const PackedPartition& p);
};

}  // namespace fuzzygait::fuzzy::detail
