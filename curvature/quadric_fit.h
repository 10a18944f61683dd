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
/// derived arrays, Area, Boundary and Unreliable; no dcurv. Each neighbour is a sample of the
/// normal curvature kappa_i = 2 z_i / (x_i^2 + y_i^2); one beyond the one rule's bound (2 / mean
/// edge, detail::keep_sample: marching cubes' tiny edges) is left out. A vertex with fewer than 3
/// samples left, samples that do not determine the three unknowns (collinear, coincident), or a
/// fit whose max(|k1|, |k2|) exceeds twice its largest |kappa_i| (directions nearly on two lines:
/// detail::determined_by_samples) is flagged Unreliable with zero curvature. Never NaN or Inf;
/// never max(|k1|, |k2|) above 4 / mean edge.
/// @throw isocurv::Error for invalid input (check_input)
CurvatureField estimate_quadric_fit_reference(const Mesh& mesh, const Options& options = {});

}  // namespace isocurv::curvature
