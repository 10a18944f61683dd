#pragma once
// Curvature-based ambient occlusion at one point, from the principal curvatures (outward normals:
// concave is negative) and the hemisphere radius rho (world units). SEEDS-SPEC.md sections 2.3
// (G-AO2) and 5.4 (R-AO2, R-AO4) give the corrected forms used here; the papers' misprints are
// noted where they matter. Griffin's polynomial stays in curvature/derived.h (ambient_occlusion),
// Griffin's exact integral is ao/griffin_exact.h.
// Tested in tests/ao/test_ao.cpp.
#include <algorithm>
#include <cmath>

namespace isocurv::ao {

/// Where the normal section z = A x^2 / 2 of the osculating quadric (A = -rho k along an azimuth,
/// positive where the surface curves up towards the normal: concave) meets the unit hemisphere:
/// z^2 + 2 z / A - 1 = 0, so z = (-1 + sqrt(1 + A^2)) / A (Griffin eq. 11 prints sqrt(1 - A^2)),
/// written A / (1 + sqrt(1 + A^2)) to avoid the cancellation; 0 at A = 0, in (-1, 1).
inline double horizon_height(double A) { return A / (1 + std::sqrt(1 + A * A)); }

/// Hattori's simplified curvature AO (Prantl's report eq. 6.6-6.9, re-derived: R-AO2):
/// AO = (2/pi) arccos(z(x)), the horizon's angle from the normal over a right angle, with
/// x = -rho (k1 + k2) as printed, or the umbilic mean x = -rho (k1 + k2) / 2 when `half`.
/// 1 for x <= 0 (flat or convex), decreasing to 0 as the surface closes in. (SEEDS-SPEC's check
/// value 0.7281 "at rho s = 2" is the half form at rho (k1 + k2) = -2; the printed form gives
/// 0.5759 there.)
inline double hattori(double k1, double k2, double rho, bool half = false) {
  const double x = -rho * (k1 + k2) * (half ? 0.5 : 1.0);
  if (!(x > 0)) return 1;
  return (2 / M_PI) * std::acos(horizon_height(x));
}

/// Prantl's mean-curvature mapping (report eq. 7.14, R-AO4), with the Gaussian moved to the
/// concave side for outward normals (the report writes it for inward ones): m = clamp(H / href,
/// -1, 1); m < 0: a exp(-m^2 / (2 * 0.2)); m >= 0: a + (1 - a) m. a = 0.9 as in the report (so a
/// plane gets 0.9, not 1; a = 1 makes flat regions white but loses detail, the report says).
/// href > 0, the "curvature extreme" (ao::compute takes the 98th percentile of |H|).
inline double prantl(double H, double href, double a = 0.9) {
  const double m = std::clamp(H / href, -1.0, 1.0);
  if (m < 0) return a * std::exp(-m * m / (2 * 0.2));
  return a + (1 - a) * m;
}

}  // namespace isocurv::ao
