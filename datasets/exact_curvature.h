#pragma once
// The curvature oracle: exact principal curvatures of an analytic field's isosurface.
#include <Eigen/Core>

#include "datasets/field.h"

namespace isocurv::datasets {

/// Curvature of a surface at one point (DESIGN.md conventions). Units: 1/world length.
struct SurfaceCurvature {
  double k1 = 0, k2 = 0;  ///< principal curvatures, k1 >= k2, positive where the surface bends away
                          ///< from the outward normal (a solid sphere of radius R: +1/R)
  Eigen::Vector3d dir1 = Eigen::Vector3d::Zero();    ///< unit tangent direction of k1
  Eigen::Vector3d dir2 = Eigen::Vector3d::Zero();    ///< unit tangent direction of k2 = normal x dir1
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  ///< unit normal pointing out of the object
  double H = 0;  ///< mean curvature (k1 + k2) / 2
  double K = 0;  ///< Gaussian curvature k1 * k2
};

/// Exact curvature of the level set of `field` through p (the isosurface when p lies on it; use
/// project_to_surface for points that only approximate it, e.g. mesh vertices). From the gradient g
/// and Hessian Hs: n = +-g/|g| (outward per field.inside()), shape operator S = +-P Hs P / |g| with
/// P = I - n n^T, eigen-decomposed on the tangent plane. For umbilics (k1 == k2) dir1 is an
/// arbitrary tangent. Throws isocurv::Error where the gradient vanishes.
SurfaceCurvature exact_curvature(const Field& field, const Eigen::Vector3d& p);

/// Moves p onto the isosurface: Newton steps along the line through p in the gradient direction
/// (near the surface this approximates the nearest surface point), falling back to Newton steps
/// along the local gradient where that line grazes the level sets. Converged when a step is below
/// 1e-12 of the field's box diagonal; steps are capped at 0.1 of it. Throws isocurv::Error where the
/// gradient vanishes or after `max_iterations` steps without convergence.
Eigen::Vector3d project_to_surface(const Field& field, const Eigen::Vector3d& p, int max_iterations = 100);

}  // namespace isocurv::datasets
