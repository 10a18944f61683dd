#include "datasets/exact_curvature.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.h"

namespace isocurv::datasets {
namespace {

std::string where(const Field& field, const Eigen::Vector3d& p) {
  std::ostringstream s;
  s << field.name() << " at (" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return s.str();
}

// Any unit vector perpendicular to the unit vector n.
Eigen::Vector3d perpendicular(const Eigen::Vector3d& n) {
  const Eigen::Vector3d a = std::abs(n.x()) < 0.6 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return (a - a.dot(n) * n).normalized();
}

}  // namespace

SurfaceCurvature exact_curvature(const Field& field, const Eigen::Vector3d& p) {
  const Eigen::Vector3d g = field.gradient(p);
  const double glen = g.norm();
  if (!(glen > 0) || !std::isfinite(glen)) throw Error(where(field, p), "zero gradient, curvature undefined");
  // The gradient points towards larger values: into the object when it is above the isovalue.
  const double sign = field.inside() == volume::Inside::Above ? -1.0 : 1.0;
  SurfaceCurvature c;
  c.normal = sign * g / glen;
  // Shape operator dn/dp restricted to the tangent plane, in the tangent basis (t1, t2).
  const Eigen::Vector3d t1 = perpendicular(c.normal), t2 = c.normal.cross(t1);
  const Eigen::Matrix3d hs = field.hessian(p);
  Eigen::Matrix2d s;
  s(0, 0) = t1.dot(hs * t1);
  s(1, 1) = t2.dot(hs * t2);
  s(0, 1) = s(1, 0) = 0.5 * (t1.dot(hs * t2) + t2.dot(hs * t1));
  s *= sign / glen;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(s);  // ascending eigenvalues
  c.k1 = eig.eigenvalues()(1);
  c.k2 = eig.eigenvalues()(0);
  const Eigen::Vector2d v1 = eig.eigenvectors().col(1);
  c.dir1 = (v1.x() * t1 + v1.y() * t2).normalized();
  c.dir2 = c.normal.cross(c.dir1);
  c.H = 0.5 * (c.k1 + c.k2);
  c.K = c.k1 * c.k2;
  return c;
}

Eigen::Vector3d project_to_surface(const Field& field, const Eigen::Vector3d& p, int max_iterations) {
  const double tolerance = 1e-12 * field.box().diagonal().norm();
  const double max_step = 0.1 * field.box().diagonal().norm();
  const auto clamp = [&](double t) { return std::max(-max_step, std::min(max_step, t)); };
  const Eigen::Vector3d g0 = field.gradient(p);
  if (!(g0.squaredNorm() > 0) || !std::isfinite(g0.squaredNorm()))
    throw Error(where(field, p), "zero gradient while projecting onto the surface");
  // First along the line through p in the gradient direction (1-D Newton): for points near the
  // surface this lands close to the nearest surface point even where the field is strongly curved.
  const Eigen::Vector3d n0 = g0.normalized();
  Eigen::Vector3d x = p;
  int i = 0;
  for (; i < max_iterations; ++i) {
    const Eigen::Vector3d g = field.gradient(x);
    const double slope = g.dot(n0);
    if (!(std::abs(slope) > 0.1 * g.norm())) break;  // the line grazes a level set: fall back
    const double t = clamp((field.value(x) - field.isovalue()) / slope);
    x -= t * n0;
    if (std::abs(t) <= tolerance) return x;
  }
  // Otherwise Newton steps along the local gradient.
  for (; i < max_iterations; ++i) {
    const Eigen::Vector3d g = field.gradient(x);
    const double g2 = g.squaredNorm();
    if (!(g2 > 0) || !std::isfinite(g2)) throw Error(where(field, x), "zero gradient while projecting onto the surface");
    const double t = clamp((field.value(x) - field.isovalue()) / std::sqrt(g2));
    x -= t * g / std::sqrt(g2);
    if (std::abs(t) <= tolerance) return x;
  }
  throw Error(where(field, p), "projection onto the surface did not converge");
}

}  // namespace isocurv::datasets
