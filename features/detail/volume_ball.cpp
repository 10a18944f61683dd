#include "features/detail/volume_ball.h"

#include <openvdb/tools/Interpolation.h>

#include <cmath>

#include "core/error.h"
#include "curvature/detail/local_geometry.h"

namespace isocurv::features::detail {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// Gauss-Legendre nodes and weights on [-1, 1] for n points (Newton on the
/// Legendre polynomial).
void gauss_legendre(int n, std::vector<double> &x, std::vector<double> &w) {
  x.assign(n, 0);
  w.assign(n, 0);
  for (int i = 0; i < n; ++i) {
    double z = std::cos(kPi * (i + 0.75) / (n + 0.5)), dp = 1;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1, p1 = z;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
        p0 = p1, p1 = p2;
      }
      const double pn = n == 1 ? z : p1, pn1 = n == 1 ? 1 : p0;
      dp = n * (z * pn - pn1) / (z * z - 1);
      const double dz = pn / dp;
      z -= dz;
      if (std::abs(dz) < 1e-15)
        break;
    }
    x[i] = z;
    w[i] = 2 / ((1 - z * z) * dp * dp);
  }
}

} // namespace

VolumeBall::VolumeBall(const volume::Volume &volume, double isovalue,
                       int azimuths, int radial)
    : volume_(volume), accessor_(volume.grid->getConstAccessor()),
      isovalue_(isovalue),
      sign_(volume.inside == volume::Inside::Above ? 1 : -1),
      azimuths_(azimuths), radial_(radial) {
  if (azimuths < 1 || radial < 2 || radial > 16)
    throw Error("feature quadrature: azimuths must be >= 1 and radial 2..16");
  gauss_legendre(radial, nodes_, weights_);
}

double VolumeBall::inside(const openvdb::Vec3d &world) {
  return inside_at_index(volume_.grid->transform().worldToIndex(world));
}

double VolumeBall::inside_at_index(const openvdb::Vec3d &index) {
  return sign_ *
         (openvdb::tools::BoxSampler::sample(accessor_, index) - isovalue_);
}

VolumeBall::Result VolumeBall::inside_volume(const openvdb::Vec3d &p,
                                             const openvdb::Vec3d &n,
                                             double r) {
  Result res;
  // Does the ball's index-space bounding box stay in the data domain?
  bool &leaves_domain = res.leaves;
  const openvdb::CoordBBox &dom = volume_.domain;
  for (int corner = 0; corner < 8; ++corner) {
    const openvdb::Vec3d w(p.x() + ((corner & 1) ? r : -r),
                           p.y() + ((corner & 2) ? r : -r),
                           p.z() + ((corner & 4) ? r : -r));
    const openvdb::Vec3d i = volume_.grid->transform().worldToIndex(w);
    for (int a = 0; a < 3; ++a)
      if (i[a] < dom.min()[a] || i[a] > dom.max()[a])
        leaves_domain = true;
  }
  Eigen::Vector3d u, v;
  curvature::detail::tangent_basis(Eigen::Vector3d(n.x(), n.y(), n.z()), u, v);
  const openvdb::Vec3d e1(u.x(), u.y(), u.z()), e2(v.x(), v.y(), v.z());

  const openvdb::math::MapBase &map = *volume_.grid->transform().baseMap();
  const bool linear = volume_.grid->transform().isLinear();
  const openvdb::Vec3d pi = volume_.grid->transform().worldToIndex(p);
  const openvdb::Vec3d ni = linear ? map.applyInverseJacobian(n) : n;
  const std::vector<double> &gx = nodes_;
  const std::vector<double> &gw = weights_;
  double volume = 0;
  std::vector<double> &outside =
      outside_; // per radius: sum over azimuths of 1 - L
  outside.assign(radial_, 0);
  for (int k = 0; k < azimuths_; ++k) {
    const double phi = 2 * kPi * (k + 0.5) / azimuths_;
    const openvdb::Vec3d u = std::cos(phi) * e1 + std::sin(phi) * e2;
    double over_t = 0;
    for (int j = 0; j < radial_; ++j) {
      const double t = 0.5 * r * (gx[j] + 1);
      // Linear (affine) transforms: the arc in index space, no per-sample
      // transform.
      const openvdb::Vec3d ui = linear ? map.applyInverseJacobian(u) : u;
      auto at = [&](double s) {
        const double c = std::sqrt(std::max(0.0, 1 - s * s));
        return linear ? inside_at_index(pi + t * (c * ui + s * ni))
                      : inside(p + t * (c * u + s * n));
      };
      // Inside length of the arc in s.
      double length = 0, s0 = -1, g0 = at(s0);
      for (int i = 1; i < kArcSamples; ++i) {
        const double s1 = -1 + 2.0 * i / (kArcSamples - 1), g1 = at(s1);
        const bool in0 = g0 > 0, in1 = g1 > 0;
        if (in0 && in1) {
          length += s1 - s0;
        } else if (in0 != in1) {
          // Regula falsi (Illinois) for the crossing between s0 and s1.
          double lo = s0, hi = s1, glo = g0, ghi = g1, s = 0.5 * (lo + hi);
          int side = 0;
          for (int it = 0; it < kRefineSteps; ++it) {
            s = (lo * ghi - hi * glo) / (ghi - glo);
            const double gs = at(s);
            if ((gs > 0) == (glo > 0)) {
              lo = s, glo = gs;
              if (side == -1)
                ghi *= 0.5;
              side = -1;
            } else {
              hi = s, ghi = gs;
              if (side == 1)
                glo *= 0.5;
              side = 1;
            }
          }
          length += in0 ? s - s0 : s1 - s;
        }
        s0 = s1, g0 = g1;
      }
      over_t += 0.5 * r * gw[j] * t * t * length;
      outside[j] += 1 - length;
    }
    volume += (2 * kPi / azimuths_) * over_t;
  }
  res.vr = volume;
  // Weighted least squares m_j = d + (H / 2) x_j, x_j = t_j^2, weights the
  // Gauss-Legendre ones.
  double sw = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (int j = 0; j < radial_; ++j) {
    const double t = 0.5 * r * (gx[j] + 1), x = t * t,
                 m = t * outside[j] / azimuths_;
    sw += gw[j], sx += gw[j] * x, sy += gw[j] * m, sxx += gw[j] * x * x,
        sxy += gw[j] * x * m;
  }
  const double det = sw * sxx - sx * sx;
  res.h_fit = det > 0 ? 2 * (sw * sxy - sx * sy) / det : 0;
  return res;
}

} // namespace isocurv::features::detail
