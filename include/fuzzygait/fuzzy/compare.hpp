// Tolerant comparisons and NaN-aware min/max with the exact semantics of fuzzylite 6, so that
// every branch a membership function or a defuzzifier takes is the one fuzzylite takes, and the
// exact equality the value types' operator== use.
// Templated on the scalar so that automatic differentiation (dual numbers, Ceres Jets) flows
// through the same code.
#pragma once

#include <cmath>

namespace fuzzygait::fuzzy {

// Two values closer than this are equal (fuzzylite's default `macheps`).
inline constexpr double kTolerance = 1e-6;

namespace detail {
template <class T>
bool is_nan(const T& x) {
  return !(x == x);
}
template <class T>
T abs_value(const T& x) {
  using std::abs;
  return abs(x);
}
}  // namespace detail

template <class T>
bool is_eq(const T& a, const T& b) {
  return a == b || detail::abs_value(T(a - b)) < T(kTolerance) ||
         (detail::is_nan(a) && detail::is_nan(b));
}
template <class T>
bool is_lt(const T& a, const T& b) {
  return !is_eq(a, b) && a < b;
}
template <class T>
bool is_le(const T& a, const T& b) {
  return is_eq(a, b) || a < b;
}
template <class T>
bool is_gt(const T& a, const T& b) {
  return !is_eq(a, b) && a > b;
}
template <class T>
bool is_ge(const T& a, const T& b) {
  return is_eq(a, b) || a > b;
}

// Exactly equal, or both NaN (no tolerance): the equality of terms, variables and rules, for
// which a NaN parameter equals itself.
template <class T>
bool is_same_value(const T& a, const T& b) {
  return a == b || (detail::is_nan(a) && detail::is_nan(b));
}

// min/max that ignore a NaN operand (fuzzylite's Op::min / Op::max).
template <class T>
T nan_min(const T& a, const T& b) {
  if (detail::is_nan(a)) return b;
  if (detail::is_nan(b)) return a;
  return a < b ? a : b;
}
template <class T>
T nan_max(const T& a, const T& b) {
  if (detail::is_nan(a)) return b;
  if (detail::is_nan(b)) return a;
  return a > b ? a : b;
}

}  // namespace fuzzygait::fuzzy
