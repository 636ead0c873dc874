// A range a measure should stay in, for the tuners' costs.
#pragma once

namespace fuzzygait::learn {

// NaN-free bounds; use +-infinity for one side.
struct Range {
  double min;
  double max;
};

}  // namespace fuzzygait::learn
