// Membership functions of every term shape, written once and templated on the scalar type.
// Each expression keeps fuzzylite 6's operation order, so doubles give the same bits as
// fuzzylite, and dual numbers (automatic differentiation) flow through the same code.
// Parameters come in FLL order; `h` is the term's height.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

#include "fuzzygait/fuzzy/compare.hpp"

namespace fuzzygait::fuzzy::shapes {

using detail::is_nan;

template <class T>
T quiet_nan() {
  return T(std::numeric_limits<double>::quiet_NaN());
}

template <class T>
T bell(const T& x, const T& center, const T& width, const T& slope, const T& h) {
  using std::abs;
  using std::pow;
  if (is_nan(x)) return quiet_nan<T>();
  return h * (T(1.0) / (T(1.0) + pow(abs(T((x - center) / width)), T(2.0) * slope)));
}

template <class T>
T binary(const T& x, const T& start, const T& direction, const T& h) {
  if (is_nan(x)) return quiet_nan<T>();
  if (direction > start && is_ge(x, start)) return h * T(1.0);
  if (direction < start && is_le(x, start)) return h * T(1.0);
  return h * T(0.0);
}

template <class T>
T concave(const T& x, const T& inflection, const T& end, const T& h) {
  if (is_nan(x)) return quiet_nan<T>();
  if (is_le(inflection, end)) {
    if (is_lt(x, end)) return h * (end - inflection) / (T(2.0) * end - inflection - x);
  } else {
    if (is_gt(x, end)) return h * (inflection - end) / (inflection - T(2.0) * end + x);
  }
  return h * T(1.0);
}

template <class T>
T cosine(const T& x, const T& center, const T& width, const T& h) {
  using std::atan;
  using std::cos;
  if (is_nan(x)) return quiet_nan<T>();
  if (is_lt(x, T(center - T(0.5) * width)) || is_gt(x, T(center + T(0.5) * width))) {
    return h * T(0.0);
  }
  const double pi = 4.0 * std::atan(1.0);
  return h * (T(0.5) * (T(1.0) + cos(T(2.0) / width * T(pi) * (x - center))));
}

// xy holds sorted points x0 y0 x1 y1 ...; n is the number of points (>= 1).
template <class T>
T discrete(const T& x, const T* xy, std::size_t n, const T& h) {
  if (is_nan(x)) return quiet_nan<T>();
  if (is_le(x, xy[0])) return h * xy[1];
  if (is_ge(x, xy[2 * (n - 1)])) return h * xy[2 * (n - 1) + 1];
  // std::lower_bound / std::upper_bound over the x coordinates, as fuzzylite does.
  std::size_t lower = 0;
  std::size_t count = n;
  while (count > 0) {
    const std::size_t step = count / 2;
    if (xy[2 * (lower + step)] < x) {
      lower += step + 1;
      count -= step + 1;
    } else {
      count = step;
    }
  }
  if (is_eq(x, xy[2 * lower])) return h * xy[2 * lower + 1];
  std::size_t upper = 0;
  count = n;
  while (count > 0) {
    const std::size_t step = count / 2;
    if (!(x < xy[2 * (upper + step)])) {
      upper += step + 1;
      count -= step + 1;
    } else {
      count = step;
    }
  }
  --lower;
  const T& x0 = xy[2 * lower];
  const T& y0 = xy[2 * lower + 1];
  const T& x1 = xy[2 * upper];
  const T& y1 = xy[2 * upper + 1];
  return h * ((y1 - y0) / (x1 - x0) * (x - x0) + y0);
}

template <class T>
T gaussian(const T& x, const T& mean, const T& sd, const T& h) {
  using std::exp;
  if (is_nan(x)) return quiet_nan<T>();
  return h * exp((-(x - mean) * (x - mean)) / (T(2.0) * sd * sd));
}

template <class T>
T gaussian_product(const T& x, const T& mean_a, const T& sd_a, const T& mean_b, const T& sd_b,
                   const T& h) {
  using std::exp;
  if (is_nan(x)) return quiet_nan<T>();
  T a(1.0);
  T b(1.0);
  if (is_lt(x, mean_a)) a = exp((-(x - mean_a) * (x - mean_a)) / (T(2.0) * sd_a * sd_a));
  if (is_gt(x, mean_b)) b = exp((-(x - mean_b) * (x - mean_b)) / (T(2.0) * sd_b * sd_b));
  return h * a * b;
}

template <class T>
T pi_shape(const T& x, const T& bottom_left, const T& top_left, const T& top_right,
           const T& bottom_right, const T& h) {
  using std::pow;
  if (is_nan(x)) return quiet_nan<T>();
  T s;
  if (is_le(x, bottom_left)) {
    s = T(0.0);
  } else if (is_le(x, T(T(0.5) * (bottom_left + top_left)))) {
    s = T(2.0) * pow(T((x - bottom_left) / (top_left - bottom_left)), 2.0);
  } else if (is_lt(x, top_left)) {
    s = T(1.0) - T(2.0) * pow(T((x - top_left) / (top_left - bottom_left)), 2.0);
  } else {
    s = T(1.0);
  }
  T z;
  if (is_le(x, top_right)) {
    z = T(1.0);
  } else if (is_le(x, T(T(0.5) * (top_right + bottom_right)))) {
    z = T(1.0) - T(2.0) * pow(T((x - top_right) / (bottom_right - top_right)), 2.0);
  } else if (is_lt(x, bottom_right)) {
    z = T(2.0) * pow(T((x - bottom_right) / (bottom_right - top_right)), 2.0);
  } else {
    z = T(0.0);
  }
  return h * s * z;
}

template <class T>
T ramp(const T& x, const T& start, const T& end, const T& h) {
  if (is_nan(x)) return quiet_nan<T>();
  if (is_eq(start, end)) return h * T(0.0);
  if (is_lt(start, end)) {
    if (is_le(x, start)) return h * T(0.0);
    if (is_ge(x, end)) return h * T(1.0);
    return h * (x - start) / (end - start);
  }
  if (is_ge(x, start)) return h * T(0.0);
  if (is_le(x, end)) return h * T(1.0);
  return h * (start - x) / (start - end);
}

template <class T>
T rectangle(const T& x, const T& start, const T& end, const T& h) {
  if (is_nan(x)) return quiet_nan<T>();
  if (is_ge(x, start) && is_le(x, end)) return h * T(1.0);
  return h * T(0.0);
}

template <class T>
T s_shape(const T& x, const T& start, const T& end, const T& h) {
  using std::pow;
  if (is_nan(x)) return quiet_nan<T>();
  if (is_le(x, start)) return h * T(0.0);
  if (is_le(x, T(T(0.5) * (start + end)))) {
    return h * (T(2.0) * pow(T((x - start) / (end - start)), 2.0));
  }
  if (is_lt(x, end)) return h * (T(1.0) - T(2.0) * pow(T((x - end) / (end - start)), 2.0));
  return h * T(1.0);
}

template <class T>
T sigmoid(const T& x, const T& inflection, const T& slope, const T& h) {
  using std::exp;
  if (is_nan(x)) return quiet_nan<T>();
  return h * T(1.0) / (T(1.0) + exp(-slope * (x - inflection)));
}

template <class T>
T sigmoid_difference(const T& x, const T& left, const T& rising, const T& falling, const T& right,
                     const T& h) {
  using std::abs;
  using std::exp;
  if (is_nan(x)) return quiet_nan<T>();
  const T a = T(1.0) / (T(1.0) + exp(-rising * (x - left)));
  const T b = T(1.0) / (T(1.0) + exp(-falling * (x - right)));
  return h * abs(T(a - b));
}

template <class T>
T sigmoid_product(const T& x, const T& left, const T& rising, const T& falling, const T& right,
                  const T& h) {
  using std::exp;
  if (is_nan(x)) return quiet_nan<T>();
  const T a = T(1.0) + exp(-rising * (x - left));
  const T b = T(1.0) + exp(-falling * (x - right));
  return h * T(1.0) / (a * b);
}

template <class T>
T spike(const T& x, const T& center, const T& width, const T& h) {
  using std::abs;
  using std::exp;
  if (is_nan(x)) return quiet_nan<T>();
  return h * exp(-abs(T(T(10.0) / width * (x - center))));
}

template <class T>
T trapezoid(const T& x, const T& a, const T& b, const T& c, const T& d, const T& h) {
  if (is_nan(x)) return quiet_nan<T>();
  const double inf = std::numeric_limits<double>::infinity();
  if (is_lt(x, a) || is_gt(x, d)) return h * T(0.0);
  if (is_lt(x, b)) {
    if (a == T(-inf)) return h * T(1.0);
    return h * nan_min(T(1.0), T((x - a) / (b - a)));
  }
  if (is_le(x, c)) return h * T(1.0);
  if (is_lt(x, d)) {
    if (d == T(inf)) return h * T(1.0);
    return h * (d - x) / (d - c);
  }
  if (d == T(inf)) return h * T(1.0);
  return h * T(0.0);
}

template <class T>
T triangle(const T& x, const T& a, const T& b, const T& c, const T& h) {
  if (is_nan(x)) return quiet_nan<T>();
  const double inf = std::numeric_limits<double>::infinity();
  if (is_lt(x, a) || is_gt(x, c)) return h * T(0.0);
  if (is_eq(x, b)) return h * T(1.0);
  if (is_lt(x, b)) {
    if (a == T(-inf)) return h * T(1.0);
    return h * (x - a) / (b - a);
  }
  if (c == T(inf)) return h * T(1.0);
  return h * (c - x) / (c - b);
}

template <class T>
T z_shape(const T& x, const T& start, const T& end, const T& h) {
  using std::pow;
  if (is_nan(x)) return quiet_nan<T>();
  if (is_le(x, start)) return h * T(1.0);
  if (is_le(x, T(T(0.5) * (start + end)))) {
    return h * (T(1.0) - T(2.0) * pow(T((x - start) / (end - start)), 2.0));
  }
  if (is_lt(x, end)) return h * (T(2.0) * pow(T((x - end) / (end - start)), 2.0));
  return h * T(0.0);
}

// Tsukamoto inverses of the monotonic shapes: the output value z at which the term's
// membership equals the activation degree w (fuzzylite's Term::tsukamoto).
template <class T>
T ramp_inverse(const T& w, const T& start, const T& end) {
  return (end - start) / T(1.0 - 0.0) * (w - T(0.0)) + start;
}

template <class T>
T sigmoid_inverse(const T& w, const T& inflection, const T& slope, const T& minimum,
                  const T& maximum) {
  using std::log;
  if (is_eq(w, T(1.0))) return is_ge(slope, T(0.0)) ? maximum : minimum;
  if (is_eq(w, T(0.0))) return is_ge(slope, T(0.0)) ? minimum : maximum;
  return inflection + (log(T(1.0) / w - T(1.0)) / -slope);
}

template <class T>
T s_shape_inverse(const T& w, const T& start, const T& end, const T& h) {
  using std::abs;
  using std::sqrt;
  const T difference = end - start;
  const T a = start + sqrt(T(0.5) * w * difference * difference);
  const T b = end + sqrt(T(-0.5) * (w - T(1.0)) * difference * difference);
  if (abs(T(w - s_shape(a, start, end, h))) < abs(T(w - s_shape(b, start, end, h)))) return a;
  return b;
}

template <class T>
T z_shape_inverse(const T& w, const T& start, const T& end, const T& h) {
  using std::abs;
  using std::sqrt;
  const T difference = end - start;
  const T a = start + sqrt(T(-0.5) * (w - T(1.0)) * difference * difference);
  const T b = end + sqrt(T(0.5) * w * difference * difference);
  if (abs(T(w - z_shape(a, start, end, h))) < abs(T(w - z_shape(b, start, end, h)))) return a;
  return b;
}

template <class T>
T concave_inverse(const T& w, const T& inflection, const T& end, const T& h) {
  // fuzzylite evaluates the membership at the activation degree here; kept for equality.
  return (inflection - end) / concave(w, inflection, end, h) + T(2.0) * end - inflection;
}

}  // namespace fuzzygait::fuzzy::shapes
