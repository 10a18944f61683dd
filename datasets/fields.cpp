// The catalogue of analytic fields: formulas, parameters, gradients and Hessians.
//
// Sizes (world units):
//   sphere          |p| - 0.8 (signed distance), inside Below, box [-1,1]^3.
//   torus           0.25 - dist(p, circle of radius 0.6 in z=0), inside Above, box [-1,1]^2 x [-0.4,0.4].
//   ellipsoid       1 - (x/0.8)^2 - (y/0.6)^2 - (z/0.4)^2, inside Above, box = semi-axes + 0.2.
//   gyroid          sin(wx)cos(wy) + sin(wy)cos(wz) + sin(wz)cos(wx), w = 2 pi (period 1), iso 0,
//                   inside Above, cut by the box [-1,1]^3 (two periods per axis).
//   schwarz_p       cos(wx) + cos(wy) + cos(wz), w = 2 pi, iso 0, inside Above, cut by [-1,1]^3.
//   f1, f2          Prantl et al. section 4.1 heightfields z = f(x,y) as f(x,y) - z = 0, inside Above
//                   (the solid under the graph, normal pointing up), cut by the box sides
//                   x, y = +-10. f1 = 10 sin(r)/r, r = sqrt(x^2+y^2) (10 at r = 0), z in [-3.5, 11.5];
//                   f2 = sin(x)cos(y) + 0.1(x^2 - y^2), z in [-12, 12].
//   marschner_lobb  Marschner & Lobb (1994) test signal, f_M = 6, alpha = 0.25, iso 0.5, inside
//                   Above, cut by [-1,1]^3.
//   hydrogen        3d_z2 orbital density |psi_320|^2 ~ (2z^2 - x^2 - y^2)^2 exp(-2r/3), lengths in
//                   Bohr radii, normalised to max 1, iso 0.05, inside Above: two lobes and a ring,
//                   box [-14.5,14.5]^2 x [-18,18].
//   buckyball       sum of Gaussians exp(-d^2 / (2 sigma^2)) on the 60 C60 sites, bond 1.42 A,
//                   sigma 0.5 A, iso 0.5, inside Above, lengths in angstrom, box [-4.6,4.6]^3. Each
//                   Gaussian is cut off beyond 7 sigma (its value there is below 3e-11).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <functional>

#include "core/error.h"
#include "datasets/c60.h"
#include "datasets/field.h"

