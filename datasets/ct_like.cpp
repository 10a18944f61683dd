#include "datasets/ct_like.h"

#include <Eigen/Geometry>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "core/error.h"
#include "volume/from_dense.h"

namespace isocurv::datasets {
namespace {

using V3 = Eigen::Vector3d;
using M3 = Eigen::Matrix3d;
/// A solid: phi > 0 inside, 0 on the surface, smooth near it.
using Phi = std::function<double(const V3&)>;

V3 gradient(const Phi& phi, const V3& p) {
  const double h = 1e-5;
  V3 g;
  for (int a = 0; a < 3; ++a) {
    V3 d = V3::Zero();
    d[a] = h;
    g[a] = (phi(p + d) - phi(p - d)) / (2 * h);
  }
  return g;
}

M3 hessian(const Phi& phi, const V3& p) {
  const double h = 1e-3;
  M3 m;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      V3 da = V3::Zero(), db = V3::Zero();
      da[a] = h, db[b] = h;
      m(a, b) = (phi(p + da + db) - phi(p + da - db) - phi(p - da + db) + phi(p - da - db)) /
                (4 * h * h);
    }
  return 0.5 * (m + m.transpose());
}

M3 adjugate(const M3& m) {
  M3 c;
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) {
      const int r1 = (r + 1) % 3, r2 = (r + 2) % 3, k1 = (k + 1) % 3, k2 = (k + 2) % 3;
      c(k, r) = m(r1, k1) * m(r2, k2) - m(r1, k2) * m(r2, k1);
    }
  return c;
}

/// The exact curvature of phi's zero set at the point nearest p (Newton projection), outward
/// normals (-grad phi): H = (-tr Hs / |g| + g.Hs g / |g|^3) / 2, K = g.adj(Hs) g / |g|^4.
void implicit_exact(const Phi& phi, V3 p, double& H, double& K) {
  for (int it = 0; it < 30; ++it) {
    const V3 g = gradient(phi, p);
    const double v = phi(p);
    p -= v * g / g.squaredNorm();
    if (std::abs(v) < 1e-13) break;
  }
  const V3 g = gradient(phi, p);
  const M3 hs = hessian(phi, p);
  const double n = g.norm();
  H = 0.5 * (-hs.trace() / n + g.dot(hs * g) / (n * n * n));
  K = g.dot(adjugate(hs) * g) / (n * n * n * n);
}

struct Grid {
  std::array<int, 3> dims;
  V3 spacing = V3::Ones();
};

/// The same box sampled `refine` times finer along every axis: the same world extent, the
/// spacing divided by `refine`.
Grid refined(const Grid& g, int refine) {
  Grid r{g.dims, g.spacing / refine};
  for (int a = 0; a < 3; ++a) r.dims[a] = (g.dims[a] - 1) * refine + 1;
  return r;
}

/// Samples the class's intensity at every voxel centre (world = index * spacing).
volume::Volume make_volume(const Grid& grid, const std::string& type,
                           const std::function<double(const V3&)>& value) {
  const auto [nx, ny, nz] = grid.dims;
  std::vector<float> data(std::size_t(nx) * ny * nz);
  tbb::parallel_for(tbb::blocked_range<int>(0, nz), [&](const tbb::blocked_range<int>& r) {
    for (int z = r.begin(); z != r.end(); ++z)
      for (int y = 0; y < ny; ++y)
        for (int x = 0; x < nx; ++x)
          data[(std::size_t(z) * ny + y) * nx + x] = float(
              value(V3(x * grid.spacing[0], y * grid.spacing[1], z * grid.spacing[2])));
  });
  volume::DenseSource src;
  src.path = "ct-like";
  src.format = "generated";
  src.voxel_type = type;
  src.inside = volume::Inside::Above;
  openvdb::math::Mat4d m = openvdb::math::Mat4d::identity();
  m.setToScale(openvdb::Vec3d(grid.spacing[0], grid.spacing[1], grid.spacing[2]));
  return volume::from_dense(data.data(), grid.dims,
                            openvdb::math::Transform::createLinearTransform(m), src);
}

