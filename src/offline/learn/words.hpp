// What a controller's output words promise ("stay" near zero, "flex" positive, "fast" faster than
// the plain word, "slow" below "fast"...), as separate promises whose breaches can be priced one
// by one: summed by learn::word_penalty for the tuner, and as residuals of the fits. Templated on
// the scalar for the fits' dual numbers. Internal to the offline library.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include "fuzzygait/fuzzy/engine.hpp"

namespace fuzzygait::learn::detail {

struct WordPromise {
  enum class Kind {
    NearZero,  // |term| within one unit
    Positive,  // term >= 0
    Negative,  // term <= 0
    Faster,    // |term| >= |other|  ("flex_fast" and "flex")
    Slower,    // |term| <= |other|  ("flex_slow" and "flex")
    NotAbove,  // term <= other      ("slow" and "fast")
  };
  Kind kind;
  std::size_t term;
  std::size_t other = 0;
};

// The promises of an output's Constant terms, in the order learn::word_penalty sums them.
std::vector<WordPromise> word_promises(const fuzzy::OutputVariable& output);

// How far a promise is broken, in units of `unit` (0 when kept); values[t] is output term t's.
template <class T>
T broken_by(const WordPromise& p, const T* values, double unit) {
  using std::abs;
  auto over = [](const T& x) { return x > 0.0 ? x : T(0.0); };
  const T& v = values[p.term];
  switch (p.kind) {
    case WordPromise::Kind::NearZero:
      return over(T(abs(v) - unit)) / unit;
    case WordPromise::Kind::Positive:
      return over(T(-v)) / unit;
    case WordPromise::Kind::Negative:
      return over(v) / unit;
    case WordPromise::Kind::Faster:
      return over(T(abs(values[p.other]) - abs(v))) / unit;
    case WordPromise::Kind::Slower:
      return over(T(abs(v) - abs(values[p.other]))) / unit;
    case WordPromise::Kind::NotAbove:
      return over(T(v - values[p.other])) / unit;
  }
  return T(0.0);
}

// Moves values (values[t] is output term t's) as little as each promise needs until every one is
// kept: into [-unit, unit], to the right sign, as fast or as slow as the plain word, no higher
// than the other word. The promises are kept in a few passes (a value moved for one promise can
// break an earlier one only through another word, which the next pass settles).
void keep_promises(std::vector<double>& values, const std::vector<WordPromise>& promises,
                   double unit);

}  // namespace fuzzygait::learn::detail
