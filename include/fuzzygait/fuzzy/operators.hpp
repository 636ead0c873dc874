// The fuzzy operators of the FLL language: T-norms (conjunction, implication), S-norms
// (disjunction, aggregation) and hedges, with fuzzylite 6's exact formulas. Templated on the
// scalar so that automatic differentiation flows through them.
#pragma once

#include <cmath>
#include <cstdint>
#include <optional>
#include <string_view>

#include "fuzzygait/fuzzy/compare.hpp"

namespace fuzzygait::fuzzy {

enum class TNorm : std::uint8_t {
  None,
  AlgebraicProduct,
  BoundedDifference,
  DrasticProduct,
  EinsteinProduct,
  HamacherProduct,
  Minimum,
  NilpotentMinimum,
};

enum class SNorm : std::uint8_t {
  None,
  AlgebraicSum,
  BoundedSum,
  DrasticSum,
  EinsteinSum,
  HamacherSum,
  Maximum,
  NilpotentMaximum,
  NormalizedSum,
  UnboundedSum,
};

enum class Hedge : std::uint8_t { Any, Extremely, Not, Seldom, Somewhat, Very };

// FLL names ("none" for None) and their inverse; nullopt for an unknown name.
std::string_view name(TNorm norm);
std::string_view name(SNorm norm);
std::string_view name(Hedge hedge);
std::optional<TNorm> tnorm_from_name(std::string_view text);
std::optional<SNorm> snorm_from_name(std::string_view text);
std::optional<Hedge> hedge_from_name(std::string_view text);

template <class T>
T apply(TNorm norm, const T& a, const T& b) {
  switch (norm) {
    case TNorm::AlgebraicProduct:
      return a * b;
    case TNorm::BoundedDifference:
      return nan_max(T(0.0), T(a + b - T(1.0)));
    case TNorm::DrasticProduct:
      return is_eq(nan_max(a, b), T(1.0)) ? nan_min(a, b) : T(0.0);
    case TNorm::EinsteinProduct:
      return (a * b) / (T(2.0) - (a + b - a * b));
    case TNorm::HamacherProduct:
      return is_eq(T(a + b), T(0.0)) ? T(0.0) : (a * b) / (a + b - a * b);
    case TNorm::Minimum:
      return nan_min(a, b);
    case TNorm::NilpotentMinimum:
      return is_gt(T(a + b), T(1.0)) ? nan_min(a, b) : T(0.0);
    case TNorm::None:
      break;
  }
  return T(std::nan(""));
}

template <class T>
T apply(SNorm norm, const T& a, const T& b) {
  switch (norm) {
    case SNorm::AlgebraicSum:
      return a + b - (a * b);
    case SNorm::BoundedSum:
      return nan_min(T(1.0), T(a + b));
    case SNorm::DrasticSum:
      return is_eq(nan_min(a, b), T(0.0)) ? nan_max(a, b) : T(1.0);
    case SNorm::EinsteinSum:
      return (a + b) / (T(1.0) + a * b);
    case SNorm::HamacherSum:
      return is_eq(T(a * b), T(1.0)) ? T(1.0) : (a + b - T(2.0) * a * b) / (T(1.0) - a * b);
    case SNorm::Maximum:
      return nan_max(a, b);
    case SNorm::NilpotentMaximum:
      return is_lt(T(a + b), T(1.0)) ? nan_max(a, b) : T(1.0);
    case SNorm::NormalizedSum:
      return (a + b) / nan_max(T(1.0), T(a + b));
    case SNorm::UnboundedSum:
      return a + b;
    case SNorm::None:
      break;
  }
  return T(std::nan(""));
}

template <class T>
T apply(Hedge hedge, const T& x) {
  using std::sqrt;
  switch (hedge) {
    case Hedge::Any:
      return T(1.0);
    case Hedge::Extremely:
      return is_le(x, T(0.5)) ? T(2.0) * x * x : T(1.0) - T(2.0) * (T(1.0) - x) * (T(1.0) - x);
    case Hedge::Not:
      return T(1.0) - x;
    case Hedge::Seldom:
      return is_le(x, T(0.5)) ? sqrt(T(0.5) * x) : T(1.0) - sqrt(T(0.5) * (T(1.0) - x));
    case Hedge::Somewhat:
      return sqrt(x);
    case Hedge::Very:
      return x * x;
  }
  return T(std::nan(""));
}

}  // namespace fuzzygait::fuzzy
