// Three-dimensional vectors and unit quaternions for posing a body: the few operations the body
// and path parts need, inline and free of allocation. Right-handed; metres; radians.
#pragma once

#include <cmath>

namespace fuzzygait::body {

struct Vec3 {
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;
};

constexpr Vec3 operator+(Vec3 a, Vec3 b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
constexpr Vec3 operator-(Vec3 a, Vec3 b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
constexpr Vec3 operator-(Vec3 a) {
  return {-a.x, -a.y, -a.z};
}
constexpr Vec3 operator*(double s, Vec3 a) {
  return {s * a.x, s * a.y, s * a.z};
}
constexpr double dot(Vec3 a, Vec3 b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
constexpr Vec3 cross(Vec3 a, Vec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double length(Vec3 a) {
  return std::sqrt(dot(a, a));
}
// `a` scaled to length 1; the zero vector stays zero.
inline Vec3 normalized(Vec3 a) {
  const double n = length(a);
  return n > 0.0 ? (1.0 / n) * a : Vec3{};
}

// A rotation as a unit quaternion w + xi + yj + zk; the default is no rotation.
struct Quat {
  double w = 1.0;
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;
};

// Rotation by `angle` about the unit `axis` (right-handed).
inline Quat axis_angle(Vec3 axis, double angle) {
  const double s = std::sin(0.5 * angle);
  return {std::cos(0.5 * angle), s * axis.x, s * axis.y, s * axis.z};
}
constexpr Quat operator*(Quat a, Quat b) {  // b first, then a
  return {
      a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z, a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
      a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x, a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w};
}
constexpr Quat conjugate(Quat q) {  // the inverse of a unit quaternion
  return {q.w, -q.x, -q.y, -q.z};
}
inline Quat normalized(Quat q) {
  const double n = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  return n > 0.0 ? Quat{q.w / n, q.x / n, q.y / n, q.z / n} : Quat{};
}
constexpr Vec3 rotate(Quat q, Vec3 v) {
  const Vec3 u{q.x, q.y, q.z};
  const Vec3 t = 2.0 * cross(u, v);
  return v + q.w * t + cross(u, t);
}

// The rotation whose columns are the orthonormal, right-handed axes x, y, z (the images of the
// unit axes). Shepperd's method: stable for every rotation.
Quat from_axes(Vec3 x, Vec3 y, Vec3 z);

}  // namespace fuzzygait::body
