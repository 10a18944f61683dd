#pragma once
// Batagelo & Wu 2007 ("Estimating curvatures and their derivatives on meshes of arbitrary
// topology from sampling directions"): the one-pass per-vertex estimator, double precision.
// Tested in tests/curvature/batagelo_test.cpp, tests/curvature/estimator_bad_input_test.cpp.
#include "core/cl_device.h"
#include "core/mesh.h"
#include "curvature/curvature_field.h"
#include "curvature/estimate.h"
#include "curvature/options.h"

namespace isocurv::curvature {

/// Per-vertex curvature and curvature derivative of `mesh` from each vertex's 1-ring alone, with
/// no pass over the faces and no use of the winding order (single-threaded, double precision,
/// results stored as float). Per vertex P with unit normal n_P and tangent frame (U, V):
///  1. Normals: as estimate_reference (options.vertex_normals, else the mesh faces weighted per
///     options.normal_weights).
///  2. Tensor (section 4.1): for each distinct 1-ring neighbour q, x = (q - P) and
///     y = (n_q - n_P), both projected on (U, V); least squares on II x = y for the symmetric
///     II = [[e, f], [f, g]] (normal equations, LDL^T with the project's pivot tolerance), each
///     neighbour weighted 1 or 1 / |x|^2 (options.batagelo_weights; x projected).
///  3. Directions: II diagonalised, k1 >= k2, (dir1, dir2, normal) right-handed.
///  4. Derivative (section 4.2, in the corrected full-tensor form of SEEDS-SPEC 3.3; the printed
///     eq. 15-16 do not converge): for each neighbour, the difference of q's second fundamental
///     form (its principal frame rotated into P's plane) from P's, along (q - P) in P's principal
///     frame; least squares for C = (C111, C112, C122, C222), the project's dcurv convention
///     (e1 = dir1, the maximum direction).
/// Area (Meyer's mixed area) and Boundary are filled as by estimate_reference, for reporting;
/// neither enters the estimate. A vertex whose neighbours do not span the tangent plane (fewer
/// than two non-collinear ones, an isolated vertex, a zero normal) gets zero curvature and
/// derivative and Unreliable = 1; a vertex whose derivative system is singular gets dcurv zero
/// (and Unreliable = 1). Never returns NaN or Inf. Throws isocurv::Error for invalid input
/// (check_input).
CurvatureField estimate_batagelo_reference(const Mesh& mesh, const Options& options = {});

/// The same on `device` in float (curvature/mesh_estimator_kernels.cl): normals, areas and
/// boundary flags by the Rusinkiewicz path's kernels, then one kernel per vertex for the tensor
/// and directions (timings->tensor; directions stays 0) and one for the derivative. Matches the
/// reference to float precision; deterministic (bit-identical run to run on one device). An empty
/// mesh gives an empty field. Buffers are kept per device between calls (calls are serialised).
/// @param timings when given, receives the step times (the queue is drained after each step)
/// @throw isocurv::Error for invalid input (check_input) or an OpenCL failure
CurvatureField estimate_batagelo(const Mesh& mesh, Device& device, const Options& options = {},
                                 Timings* timings = nullptr);

}  // namespace isocurv::curvature
