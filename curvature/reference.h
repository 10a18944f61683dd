#pragma once
// The specification of the curvature stage: Rusinkiewicz's estimator, as Griffin et al.
// parallelise it, written plainly in double precision. The OpenCL kernels are tested against it.
// Tested in tests/curvature/kernel_vs_reference_test.cpp, tests/curvature/batagelo_test.cpp.
#include "core/mesh.h"
#include "curvature/curvature_field.h"
#include "curvature/options.h"

namespace isocurv::curvature {

/// Per-vertex curvature of `mesh` (single-threaded, double precision, results stored as float).
///  1. Normals: sum over the vertex's triangles of the face normal, weighted per
///     options.normal_weights (Max by default), normalised; or options.vertex_normals.
///  2. Areas: Meyer et al.'s mixed Voronoi corner areas; a vertex's Area is their sum.
///  3. Basis: an orthonormal tangent frame per vertex from its normal alone (Duff et al. 2017).
///  4. Tensor: per triangle, the second fundamental form in the triangle's frame by least squares
///     (LDL^T) on the normal differences along its three edges; rotated into each corner's vertex
///     frame and averaged with the corner areas as weights.
///  5. Directions: the 2x2 tensor diagonalised (one Jacobi rotation): k1 >= k2, dir1, dir2 with
///     (dir1, dir2, normal) right-handed.
///  6. Derivative: per triangle, the curvature-derivative tensor by least squares on the tensor
///     differences along the edges, rotated into each vertex's principal frame, averaged as in 4.
/// Boundary is 1 on vertices of an edge used by one triangle only. Triangles with a repeated
/// index or (nearly) collinear corners (tolerances.h) contribute nothing; a vertex with no usable
/// triangle gets a zero normal (unless one is given), zero curvature and zero area. Never returns
/// NaN or Inf. Throws isocurv::Error for invalid input (see check_input).
CurvatureField estimate_reference(const Mesh& mesh, const Options& options = {});

}  // namespace isocurv::curvature
