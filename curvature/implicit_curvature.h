#pragma once
// Curvature of an implicit surface at one point from the field's derivatives there (the volume
// estimator's per-vertex step; double precision, the specification of volume_kernels.cl).
// Tested through the volume estimator: tests/curvature/volume_estimate_test.cpp (closed forms).
#include <Eigen/Core>
#include <array>

#include "volume/gaussian_jet.h"
#include "volume/volume.h"

namespace isocurv::curvature {

/// Curvature of the level set through a point of a field with world-space jet `jet` (gradient g,
/// Hessian Hs, third derivatives T). Outward unit normal n = s g / |g| with s = -1 for
/// Inside::Above (the object has the larger values) and +1 for Inside::Below; shape operator
/// S = s P Hs P / |g| (P = I - n n^T), so a solid sphere of radius R has k1 = k2 = +1/R either way.
/// dir1, dir2 come from (u, v), the tangent basis of n (Duff et al. 2017), rotated by the angle
/// that diagonalises S; (dir1, dir2, n) is right-handed. dcurv = (C111, C112, C122, C222) in that
/// frame, the derivative of the second fundamental form
/// C(a, b, c) = s/|g| [T(a,b,c) - ((a.Hs c)(m.Hs b) + (b.Hs c)(m.Hs a) + (a.Hs b)(m.Hs c)) / |g|]
/// with m = g / |g| (a, b, c tangent). A zero or non-finite gradient gives every value zero and
/// gradient_norm 0.
struct PointCurvature {
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  double k1 = 0, k2 = 0;
  Eigen::Vector3d dir1 = Eigen::Vector3d::Zero(), dir2 = Eigen::Vector3d::Zero();
  std::array<double, 4> dcurv{};
  double gradient_norm = 0;  ///< |g|, world units of value per length
};

PointCurvature implicit_curvature(const volume::Jet& jet, volume::Inside inside);

}  // namespace isocurv::curvature
