#pragma once
// Normal curvature sampled along the 1-ring edges (Batagelo & Wu eq. 12, after Chen and Schmitt
// and Meyer et al.): a comparison estimator, double only.
// Tested in tests/curvature/comparison_estimators_test.cpp.
#include "core/mesh.h"
#include "curvature/curvature_field.h"
#include "curvature/options.h"

namespace isocurv::curvature {

/// Per vertex P with unit normal n over its distinct 1-ring q_i: the normal curvature of the
/// circle through P and q_i tangent to the plane of n, kappa_i = 2 (P - q_i).n / |P - q_i|^2
/// (outward normals: +1/R on a sphere), and t_i the unit projection of q_i - P on P's tangent
/// frame (u, v); least squares (QR) for kappa_i = e t_u^2 + 2 f t_u t_v + g t_v^2 (Euler's
/// formula), II = [[e, f], [f, g]]. Normals as estimate_reference. Fills k1, k2, dir1, dir2, H, K,
/// the derived arrays, Area, Boundary and Unreliable; no dcurv. A vertex with fewer than 3
/// neighbours, or whose edge directions do not span three distinct lines, is flagged Unreliable
/// with zero curvature. Never NaN or Inf.
/// @throw isocurv::Error for invalid input (check_input)
CurvatureField estimate_normal_sampling_reference(const Mesh& mesh, const Options& options = {});

}  // namespace isocurv::curvature