namespace isocurv::datasets {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using volume::Inside;

constexpr double kPi = 3.14159265358979323846;

Eigen::AlignedBox3d make_box(const Vector3d& lo, const Vector3d& hi) { return Eigen::AlignedBox3d(lo, hi); }
Eigen::AlignedBox3d cube(double half) { return make_box(Vector3d::Constant(-half), Vector3d::Constant(half)); }

// sin(t)/t, exact to double precision near 0.
double sinc(double t) {
  if (std::abs(t) < 1e-3) return 1.0 - t * t / 6.0 + t * t * t * t / 120.0;
  return std::sin(t) / t;
}

// A function g of r = sqrt(x^2 + y^2) seen as a function of (x, y): g'(r)/r and g''(r) give the
// gradient (g'/r)(x, y) and Hessian (g'/r) I + (g'' - g'/r) u u^T, u = (x, y)/r. At r = 0 the second
// term vanishes for smooth even g (g'' = g'/r there).
struct Radial {
  double g, dg_over_r, d2g;
};
Eigen::Vector2d radial_gradient(const Radial& f, double x, double y) { return f.dg_over_r * Eigen::Vector2d(x, y); }
Eigen::Matrix2d radial_hessian(const Radial& f, double x, double y) {
  Eigen::Matrix2d h = f.dg_over_r * Eigen::Matrix2d::Identity();
  const double r = std::hypot(x, y);
  if (r > 0) {
    const Eigen::Vector2d u(x / r, y / r);
    h += (f.d2g - f.dg_over_r) * u * u.transpose();
  }
  return h;
}

// Per-thread cache of per-x factors for rows x0 + i dx, i < n. sample() evaluates every row of a
// grid at the same x positions, so values_along_x overrides compute these once per thread and grid.
struct RowCache {
  const void* owner = nullptr;
  double x0 = 0, dx = 0;
  int n = -1;
  std::vector<double> v;
  // True when the cache must be refilled (then resized to count * n entries).
  bool stale(const void* o, double x0_, double dx_, int n_, std::size_t count) {
    if (owner == o && x0 == x0_ && dx == dx_ && n == n_) return false;
    owner = o, x0 = x0_, dx = dx_, n = n_;
    v.resize(count * static_cast<std::size_t>(n_));
    return true;
  }
};

// ---------------------------------------------------------------------------------------------

class Sphere final : public Field {
 public:
  static constexpr double R = 0.8;
  Sphere()
      : Field({"sphere", "signed distance |p| - R, R = 0.8, negative inside (level set)", 0.0, Inside::Below,
               cube(1.0), true, 2}) {}
  double value(const Vector3d& p) const override { return p.norm() - R; }
  Vector3d gradient(const Vector3d& p) const override {
    const double n = p.norm();
    return n > 0 ? Vector3d(p / n) : Vector3d::Zero();
  }
  Matrix3d hessian(const Vector3d& p) const override {
    const double n = p.norm();
    if (n == 0) return Matrix3d::Zero();
    const Vector3d u = p / n;
    return (Matrix3d::Identity() - u * u.transpose()) / n;
  }
};

class Torus final : public Field {
 public:
  static constexpr double R = 0.6, r = 0.25;
  Torus()
      : Field({"torus",
               "r - dist(p, circle radius R in z=0), R = 0.6, r = 0.25, axis z, positive inside",
               0.0, Inside::Above, make_box(Vector3d(-1, -1, -0.4), Vector3d(1, 1, 0.4)), true, 0}) {}
  double value(const Vector3d& p) const override {
    const double rho = std::sqrt(p.x() * p.x() + p.y() * p.y()) - R;
    return r - std::sqrt(rho * rho + p.z() * p.z());
  }
  // q = p minus its nearest point on the core circle; d = |q|; F = r - d.
  Vector3d gradient(const Vector3d& p) const override {
    const double rho = std::hypot(p.x(), p.y());
    if (rho == 0) return Vector3d(0, 0, -p.z() / std::hypot(R, p.z()));
    const Vector3d q((rho - R) * p.x() / rho, (rho - R) * p.y() / rho, p.z());
    const double d = q.norm();
    return d > 0 ? Vector3d(-q / d) : Vector3d::Zero();
  }
  Matrix3d hessian(const Vector3d& p) const override {
    const double rho = std::hypot(p.x(), p.y());
    if (rho == 0) return Matrix3d::Zero();  // on the axis the field is not twice differentiable
    const Vector3d e_rho(p.x() / rho, p.y() / rho, 0), e_z(0, 0, 1);
    const Vector3d q = (rho - R) * e_rho + p.z() * e_z;
    const double d = q.norm();
    if (d == 0) return Matrix3d::Zero();
    // Hessian of d^2/2 = e_rho e_rho^T + e_z e_z^T + (rho - R)/rho (P_xy - e_rho e_rho^T).
    const Matrix3d p_xy = Eigen::Vector3d(1, 1, 0).asDiagonal();
    const Matrix3d h_half_sq = e_rho * e_rho.transpose() + e_z * e_z.transpose() +
                               (rho - R) / rho * (p_xy - e_rho * e_rho.transpose());
    const Matrix3d h_d = h_half_sq / d - q * q.transpose() / (d * d * d);
    return -h_d;
  }
};

class Ellipsoid final : public Field {
 public:
  Ellipsoid() : Ellipsoid(0.8, 0.6, 0.4, "ellipsoid") {}
  Ellipsoid(double a, double b, double c, const std::string& name)
      : Field({name, "1 - (x/a)^2 - (y/b)^2 - (z/c)^2, semi-axes a, b, c = " + fmt_axes(a, b, c) + ", positive inside",
               0.0, Inside::Above, make_box(-Vector3d(a, b, c) - Vector3d::Constant(0.2), Vector3d(a, b, c) + Vector3d::Constant(0.2)), true, 2}),
        inv_sq_(1 / (a * a), 1 / (b * b), 1 / (c * c)) {}
  double value(const Vector3d& p) const override { return 1.0 - p.cwiseProduct(p).dot(inv_sq_); }
  Vector3d gradient(const Vector3d& p) const override { return -2.0 * p.cwiseProduct(inv_sq_); }
  Matrix3d hessian(const Vector3d&) const override { return Matrix3d(-2.0 * inv_sq_.asDiagonal()); }

 private:
  static std::string fmt_axes(double a, double b, double c) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "%g, %g, %g", a, b, c);
    return buf;
  }
  Vector3d inv_sq_;
};

