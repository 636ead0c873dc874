#include "offline/learn/set_edit.hpp"

#include <cmath>
#include <utility>

namespace fuzzygait::learn::detail {

void move_knot(fuzzy::InputVariable& input, std::size_t index, double at) {
  input.terms.at(index).parameters[1] = at;
  input.terms.at(index - 1).parameters[2] = at;
  input.terms.at(index + 1).parameters[0] = at;
}

gait::ControllerSet with_engines(const gait::ControllerSet& base,
                                 std::vector<fuzzy::Engine>& engines, double inertia) {
  gait::ControllerSet set = base;
  set.inertia = inertia;
  for (std::size_t s = 0; s < engines.size(); ++s) {
    set.controllers[s] = gait::Controller(std::move(engines[s]), base.controllers[s].source());
  }
  return set;
}

double round_significant(double v, int digits) {
  if (v == 0.0 || !std::isfinite(v)) return v;
  const double magnitude =
      std::pow(10.0, digits - 1 - static_cast<int>(std::floor(std::log10(std::abs(v)))));
  return std::round(v * magnitude) / magnitude;
}

}  // namespace fuzzygait::learn::detail
