#pragma once
// Goldfeather and Interrante 2004's cubic fit with normals: a comparison estimator, double only.
// Tested in tests/curvature/comparison_estimators_test.cpp.
#include "core/mesh.h"
#include "curvature/curvature_field.h"
#include "curvature/options.h"

namespace isocurv::curvature {

/// Per vertex P, in its tangent frame (u, v, n) over its distinct 1-ring q_i with normals m_i:
/// least squares (QR) for z = A/2 x^2 + B xy + C/2 y^2 + D x^3 + E x^2 y + F x y^2 + G y^3 with
/// three rows per neighbour, the position z_i and the normal's slopes
/// -m_u/m_n = A x + B y + 3D x^2 + 2E xy + F y^2 and -m_v/m_n = B x + C y + E x^2 + 2F xy + 3G y^2
/// (a neighbour whose normal is not within 84 degrees of n, m_n < 0.1, gives its position row
/// only); then II = -[[A, B], [B, C]]. Normals as estimate_reference. Fills k1, k2, dir1, dir2, H,
/// K, the derived arrays, Area, Boundary and Unreliable; no dcurv. A vertex with fewer than 3
/// neighbours or a rank-deficient system (7 unknowns) is flagged Unreliable with zero curvature.
/// Never NaN or Inf.
/// @throw isocurv::Error for invalid input (check_input)
CurvatureField estimate_cubic_fit_reference(const Mesh& mesh, const Options& options = {});

}  // namespace isocurv::curvature
