#pragma once
// Quantities derived from the principal curvatures at one point: shape index, curvedness and the
// curvature-based ambient occlusion. Templates so the double reference and float code agree; the
// OpenCL kernels (curvature_math.cl) repeat these formulas.
// Tested in tests/curvature/closed_form_test.cpp, tests/ao/test_ao.cpp.
#include <algorithm>
#include <cmath>

namespace isocurv::curvature {

/// Koenderink's shape index (2/pi) atan((k1+k2)/(k1-k2)) for k1 >= k2, in [-1, 1]: +1 on a convex
/// umbilic (sphere), -1 on a concave one, 0 on a symmetric saddle. Written as atan2 so the
/// umbilic case k1 == k2 gives +-1 by the sign of k1 + k2, and a plane (k1 == k2 == 0) gives 0.
template <class T>
T shape_index(T k1, T k2) {
  return T(2 / M_PI) * std::atan2(k1 + k2, k1 - k2);
}

/// Koenderink's curvedness sqrt((k1^2 + k2^2) / 2), in 1/length, >= 0.
template <class T>
T curvedness(T k1, T k2) {
  return std::sqrt((k1 * k1 + k2 * k2) / T(2));
}

/// Coefficients of Griffin et al.'s polynomial (section 3.7): with s = k1 + k2 on a unit
/// hemisphere, AO(s) = kAoC0 + kAoC1 s + kAoC2 s^2 is the unoccluded fraction of the hemisphere
/// above the osculating quadric, fitted on the umbilic diagonal k1 = k2 over the concave range
/// s in [-24, 0] (refitting the exact integral, eq. 10-12 with sqrt(1 + A^2), gives 0.0023, 0.0779,
/// 0.739). The printed "1.0 - 0.0022 s^2 + 0.0776 s + 0.7369" is garbled: it exceeds 1 at s = 0.
inline constexpr double kAoC0 = 0.7369, kAoC1 = 0.0776, kAoC2 = 0.0022;
/// Where the parabola has its minimum (s = -C1 / (2 C2)); more concave values are held there so
/// AO never rises again as the surface closes in.
inline constexpr double kAoSMin = -kAoC1 / (2 * kAoC2);

/// Ambient-light multiplier in [0, 1] from the principal curvatures (outward normals: concave is
/// negative) and the hemisphere radius `scale` (world units). Flat regions get kAoC0 (0.7369),
/// as in the paper; convex regions saturate at 1.
template <class T>
T ambient_occlusion(T k1, T k2, T scale) {
  const T s = std::max(scale * (k1 + k2), T(kAoSMin));
  const T ao = T(kAoC0) + s * (T(kAoC1) + s * T(kAoC2));
  return std::min(std::max(ao, T(0)), T(1));
}

}  // namespace isocurv::curvature
