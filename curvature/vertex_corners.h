#pragma once
// The vertex -> corner adjacency that lets per-vertex kernels sum their triangles in a fixed order.
// Tested in tests/lines/test_vertex_pairs.cpp.
#include <cstdint>
#include <vector>

#include "core/mesh.h"

namespace isocurv::curvature {

/// Fans of up to this many corners are checked for boundary edges in registers (the kernels'
/// vertex_boundary); larger ones go to vertex_boundary_large. Shared by every mesh-estimator path.
inline constexpr std::uint32_t kMaxFan = 8;

/// Compressed rows: the corners (3 * triangle + j) of vertex v are
/// corners[offsets[v] .. offsets[v + 1]), in increasing order. Triangles with a repeated vertex
/// index are left out (they have no area, normal or edges to contribute).
struct VertexCorners {
  std::vector<std::uint32_t> offsets;  ///< vertex_count + 1 entries
  std::vector<std::uint32_t> corners;  ///< offsets.back() entries
};

/// Builds the adjacency of `mesh` into `out` (reusing its storage) by a counting sort over the
/// corners: linear time, deterministic. Assumes check_input(mesh) passed.
void build_vertex_corners(const Mesh& mesh, VertexCorners& out);

}  // namespace isocurv::curvature
