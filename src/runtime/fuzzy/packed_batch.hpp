// PackedPartition's batch evaluation, a crowd's characters through one controller at once, and
// how this machine runs it: in AVX2 vectors where simd::has_avx2(), else one call at a time.
// Internal to fuzzygait (not installed).
#pragma once

#include <cstddef>

#include "fuzzygait/fuzzy/partition.hpp"
#include "runtime/fuzzy/packed_lanes.hpp"

namespace fuzzygait::fuzzy::detail {

// The lanes of one vector of the batch.
inline constexpr std::size_t kBatchVectorLanes = 4;

// Whether the batch runs in vector lanes on this machine.
bool batch_in_vectors();

// How many lanes to give the batch for n: with vectors, n rounded up to a multiple of
// kBatchVectorLanes (the last few lanes would otherwise go one by one, at more cost than a padded
// vector whose extra outputs the caller leaves unread), else n. A caller may pass this only where
// its arrays have room for it.
inline std::size_t padded_lanes(std::size_t n) {
  return batch_in_vectors() ? (n + kBatchVectorLanes - 1) / kBatchVectorLanes * kBatchVectorLanes
                            : n;
}

// out[i] = p.evaluate(x0[i], x1[i]) for i < n, bit for bit: whole vectors in lanes, the rest (and
// all of it without vectors) by the scalar evaluate(). x1 is not read for a one-input controller
// (it may then be null).
void evaluate_batch(const PackedPartition& p, const double* x0, const double* x1, double* out,
                    std::size_t n);

// The packed data as the lane kernel reads it.
struct PackedPartitionAccess {
  static PackedView view(const PackedPartition& p);
};

}  // namespace fuzzygait::fuzzy::detail