class Gyroid final : public Field {
 public:
  static constexpr double w = 2 * kPi;
  Gyroid()
      : Field({"gyroid", "sin(wx)cos(wy) + sin(wy)cos(wz) + sin(wz)cos(wx), w = 2 pi (period 1), cut by [-1,1]^3",
               0.0, Inside::Above, cube(1.0), false, std::nullopt}) {}
  double value(const Vector3d& p) const override {
    const double sx = std::sin(w * p.x()), cx = std::cos(w * p.x());
    return combine(sx, cx, std::sin(w * p.y()), std::cos(w * p.y()), std::sin(w * p.z()), std::cos(w * p.z()));
  }
  void values_along_x(double x0, double dx, double y, double z, int n, double* out) const override {
    thread_local RowCache sc;  // sin, cos of w x per voxel
    if (sc.stale(this, x0, dx, n, 2))
      for (int i = 0; i < n; ++i) {
        const double x = x0 + i * dx;
        sc.v[2 * i] = std::sin(w * x);
        sc.v[2 * i + 1] = std::cos(w * x);
      }
    const double sy = std::sin(w * y), cy = std::cos(w * y), sz = std::sin(w * z), cz = std::cos(w * z);
    for (int i = 0; i < n; ++i) out[i] = combine(sc.v[2 * i], sc.v[2 * i + 1], sy, cy, sz, cz);
  }
  static double combine(double sx, double cx, double sy, double cy, double sz, double cz) {
    return sx * cy + sy * cz + sz * cx;
  }
  Vector3d gradient(const Vector3d& p) const override {
    const Vector3d s = (w * p).array().sin(), c = (w * p).array().cos();
    return w * Vector3d(c.x() * c.y() - s.z() * s.x(), c.y() * c.z() - s.x() * s.y(), c.z() * c.x() - s.y() * s.z());
  }
  Matrix3d hessian(const Vector3d& p) const override {
    const Vector3d s = (w * p).array().sin(), c = (w * p).array().cos();
    Matrix3d h;
    h(0, 0) = -s.x() * c.y() - s.z() * c.x();
    h(1, 1) = -s.y() * c.z() - s.x() * c.y();
    h(2, 2) = -s.z() * c.x() - s.y() * c.z();
    h(0, 1) = h(1, 0) = -c.x() * s.y();
    h(1, 2) = h(2, 1) = -c.y() * s.z();
    h(0, 2) = h(2, 0) = -c.z() * s.x();
    return w * w * h;
  }
};

class SchwarzP final : public Field {
 public:
  static constexpr double w = 2 * kPi;
  SchwarzP()
      : Field({"schwarz_p", "cos(wx) + cos(wy) + cos(wz), w = 2 pi (period 1), cut by [-1,1]^3", 0.0, Inside::Above,
               cube(1.0), false, std::nullopt}) {}
  double value(const Vector3d& p) const override {
    return std::cos(w * p.x()) + (std::cos(w * p.y()) + std::cos(w * p.z()));
  }
  void values_along_x(double x0, double dx, double y, double z, int n, double* out) const override {
    thread_local RowCache c;  // cos of w x per voxel
    if (c.stale(this, x0, dx, n, 1))
      for (int i = 0; i < n; ++i) c.v[i] = std::cos(w * (x0 + i * dx));
    const double cyz = std::cos(w * y) + std::cos(w * z);
    for (int i = 0; i < n; ++i) out[i] = c.v[i] + cyz;
  }
  Vector3d gradient(const Vector3d& p) const override { return -w * Vector3d((w * p).array().sin()); }
  Matrix3d hessian(const Vector3d& p) const override {
    return Matrix3d((-w * w * Vector3d((w * p).array().cos())).asDiagonal());
  }
};

// F = f(x, y) - z for a heightfield f given with its derivatives.
class Heightfield : public Field {
 public:
  struct Derivs {
    Eigen::Vector2d grad;
    Eigen::Matrix2d hess;
  };
  using Field::Field;
  virtual double height(double x, double y) const = 0;
  virtual Derivs eval(double x, double y) const = 0;  // derivatives of the height
  double value(const Vector3d& p) const override { return height(p.x(), p.y()) - p.z(); }
  Vector3d gradient(const Vector3d& p) const override {
    const Derivs d = eval(p.x(), p.y());
    return Vector3d(d.grad.x(), d.grad.y(), -1.0);
  }
  Matrix3d hessian(const Vector3d& p) const override {
    Matrix3d h = Matrix3d::Zero();
    h.topLeftCorner<2, 2>() = eval(p.x(), p.y()).hess;
    return h;
  }
};

