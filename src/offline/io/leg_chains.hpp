// The joints of a BVH skeleton that make its two legs, found by a mapping or the built-in names
// (io/mocap.hpp). Internal to the offline library.
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "fuzzygait/io/mocap.hpp"

namespace fuzzygait::io::detail {

// Indices into BvhClip::joints.
struct LegChain {
  int hip = -1;
  int knee = -1;
  int ankle = -1;
  int toe = -1;  // the toe base: a joint, or the ankle's End Site for a foot without toes
  int tip = -1;  // the toe base's first child; -1 when it has none (no toe angle)
};

struct SkeletonLegs {
  int root = 0;
  std::array<LegChain, 2> legs;  // rig::Side order
  std::vector<std::string> notes;
};

// Throws MocapError naming `source` (and the mapping's file and field) when a joint is missing,
// a joint does not lie below the one before it in its chain, or the legs share a joint.
SkeletonLegs find_legs(const BvhClip& bvh, std::string_view source, const LegMapping* mapping);

}  // namespace fuzzygait::io::detail
