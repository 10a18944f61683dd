#pragma once
// Taubin-style quadric fit (Batagelo & Wu section 3.1): a comparison estimator, double only.
// Tested in tests/curvature/comparison_estimators_test.cpp.
#include "core/mesh.h"
#include "curvature/curvature_field.h"
#include "curvature/options.h"

namespace isocurv::curvature {

/// Per vertex P, in its tangent frame (u, v, n) over its distinct 1-ring q_i: least squares (QR)
/// for z_i = (a x_i^2 + 2 b x_i y_i + c y_i^2) / 2 with (x, y, z) = (q_i - P) in the frame, then
/// II = -[[a, b], [b, c]] (outward normals: a sphere of radius R gives a = -1/R, k = +1/R).
/// Normals (which fix the frame only) as estimate_reference. Fills k1, k2, dir1, dir2, H, K, the
/// derived arrays, Area, Boundary and Unreliable; no dcurv. A vertex with fewer than 3
/// neighbours or neighbours that do not determine the three unknowns (collinear, coincident) is
/// flagged Unreliable with zero curvature. Never NaN or Inf.
/// @throw isocurv::Error for invalid input (check_input)
CurvatureField estimate_quadric_fit_reference(const Mesh& mesh, const Options& options = {});

}  // namespace isocurv::curvature
