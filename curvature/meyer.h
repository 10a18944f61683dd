#pragma once
// Meyer, Desbrun, Schroeder and Barr 2003's discrete operators: cotangent mean curvature and
// angle-deficit Gaussian curvature over mixed Voronoi areas. A comparison estimator, double only.
// Tested in tests/curvature/comparison_estimators_test.cpp.
#include "core/mesh.h"
#include "curvature/curvature_field.h"
#include "curvature/options.h"

namespace isocurv::curvature {

/// Per vertex i with mixed area A (the "Area" array) over its triangles:
///   H = |sum_j (cot alpha_ij + cot beta_ij) (p_i - p_j)| / (4 A), signed + where that vector
///       points along the vertex normal (outward: + on a sphere);
///   K = (2 pi - sum of the corner angles at i) / A, with pi instead of 2 pi on the boundary;
///   k1,2 = H +- sqrt(max(0, H^2 - K)).
/// The normal (for the sign and the Normals array only) as estimate_reference. No directions and
/// no derivative: dir1, dir2 and dcurv are left empty. Fills H, K, k1, k2, the derived arrays,
/// Area, Boundary and Unreliable: 1 on a vertex with zero area (zero curvature) and on boundary
/// vertices, whose one-sided rings bias both formulas (their values are kept). Never NaN or Inf.
/// vtkCurvatures' Gaussian curvature is the same angle deficit over a third of the triangles'
/// areas, and its mean curvature sums edge length x dihedral angle instead of cotangents.
/// @throw isocurv::Error for invalid input (check_input)
CurvatureField estimate_meyer_reference(const Mesh& mesh, const Options& options = {});

}  // namespace isocurv::curvature