class F1 final : public Heightfield {
 public:
  F1()
      : Heightfield({"f1", "z = 10 sin(r)/r, r = sqrt(x^2+y^2), as 10 sin(r)/r - z (Prantl et al. 4.1), solid below",
                     0.0, Inside::Above, make_box(Vector3d(-10, -10, -3.5), Vector3d(10, 10, 11.5)), false,
                     std::nullopt}) {}
  double height(double x, double y) const override { return 10.0 * sinc(std::sqrt(x * x + y * y)); }
  Derivs eval(double x, double y) const override {
    const double r = std::hypot(x, y);
    // s = sin(r)/r; s'/r; s'' = -s - 2 s'/r (from (r s)'' = -r s).
    const double s = sinc(r);
    const double ds_over_r = r < 1e-2 ? -1.0 / 3.0 + r * r / 30.0 - r * r * r * r / 840.0
                                      : (r * std::cos(r) - std::sin(r)) / (r * r * r);
    const Radial g{10.0 * s, 10.0 * ds_over_r, 10.0 * (-s - 2.0 * ds_over_r)};
    return {radial_gradient(g, x, y), radial_hessian(g, x, y)};
  }
};

class F2 final : public Heightfield {
 public:
  F2()
      : Heightfield({"f2", "z = sin(x)cos(y) + 0.1(x^2 - y^2), as f2 - z (Prantl et al. 4.1), solid below", 0.0,
                     Inside::Above, make_box(Vector3d(-10, -10, -12), Vector3d(10, 10, 12)), false, std::nullopt}) {}
  double height(double x, double y) const override { return std::sin(x) * std::cos(y) + 0.1 * (x * x - y * y); }
  Derivs eval(double x, double y) const override {
    const double sx = std::sin(x), cx = std::cos(x), sy = std::sin(y), cy = std::cos(y);
    Derivs d;
    d.grad = Eigen::Vector2d(cx * cy + 0.2 * x, -sx * sy - 0.2 * y);
    d.hess << -sx * cy + 0.2, -cx * sy, -cx * sy, -sx * cy - 0.2;
    return d;
  }
};

class MarschnerLobb final : public Field {
 public:
  static constexpr double fM = 6.0, alpha = 0.25;
  MarschnerLobb()
      : Field({"marschner_lobb",
               "(1 - sin(pi z/2) + a(1 + cos(2 pi fM cos(pi r/2)))) / (2(1+a)), fM = 6, a = 0.25, r = sqrt(x^2+y^2), "
               "cut by [-1,1]^3",
               0.5, Inside::Above, cube(1.0), false, std::nullopt}) {}
  static constexpr double c = 1.0 / (2.0 * (1.0 + alpha));
  // g(r) = cos(theta), theta = 2 pi fM cos(pi r / 2).
  static Radial radial(double r) {
    const double t = kPi * r / 2.0;
    const double theta = 2.0 * kPi * fM * std::cos(t);
    const double a = kPi * kPi * fM * std::sin(theta);  // g'(r) = a sin(t)
    Radial g;
    g.g = std::cos(theta);
    g.dg_over_r = a * (kPi / 2.0) * sinc(t);
    g.d2g = -std::pow(kPi, 4) * fM * fM * std::cos(theta) * std::sin(t) * std::sin(t) + a * (kPi / 2.0) * std::cos(t);
    return g;
  }
  double value(const Vector3d& p) const override {
    const double r = std::sqrt(p.x() * p.x() + p.y() * p.y());
    return c * (1.0 - std::sin(kPi * p.z() / 2.0) + alpha * (1.0 + radial(r).g));
  }
  Vector3d gradient(const Vector3d& p) const override {
    const Eigen::Vector2d gxy = radial_gradient(radial(std::hypot(p.x(), p.y())), p.x(), p.y());
    return c * Vector3d(alpha * gxy.x(), alpha * gxy.y(), -(kPi / 2.0) * std::cos(kPi * p.z() / 2.0));
  }
  Matrix3d hessian(const Vector3d& p) const override {
    Matrix3d h = Matrix3d::Zero();
    h.topLeftCorner<2, 2>() = alpha * radial_hessian(radial(std::hypot(p.x(), p.y())), p.x(), p.y());
    h(2, 2) = (kPi * kPi / 4.0) * std::sin(kPi * p.z() / 2.0);
    return c * h;
  }
};

