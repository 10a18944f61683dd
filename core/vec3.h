#pragma once
// Small 3-vector arithmetic on std::array<T, 3> triples (Vec3f, Vec3d), for the host code that
// needs it (trimesh2's one `vec` serves its whole curvature file the same way). Each operation is
// written component by component in the order shown, so a file that used a private copy gets the
// same results to the bit. Bring the names in with using-declarations (`using vec3::dot;`).
// Tested in tests/core/test_vec3.cpp.
#include <array>
#include <cmath>
#include <type_traits>

#include "core/mesh.h"

namespace isocurv {

using Vec3d = std::array<double, 3>;

namespace vec3 {

template <class T>
std::array<T, 3> add(const std::array<T, 3>& a, const std::array<T, 3>& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
template <class T>
std::array<T, 3> sub(const std::array<T, 3>& a, const std::array<T, 3>& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
/// a times s (s converted to the triple's type: scale(v, 2) is fine).
template <class T>
std::array<T, 3> scale(const std::array<T, 3>& a, typename std::common_type<T>::type s) {
  return {a[0] * s, a[1] * s, a[2] * s};
}
/// a0 b0 + a1 b1 + a2 b2, left to right.
template <class T>
T dot(const std::array<T, 3>& a, const std::array<T, 3>& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
/// Right-handed: cross({1, 0, 0}, {0, 1, 0}) = {0, 0, 1}.
template <class T>
std::array<T, 3> cross(const std::array<T, 3>& a, const std::array<T, 3>& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
/// The Euclidean length, sqrt(dot(a, a)).
template <class T>
T norm(const std::array<T, 3>& a) {
  return std::sqrt(dot(a, a));
}
/// a divided by its length; a itself when the length is zero or not a number.
template <class T>
std::array<T, 3> normalized(const std::array<T, 3>& a) {
  const T n = norm(a);
  return n > 0 ? std::array<T, 3>{a[0] / n, a[1] / n, a[2] / n} : a;
}
/// A float triple widened to double.
inline Vec3d to_double(const Vec3f& v) { return {v[0], v[1], v[2]}; }
/// The dot product of two float triples, computed in double.
inline double wide_dot(const Vec3f& a, const Vec3f& b) { return dot(to_double(a), to_double(b)); }

}  // namespace vec3
}  // namespace isocurv
