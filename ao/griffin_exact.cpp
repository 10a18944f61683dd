#include "ao/griffin_exact.h"

#include <array>
#include <cmath>

#include "ao/formulas.h"

namespace isocurv::ao {

namespace {

constexpr int kNodes = 24;

/// Gauss-Legendre nodes and weights on [-1, 1] (Newton on the Legendre polynomial), once.
struct GaussLegendre {
  std::array<double, kNodes> x{}, w{};
  GaussLegendre() {
    for (int i = 0; i < kNodes; ++i) {
      double t = std::cos(M_PI * (i + 0.75) / (kNodes + 0.5)), dp = 1;
      for (int it = 0; it < 100; ++it) {
        double p0 = 1, p1 = t;
        for (int k = 2; k <= kNodes; ++k) {
          const double p2 = ((2 * k - 1) * t * p1 - (k - 1) * p0) / k;
          p0 = p1, p1 = p2;
        }
        dp = kNodes * (t * p1 - p0) / (t * t - 1);
        const double dt = p1 / dp;
        t -= dt;
        if (std::abs(dt) < 1e-16) break;
      }
      x[i] = t, w[i] = 2 / ((1 - t * t) * dp * dp);
    }
  }
};

const GaussLegendre& gauss_legendre() {
  static const GaussLegendre g;
  return g;
}

}  // namespace

double griffin_exact_integral(double a1, double a2, bool cosine) {
  if (!std::isfinite(a1) || !std::isfinite(a2)) return 1;
  // A(phi) = -a1 + (a1 - a2) s, s = sin^2 phi in [0, 1]: concave (A > 0) at phi = 0 iff a1 < 0,
  // at pi/2 iff a2 < 0; in between it crosses zero once, at s0 = a1 / (a1 - a2).
  double lo = 0, hi = M_PI / 2;
  if (a1 >= 0 && a2 >= 0) return 1;
  if (a1 < 0 && a2 >= 0) hi = std::asin(std::sqrt(a1 / (a1 - a2)));
  if (a1 >= 0 && a2 < 0) lo = std::asin(std::sqrt(a1 / (a1 - a2)));
  const GaussLegendre& g = gauss_legendre();
  const double mid = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
  double sum = 0;
  for (int i = 0; i < kNodes; ++i) {
    const double phi = mid + half * g.x[i], s = std::sin(phi), c = std::cos(phi);
    const double z = std::max(0.0, horizon_height(-(a1 * c * c + a2 * s * s)));
    sum += g.w[i] * (cosine ? z * z : z);
  }
  return std::max(0.0, 1 - (2 / M_PI) * half * sum);  // the quarter [0, pi/2] is a quarter of 2pi
}

double griffin_exact(double k1, double k2, double rho) {
  return griffin_exact_integral(rho * k1, rho * k2);
}

}  // namespace isocurv::ao