class Hydrogen final : public Field {
 public:
  Hydrogen()
      : Field({"hydrogen",
               "3d_z2 orbital density (2z^2 - x^2 - y^2)^2 exp(-2r/3), Bohr radii, normalised to max 1 "
               "(at z = +-6); iso 0.05 gives two lobes and a ring",
               0.05, Inside::Above, make_box(Vector3d(-14.5, -14.5, -18), Vector3d(14.5, 14.5, 18)), true, 4}) {}
  // 1 / max density; the maximum is on the z axis at |z| = 6: 4 * 6^4 * e^-4.
  static double norm() { return 1.0 / (4.0 * 1296.0 * std::exp(-4.0)); }
  static double poly(const Vector3d& p) { return 2 * p.z() * p.z() - p.x() * p.x() - p.y() * p.y(); }
  double value(const Vector3d& p) const override {
    const double q = poly(p);
    return norm() * q * q * std::exp(-2.0 * p.norm() / 3.0);
  }
  // D = N q^2 E with E = exp(-2r/3).
  Vector3d gradient(const Vector3d& p) const override {
    const double r = p.norm(), q = poly(p), e = std::exp(-2.0 * r / 3.0);
    const Vector3d dq(-2 * p.x(), -2 * p.y(), 4 * p.z());
    const Vector3d de = r > 0 ? Vector3d(-2.0 / 3.0 * e * p / r) : Vector3d::Zero();
    return norm() * (2 * q * e * dq + q * q * de);
  }
  Matrix3d hessian(const Vector3d& p) const override {
    const double r = p.norm(), q = poly(p), e = std::exp(-2.0 * r / 3.0);
    const Vector3d dq(-2 * p.x(), -2 * p.y(), 4 * p.z());
    const Matrix3d hq = Vector3d(-2, -2, 4).asDiagonal();
    Vector3d de = Vector3d::Zero();
    Matrix3d he = Matrix3d::Zero();
    if (r > 0) {
      const Vector3d u = p / r;
      de = -2.0 / 3.0 * e * u;
      he = e * (4.0 / 9.0 * u * u.transpose() - 2.0 / (3.0 * r) * (Matrix3d::Identity() - u * u.transpose()));
    }
    const Matrix3d h = 2 * e * dq * dq.transpose() + 2 * q * e * hq +
                       2 * q * (dq * de.transpose() + de * dq.transpose()) + q * q * he;
    return norm() * h;
  }
};

