// Writing learnt values back into a controller set's engines, shared by the tuner's parameters
// and the network's weights. Internal to the offline library.
#pragma once

#include <cstddef>
#include <vector>

#include "fuzzygait/fuzzy/engine.hpp"
#include "fuzzygait/gait/controllers.hpp"

namespace fuzzygait::learn::detail {

// Moves interior knot `index` (1 to terms - 2) of a strong triangular partition to `at`: the peak
// of its term and the feet of its neighbours.
void move_knot(fuzzy::InputVariable& input, std::size_t index, double at);

// `base` with its slots' engines replaced by `engines` (one per slot, in slot order, moved from)
// and its inertia by `inertia`; each engine is compiled anew (gait::Controller), which throws
// std::invalid_argument naming the base's file for one that does not fit.
gait::ControllerSet with_engines(const gait::ControllerSet& base,
                                 std::vector<fuzzy::Engine>& engines, double inertia);

// v rounded to `digits` significant digits (0, NaN and infinities as they are).
double round_significant(double v, int digits);

}  // namespace fuzzygait::learn::detail
