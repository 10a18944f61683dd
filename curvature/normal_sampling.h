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
/// the derived arrays, Area, Boundary and Unreliable; no dcurv. A sample beyond the one rule's
/// bound (2 / mean edge, detail::keep_sample: marching cubes' tiny edges), or from a neighbour
/// straight above P, is left out. A vertex with fewer than 3 samples left, whose sample
/// directions do not span three distinct lines, or whose fit's max(|k1|, |k2|) exceeds twice
/// its largest |kappa_i| (directions nearly on two lines: detail::determined_by_samples) is
/// flagged Unreliable with zero curvature. Never NaN or Inf; never max(|k1|, |k2|) above
/// 4 / mean edge.
/// @throw isocurv::Error for invalid input (check_input)
CurvatureField estimate_normal_sampling_reference(const Mesh& mesh, const Options& options = {});

}  // namespace isocurv::curvature
