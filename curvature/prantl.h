#pragma once
// Prantl, Vasa and Kolingerova 2017 ("Fast screen space curvature estimation on GPU", section
// 3.1) in object space: a shape operator per triangle from its edges and vertex normals, averaged
// into the vertices. Double precision.
// Tested in tests/curvature/prantl_test.cpp, tests/curvature/estimator_bad_input_test.cpp.
#include <array>

#include "core/cl_device.h"
#include "core/mesh.h"
#include "curvature/curvature_field.h"
#include "curvature/estimate.h"
#include "curvature/options.h"

namespace isocurv::curvature {

/// How the per-triangle H and K are averaged into a vertex.
enum class PrantlAveraging {
  area,     ///< weighted by the triangle's area (the default)
  uniform,  ///< plain mean over the vertex's usable triangles
};

/// The shape operator [[L, M], [M, N]] of one triangle in its frame Tu = (V2 - V1)/|V2 - V1|,
/// Tv = m x Tu with m the unit face normal (right-handed; the paper's Tv = Tu x n only flips M).
struct TriangleShape {
  double L = 0, M = 0, N = 0;
  double H() const { return (L + N) / 2; }    ///< mean curvature (outward normals: sphere +1/R)
  double K() const { return L * N - M * M; }  ///< Gaussian curvature
};

/// Solves the 3-edge (edges = 3) or 2-edge (edges = 2) least-squares system of eq. 9-11,
/// [[L, M], [M, N]] (u_i, v_i) = (a_i, b_i) with e_i = V_i - V_{i+1} and dN_i = n_i - n_{i+1} in
/// the triangle's frame, by the closed-form inverse of B = A^T A (eq. 12-13 with the corrected
/// (1,1) entry r(p + r) - q^2 and factor 1/det B; SEEDS-SPEC 4.2). `p` are the corners (world
/// units), `n` their unit normals. False (shape untouched) for a degenerate triangle:
/// pr - q^2 <= kPivotTolerance (p + r)^2, with p = sum u^2, q = sum uv, r = sum v^2.
/// @throw nothing
bool prantl_triangle(const std::array<std::array<double, 3>, 3>& p,
                     const std::array<std::array<double, 3>, 3>& n, int edges,
                     TriangleShape& shape);

/// Per-vertex curvature of `mesh`: each triangle's shape operator (prantl_triangle with 3 or 2
/// edges), its H and K averaged over the vertex's triangles per `averaging`, then
/// k1,2 = H +- sqrt(max(0, H^2 - K)). Normals as estimate_reference (options.vertex_normals, else
/// the faces weighted per options.normal_weights). The method gives no principal directions and
/// no derivative: dir1, dir2 and dcurv are left empty. Area (Meyer's mixed area, for reporting)
/// and Boundary are filled. A vertex with no usable triangle gets zero curvature and
/// Unreliable = 1. Never returns NaN or Inf.
/// @param edges 3 (eq. 9-11) or 2 (eq. 17)
/// @throw isocurv::Error for invalid input (check_input) or edges other than 2 or 3
CurvatureField estimate_prantl_reference(const Mesh& mesh, const Options& options = {},
                                         int edges = 3,
                                         PrantlAveraging averaging = PrantlAveraging::area);

/// The same on `device` in float (curvature/mesh_estimator_kernels.cl): normals, areas and
/// boundary flags by the Rusinkiewicz path's kernels, one kernel per face (timings->tensor) and
/// one per vertex (timings->directions). Matches the reference to float precision;
/// deterministic. An empty mesh gives an empty field. Buffers are kept per device between calls.
/// @param timings when given, receives the step times (the queue is drained after each step)
/// @throw isocurv::Error for invalid input, edges other than 2 or 3, or an OpenCL failure
CurvatureField estimate_prantl(const Mesh& mesh, Device& device, const Options& options = {},
                               int edges = 3, PrantlAveraging averaging = PrantlAveraging::area,
                               Timings* timings = nullptr);

}  // namespace isocurv::curvature