class Buckyball final : public Field {
 public:
  static constexpr double bond = 1.42, sigma = 0.5, cutoff = 7 * sigma;
  Buckyball()
      : Field({"buckyball",
               "sum over the 60 C60 sites of exp(-d^2/(2 s^2)), bond 1.42 A, s = 0.5 A, cut off at 7 s; "
               "iso 0.5: a cage of tubes along the 90 bonds (genus 31)",
               0.5, Inside::Above, cube(4.6), true, -60}),
        sites_(c60_sites(bond)) {}
  // exp(-t / (2 sigma^2)) for a squared distance t. A site's weight is g(dx^2) * g(dy^2 + dz^2), the
  // Gaussian factored so that rows of voxels can reuse the x factor (values_along_x).
  static double gauss(double t) { return std::exp(-t / (2 * sigma * sigma)); }
  // Calls f(d, weight) for every site within the cutoff, in site order, d = p - site.
  template <class F>
  void for_near_sites(const Vector3d& p, F&& f) const {
    for (const Vector3d& s : sites_) {
      const Vector3d d = p - s;
      const double perp2 = d.y() * d.y() + d.z() * d.z();
      if (d.x() * d.x() + perp2 < cutoff * cutoff) f(d, gauss(d.x() * d.x()) * gauss(perp2));
    }
  }
  double value(const Vector3d& p) const override {
    double v = 0;
    for_near_sites(p, [&](const Vector3d&, double w) { v += w; });
    return v;
  }
  // The same sums, bit for bit, visiting for each site only the voxels of the row within its cutoff.
  // The x factors depend on the row's x positions only: a per-thread table serves every row of a grid.
  void values_along_x(double x0, double dx, double y, double z, int n, double* out) const override {
    struct Table {
      const Buckyball* owner = nullptr;
      double x0 = 0, dx = 0;
      int n = -1;
      std::vector<double> g;  // g[site * n + i] = gauss(((x0 + i dx) - site.x)^2)
    };
    thread_local Table table;
    if (table.owner != this || table.x0 != x0 || table.dx != dx || table.n != n) {
      table.owner = this;
      table.x0 = x0;
      table.dx = dx;
      table.n = n;
      table.g.resize(sites_.size() * n);
      for (std::size_t k = 0; k < sites_.size(); ++k)
        for (int i = 0; i < n; ++i) {
          const double ddx = (x0 + i * dx) - sites_[k].x();
          table.g[k * n + i] = gauss(ddx * ddx);
        }
    }
    std::fill(out, out + n, 0.0);
    for (std::size_t k = 0; k < sites_.size(); ++k) {
      const Vector3d& s = sites_[k];
      const double dy = y - s.y(), dz = z - s.z(), perp2 = dy * dy + dz * dz;
      if (perp2 >= cutoff * cutoff) continue;
      const double g_perp = gauss(perp2);
      const double half = std::sqrt(cutoff * cutoff - perp2);
      // Candidate voxels (one extra on each side), then the exact test of for_near_sites.
      const int lo = std::max(0, static_cast<int>(std::floor((s.x() - half - x0) / dx)) - 1);
      const int hi = std::min(n - 1, static_cast<int>(std::ceil((s.x() + half - x0) / dx)) + 1);
      for (int i = lo; i <= hi; ++i) {
        const double ddx = (x0 + i * dx) - s.x();
        if (ddx * ddx + perp2 < cutoff * cutoff) out[i] += table.g[k * n + i] * g_perp;
      }
    }
  }
  Vector3d gradient(const Vector3d& p) const override {
    Vector3d g = Vector3d::Zero();
    for_near_sites(p, [&](const Vector3d& d, double w) { g -= w * d / (sigma * sigma); });
    return g;
  }
  Matrix3d hessian(const Vector3d& p) const override {
    const double s2 = sigma * sigma;
    Matrix3d h = Matrix3d::Zero();
    for_near_sites(p, [&](const Vector3d& d, double w) {
      h += w * (d * d.transpose() / (s2 * s2) - Matrix3d::Identity() / s2);
    });
    return h;
  }

 private:
  std::vector<Vector3d> sites_;
};

using Maker = std::function<std::unique_ptr<Field>()>;
const std::vector<std::pair<std::string, Maker>>& catalogue() {
  static const std::vector<std::pair<std::string, Maker>> entries = {
      {"sphere", [] { return std::make_unique<Sphere>(); }},
      {"torus", [] { return std::make_unique<Torus>(); }},
      {"ellipsoid", [] { return std::make_unique<Ellipsoid>(); }},
      {"gyroid", [] { return std::make_unique<Gyroid>(); }},
      {"schwarz_p", [] { return std::make_unique<SchwarzP>(); }},
      {"f1", [] { return std::make_unique<F1>(); }},
      {"f2", [] { return std::make_unique<F2>(); }},
      {"marschner_lobb", [] { return std::make_unique<MarschnerLobb>(); }},
      {"hydrogen", [] { return std::make_unique<Hydrogen>(); }},
      {"buckyball", [] { return std::make_unique<Buckyball>(); }},
  };
  return entries;
}

}  // namespace

void Field::values_along_x(double x0, double dx, double y, double z, int n, double* out) const {
  for (int i = 0; i < n; ++i) out[i] = value(Vector3d(x0 + i * dx, y, z));
}

std::vector<std::string> field_names() {
  std::vector<std::string> names;
  for (const auto& e : catalogue()) names.push_back(e.first);
  return names;
}

std::unique_ptr<Field> make_ellipsoid(double a, double b, double c) {
  if (!(a > 0 && b > 0 && c > 0 && std::isfinite(a) && std::isfinite(b) && std::isfinite(c)))
    throw Error("datasets: ellipsoid semi-axes must be positive and finite");
  return std::make_unique<Ellipsoid>(a, b, c, "ellipsoid_abc");
}

std::unique_ptr<Field> make_field(const std::string& name) {
  for (const auto& e : catalogue())
    if (e.first == name) return e.second();
  std::string known;
  for (const auto& e : catalogue()) known += (known.empty() ? "" : ", ") + e.first;
  throw Error("unknown dataset '" + name + "' (known: " + known + ")");
}

}  // namespace isocurv::datasets