/// A grey-level class (see ct_like.h): blur b per axis, noise by a seeded Gaussian per voxel
/// (drawn in a fixed order, so the volume does not depend on the thread count).
volume::Volume grey(const Phi& phi, const Grid& grid, const std::string& type, double lo,
                    double hi, double noise, const V3& blur, unsigned seed) {
  const auto [nx, ny, nz] = grid.dims;
  std::vector<float> draws(std::size_t(nx) * ny * nz);
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  for (float& d : draws) d = float(gauss(rng));
  const double top = type == "uint8" ? 255 : 65535;
  return make_volume(grid, type, [&](const V3& p) {
    const V3 g = gradient(phi, p);
    const double len = g.norm();
    const double d = len > 0 ? phi(p) / len : phi(p);
    double b = blur[0];
    if (len > 0) {
      const V3 n = g / len;
      b = std::sqrt(n[0] * n[0] * blur[0] * blur[0] + n[1] * n[1] * blur[1] * blur[1] +
                    n[2] * n[2] * blur[2] * blur[2]);
    }
    const int x = int(std::lround(p[0] / grid.spacing[0])),
              y = int(std::lround(p[1] / grid.spacing[1])),
              z = int(std::lround(p[2] / grid.spacing[2]));
    const double e = 0.5 * std::erfc(-d / (std::sqrt(2.0) * b));
    const double v = lo + (hi - lo) * e + noise * draws[(std::size_t(z) * ny + y) * nx + x];
    return std::clamp(std::round(v), 0.0, top);
  });
}

volume::Volume binary(const Phi& phi, const Grid& grid) {
  return make_volume(grid, "uint8", [&](const V3& p) { return phi(p) > 0 ? 255.0 : 0.0; });
}

Phi sphere(const V3& c, double R) {
  return [=](const V3& p) { return R - (p - c).norm(); };
}

Phi torus(const V3& c, double Rt, double r) {
  return [=](const V3& p) {
    const V3 d = p - c;
    return r - std::hypot(std::hypot(d.x(), d.y()) - Rt, d.z());
  };
}

// The blur is the scanner's at the class's own grid (`grid`, refine 1), in world units, so a
// refined class is the same scan sampled finer; the noise per voxel is the same at every refine.
CtCase grey_case(const std::string& name, const Phi& phi, const Grid& grid,
                 const std::string& type, unsigned seed, int refine) {
  const bool u8 = type == "uint8";
  const double lo = u8 ? 20 : 1000, hi = u8 ? 220 : 4000, noise = u8 ? 3 : 40;
  V3 blur = V3::Ones();
  for (int a = 0; a < 3; ++a) blur[a] = std::max(1.0, 0.5 * grid.spacing[a]);
  CtCase c;
  c.name = name;
  c.volume = grey(phi, refined(grid, refine), type, lo, hi, noise, blur, seed);
  c.iso = float(0.5 * (lo + hi));
  c.exact = [phi](const V3& p, double& H, double& K) { implicit_exact(phi, p, H, K); };
  return c;
}

CtCase binary_case(const std::string& name, const Phi& phi, const Grid& grid, int refine) {
  CtCase c;
  c.name = name;
  c.volume = binary(phi, refined(grid, refine));
  c.iso = 127.5f;
  c.exact = [phi](const V3& p, double& H, double& K) { implicit_exact(phi, p, H, K); };
  c.binary = true;
  return c;
}

std::array<int, 3> cube(int n) { return {n, n, n}; }

}  // namespace

std::vector<std::string> ct_like_names() {
  return {"sphere_u8",     "torus_u8",     "tube_u8",       "ellipsoid_u16_thick", "gyroid_u8",
          "sphere_box_u8", "torus_binary", "sphere_binary", "part_binary"};
}

