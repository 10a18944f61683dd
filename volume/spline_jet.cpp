#include "volume/spline_jet.h"

#include <cmath>

#include "volume/detail/separable_sum.h"

namespace isocurv::volume {
namespace {

constexpr int kDegree = 4;
constexpr int kTaps = kDegree + 1;

}  // namespace

SplineWeights spline_weights(double q) {
  // beta4(x) = M4(x + 2.5) with M_p the cardinal B-spline of degree p on [0, p + 1]. With
  // x = q + 2.5 = base + u (0 <= u < 1) the taps are i = base - j, j = 0..4, at M4(u + j).
  const double x = q + kSplineReach;
  const double base = std::floor(x), u = x - base;
  // m[p][j] = M_p(u + j) for j = 0..p, by the recursion
  // M_p(y) = (y M_{p-1}(y) + (p + 1 - y) M_{p-1}(y - 1)) / p (all terms non-negative).
  double m[kTaps][kTaps] = {};
  m[0][0] = 1;
  for (int p = 1; p <= kDegree; ++p)
    for (int j = 0; j <= p; ++j) {
      const double y = u + j;
      const double left = j <= p - 1 ? m[p - 1][j] : 0, right = j >= 1 ? m[p - 1][j - 1] : 0;
      m[p][j] = (y * left + (p + 1 - y) * right) / p;
    }
  // d^n/dq^n M4(y) = sum_k (-1)^k C(n, k) M_{4-n}(y - k): backward differences of lower degrees.
  static const int kBinomial[4][4] = {{1, 0, 0, 0}, {1, 1, 0, 0}, {1, 2, 1, 0}, {1, 3, 3, 1}};
  SplineWeights sw;
  sw.first = int(base) - kDegree;
  for (int n = 0; n < 4; ++n)
    for (int j = 0; j < kTaps; ++j) {
      double sum = 0;
      for (int k = 0; k <= n; ++k) {
        const int at = j - k, p = kDegree - n;
        if (at >= 0 && at <= p) sum += (k % 2 ? -1 : 1) * kBinomial[n][k] * m[p][at];
      }
      sw.w[n][kDegree - j] = sum;  // tap base - j is first + (4 - j)
    }
  return sw;
}

Jet spline_jet(const SmoothedSamples& s, const openvdb::Vec3d& p, int order) {
  const SmoothingPlan& plan = *s.plan;
  const openvdb::Vec3d q = plan.frame.to_index(p);
  SplineWeights w[3];
  for (int a = 0; a < 3; ++a) w[a] = spline_weights(q[a]);
  auto sample = [&](int x, int y, int z) {
    const std::ptrdiff_t i = plan.sample_index(plan.stages[3], openvdb::Coord(x, y, z));
    return i < 0 ? s.background : s.samples[std::size_t(i)];
  };
  // d[nx][ny][nz]: the index-space derivative of orders (nx, ny, nz), nx + ny + nz <= order.
  double d[4][4][4] = {};
  detail::separable_sum(w, order, sample, d);
  return world_jet(d, plan.frame.B, order);
}

}  // namespace isocurv::volume
