#include "volume/gaussian_jet.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "volume/detail/separable_sum.h"

namespace isocurv::volume {

GridFrame grid_frame(const Volume& volume) {
  const openvdb::math::Transform& xform = volume.grid->transform();
  if (!xform.isLinear())
    throw Error(volume.path, "the volume estimator needs an affine grid transform");
  GridFrame f;
  f.origin = xform.indexToWorld(openvdb::Vec3d(0, 0, 0));
  for (int a = 0; a < 3; ++a) {
    openvdb::Vec3d e(0, 0, 0);
    e[a] = 1;
    const openvdb::Vec3d col = xform.indexToWorld(e) - f.origin;
    for (int r = 0; r < 3; ++r) f.A(r, a) = col[r];
    f.spacing[a] = col.length();
  }
  for (int a = 0; a < 3; ++a)
    for (int b = a + 1; b < 3; ++b) {
      double d = 0;
      for (int r = 0; r < 3; ++r) d += f.A(r, a) * f.A(r, b);
      if (std::abs(d) > 1e-6 * f.spacing[a] * f.spacing[b])
        throw Error(volume.path,
                    "the volume estimator needs a grid whose axes are orthogonal (this transform "
                    "shears them); use --estimator rusinkiewicz");
    }
  f.B = f.A.inverse();
  f.clamp = volume.dense && !volume.domain.empty();
  f.lo = volume.domain.min();
  f.hi = volume.domain.max();
  return f;
}

AxisWeights axis_weights(double q, double s, double radius) {
  AxisWeights aw;
  const double reach = radius * s;
  aw.first = int(std::ceil(q - reach));
  const int last = int(std::floor(q + reach));
  aw.count = std::min(last - aw.first + 1, AxisWeights::kMaxTaps);
  const double s2 = s * s;
  double moment[4] = {0, 0, 0, 0};
  for (int t = 0; t < aw.count; ++t) {
    const double d = aw.first + t - q;  // tap minus evaluation point
    const double g = std::exp(-d * d / (2 * s2));
    // d^n/dq^n of G(q - j): with x = q - j = -d, G' = -x/s^2 G, G'' = (x^2/s^4 - 1/s^2) G and
    // G''' = (-x^3/s^6 + 3x/s^4) G.
    aw.w[0][t] = g;
    aw.w[1][t] = d / s2 * g;
    aw.w[2][t] = (d * d / s2 - 1) / s2 * g;
    aw.w[3][t] = (d * d / s2 - 3) * d / (s2 * s2) * g;
    moment[0] += aw.w[0][t];
    moment[1] += aw.w[1][t] * d;
    moment[2] += aw.w[2][t] * d * d / 2;
    moment[3] += aw.w[3][t] * d * d * d / 6;
  }
  for (int n = 0; n < 4; ++n)
    for (int t = 0; t < aw.count; ++t) aw.w[n][t] /= moment[n];
  return aw;
}

Jet world_jet(const double (&d)[4][4][4], const openvdb::Mat3d& B, int order) {
  // Index-space tensors by axis indices, then to world space: each index of a derivative tensor
  // picks up B (d/dworld_k = sum_a B(a, k) d/dindex_a).
  auto idx = [&](std::initializer_list<int> axes) {
    int n[3] = {0, 0, 0};
    for (int a : axes) ++n[a];
    return d[n[0]][n[1]][n[2]];
  };
  Jet jet;
  jet.value = d[0][0][0];
  if (order >= 1)
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a) jet.gradient[k] += B(a, k) * idx({a});
  if (order >= 2)
    for (int e = 0; e < 6; ++e) {
      const int k = kHessianAxes[e][0], l = kHessianAxes[e][1];
      double sum = 0;
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) sum += B(a, k) * B(b, l) * idx({a, b});
      jet.hessian[e] = sum;
    }
  if (order >= 3)
    for (int e = 0; e < 10; ++e) {
      const int k = kThirdAxes[e][0], l = kThirdAxes[e][1], m = kThirdAxes[e][2];
      double sum = 0;
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
          for (int c = 0; c < 3; ++c) sum += B(a, k) * B(b, l) * B(c, m) * idx({a, b, c});
      jet.third[e] = sum;
    }
  return jet;
}

Jet gaussian_jet(const openvdb::FloatGrid& grid, const GridFrame& frame, const openvdb::Vec3d& p,
                 double sigma, int order, double radius) {
  const openvdb::Vec3d q = frame.to_index(p);
  AxisWeights w[3];
  for (int a = 0; a < 3; ++a) w[a] = axis_weights(q[a], sigma / frame.spacing[a], radius);
  openvdb::FloatGrid::ConstAccessor acc = grid.getConstAccessor();
  auto clamp = [&](int v, int a) {
    return frame.clamp ? std::min(std::max(v, frame.lo[a]), frame.hi[a]) : v;
  };

  // d[nx][ny][nz]: the index-space derivative of orders (nx, ny, nz), nx + ny + nz <= order.
  double d[4][4][4] = {};
  detail::separable_sum(
      w, order,
      [&](int x, int y, int z) -> double {
        return acc.getValue(openvdb::Coord(clamp(x, 0), clamp(y, 1), clamp(z, 2)));
      },
      d);
  return world_jet(d, frame.B, order);
}

Jet shifted_jet(const Jet& jet, const openvdb::Vec3d& step) {
  // Symmetric storage: Hessian (xx xy xz yy yz zz), third (xxx xxy xxz xyy xyz xzz yyy yyz yzz
  // zzz).
  static const int kPair[3][3] = {{0, 1, 2}, {1, 3, 4}, {2, 4, 5}};
  static const int kTriple[3][3][3] = {{{0, 1, 2}, {1, 3, 4}, {2, 4, 5}},
                                       {{1, 3, 4}, {3, 6, 7}, {4, 7, 8}},
                                       {{2, 4, 5}, {4, 7, 8}, {5, 8, 9}}};
  double ts[3][3] = {}, hs[3] = {};  // T(., ., s) and H s
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 3; ++l) {
      for (int m = 0; m < 3; ++m) ts[k][l] += jet.third[kTriple[k][l][m]] * step[m];
      hs[k] += jet.hessian[kPair[k][l]] * step[l];
    }
  Jet out = jet;
  for (int k = 0; k < 3; ++k) {
    double tss = 0;
    for (int l = 0; l < 3; ++l) tss += ts[k][l] * step[l];
    out.gradient[k] += hs[k] + tss / 2;
    out.value += step[k] * (jet.gradient[k] + hs[k] / 2 + tss / 6);
  }
  for (int e = 0; e < 6; ++e) out.hessian[e] += ts[kHessianAxes[e][0]][kHessianAxes[e][1]];
  return out;
}

}  // namespace isocurv::volume
