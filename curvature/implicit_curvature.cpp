#include "curvature/implicit_curvature.h"

#include <Eigen/Geometry>
#include <cmath>

namespace isocurv::curvature {
namespace {

using V3 = Eigen::Vector3d;

// An orthonormal tangent basis (u, v) with (u, v, n) right-handed (Duff et al. 2017), as in
// reference.cpp and curvature_math.cl.
void tangent_basis(const V3& n, V3& u, V3& v) {
  const double sign = n.z() < 0 ? -1.0 : 1.0;
  const double a = -1.0 / (sign + n.z());
  const double b = n.x() * n.y() * a;
  u = V3(1 + sign * n.x() * n.x() * a, sign * b, -sign * n.x());
  v = V3(b, sign + n.y() * n.y() * a, -n.y());
}

// T(a, b, c) for the symmetric 3-tensor stored as (xxx, xxy, xxz, xyy, xyz, xzz, yyy, yyz, yzz,
// zzz).
double cubic(const std::array<double, 10>& t, const V3& a, const V3& b, const V3& c) {
  static const int kIndex[3][3][3] = {{{0, 1, 2}, {1, 3, 4}, {2, 4, 5}},
                                      {{1, 3, 4}, {3, 6, 7}, {4, 7, 8}},
                                      {{2, 4, 5}, {4, 7, 8}, {5, 8, 9}}};
  double sum = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) sum += t[kIndex[i][j][k]] * a[i] * b[j] * c[k];
  return sum;
}

}  // namespace

PointCurvature implicit_curvature(const volume::Jet& jet, volume::Inside inside) {
  PointCurvature r;
  const V3 g(jet.gradient[0], jet.gradient[1], jet.gradient[2]);
  const double len = g.norm();
  if (!(len > 0) || !std::isfinite(len)) return r;
  const auto& h = jet.hessian;
  Eigen::Matrix3d Hs;
  Hs << h[0], h[1], h[2], h[1], h[3], h[4], h[2], h[4], h[5];
  const double s = inside == volume::Inside::Above ? -1.0 : 1.0;
  const V3 m = g / len, n = s * m;
  V3 u, v;
  tangent_basis(n, u, v);
  // S restricted to the tangent plane, in (u, v): s u.Hs v / |g| (P u = u).
  const double a = s * u.dot(Hs * u) / len, b = s * u.dot(Hs * v) / len,
               c = s * v.dot(Hs * v) / len;
  const double mean = (a + c) / 2, half = (a - c) / 2, r2 = std::sqrt(half * half + b * b);
  const double theta = 0.5 * std::atan2(2 * b, a - c);
  r.normal = n;
  r.k1 = mean + r2;
  r.k2 = mean - r2;
  r.dir1 = std::cos(theta) * u + std::sin(theta) * v;
  r.dir2 = n.cross(r.dir1);
  r.gradient_norm = len;
  const V3 Hm = Hs * m;
  auto C = [&](const V3& x, const V3& y, const V3& z) {
    const double quad =
        (x.dot(Hs * z) * Hm.dot(y) + y.dot(Hs * z) * Hm.dot(x) + x.dot(Hs * y) * Hm.dot(z)) / len;
    return s / len * (cubic(jet.third, x, y, z) - quad);
  };
  const V3 &e1 = r.dir1, &e2 = r.dir2;
  r.dcurv = {C(e1, e1, e1), C(e1, e1, e2), C(e1, e2, e2), C(e2, e2, e2)};
  return r;
}

}  // namespace isocurv::curvature