CtCase ct_like_case(const std::string& name, bool small, int refine) {
  if (refine < 1 || refine > 8) throw Error("ct_like_case: refine must be 1 to 8");
  const V3 jitter(0.31, -0.17, 0.07);  // centres off the grid
  if (name == "sphere_u8") {
    const double R = small ? 16 : 40;
    const int n = int(2 * R) + 12;
    return grey_case(name, sphere(V3::Constant(n / 2.0) + jitter, R), {cube(n)}, "uint8", 1, refine);
  }
  if (name == "torus_u8" || name == "tube_u8") {
    const bool tube = name == "tube_u8";
    const double r = tube ? 3.5 : (small ? 6 : 14), Rt = tube ? (small ? 14 : 24) : (small ? 14 : 36);
    const int nxy = int(2 * (Rt + r)) + 12, nz = int(2 * r) + 12;
    const V3 c = V3(nxy / 2.0, nxy / 2.0, nz / 2.0) + V3(0.23, -0.11, 0.17);
    return grey_case(name, torus(c, Rt, r), {{nxy, nxy, nz}}, "uint8", tube ? 5 : 2, refine);
  }
  if (name == "ellipsoid_u16_thick") {
    const V3 axes = small ? V3(18, 13, 10) : V3(32, 24, 17);
    const V3 spacing(1, 1, 2.5);
    const M3 rot = Eigen::AngleAxisd(0.5, V3(1, 2, 3).normalized()).toRotationMatrix();
    const double extent = 2 * axes.maxCoeff() + 10;
    Grid grid{{0, 0, 0}, spacing};
    for (int a = 0; a < 3; ++a) grid.dims[a] = int(std::ceil(extent / spacing[a])) + 1;
    const V3 c = V3::Constant(extent / 2) + jitter;
    // phi = 1 - |x / a|^2 scaled by the smallest axis to be near a distance at the surface.
    const double s = axes.minCoeff() / 2;
    const Phi phi = [=](const V3& p) {
      const V3 q = rot.transpose() * (p - c);
      return s * (1 - q.cwiseQuotient(axes).squaredNorm());
    };
    return grey_case(name, phi, grid, "uint16", 6, refine);
  }
  if (name == "gyroid_u8") {
    const double period = small ? 32 : 48, t = 0.8, k = 2 * M_PI / period;
    const int n = int(period) + 12;
    const Phi phi = [=](const V3& p) {
      const V3 q = k * (p + V3(1.3, 0.7, 2.1));
      const double g = std::sin(q.x()) * std::cos(q.y()) + std::sin(q.y()) * std::cos(q.z()) +
                       std::sin(q.z()) * std::cos(q.x());
      return (t - std::abs(g)) / k;  // near a distance: |grad g| is about k
    };
    return grey_case(name, phi, {cube(n)}, "uint8", 7, refine);
  }
  if (name == "sphere_box_u8") {
    const double R = small ? 16 : 30;
    const std::array<int, 3> dims = {int(1.5 * R) + 12, int(2 * R) + 12, int(1.5 * R) + 12};
    const V3 c(0.5 * R + 0.3, dims[1] / 2.0 - 0.17, 0.5 * R + 0.2);
    return grey_case(name, sphere(c, R), {dims}, "uint8", 8, refine);
  }
  if (name == "torus_binary") {
    // Lachaud, Romon, Thibert and Coeurjolly's torus: R 6, r 2, grid step 0.5.
    const Grid grid{{41, 41, 17}, V3::Constant(0.5)};
    return binary_case(name, torus(V3(10.013, 10.027, 4.031), 6, 2), grid, refine);
  }
  if (name == "sphere_binary") {
    const double R = small ? 12 : 24;
    const int n = int(2 * R) + 10;
    return binary_case(name, sphere(V3::Constant(n / 2.0) + jitter, R), {cube(n)}, refine);
  }
  if (name == "part_binary") {
    // A box with rounded edges (rounding radius rr), turned off the grid's axes.
    const V3 half = small ? V3(12, 9, 7) : V3(24, 18, 14);
    const double rr = small ? 4 : 7;
    const int n = int(2 * (half.norm() + rr)) + 8;
    const V3 c = V3::Constant(n / 2.0) + jitter;
    const M3 rot = Eigen::AngleAxisd(0.3, V3(1, 1, 1).normalized()).toRotationMatrix();
    auto local = [=](const V3& p) { return V3((rot.transpose() * (p - c)).cwiseAbs() - half); };
    const Phi phi = [=](const V3& p) {
      const V3 q = local(p);
      const double outside = q.cwiseMax(0.0).norm(), inside = std::min(q.maxCoeff(), 0.0);
      return rr - outside - inside;
    };
    CtCase cs = binary_case(name, phi, {cube(n)}, refine);
    // Exact: faces flat, edges cylinders of radius rr, corners spheres.
    cs.exact = [=](const V3& p, double& H, double& K) {
      const V3 q = local(p);
      const int positive = int(q.x() > 0) + int(q.y() > 0) + int(q.z() > 0);
      H = positive == 2 ? 0.5 / rr : positive == 3 ? 1 / rr : 0;
      K = positive == 3 ? 1 / (rr * rr) : 0;
    };
    return cs;
  }
  throw Error("ct_like_case: no class called '" + name + "'");
}

}  // namespace isocurv::datasets
