#pragma once
// Connectivity the neighbourhood features walk: vertex -> vertex and vertex ->
// triangle lists (compressed rows), and the vertices on open boundaries.
#include <cstdint>
#include <vector>

#include "core/mesh.h"

namespace isocurv::features::detail {

struct MeshGraph {
  std::vector<std::uint32_t> vv_start,
      vv; ///< neighbours of v: vv[vv_start[v] .. vv_start[v+1])
  std::vector<std::uint32_t> vt_start,
      vt; ///< triangles of v:  vt[vt_start[v] .. vt_start[v+1])
  std::vector<std::uint8_t>
      on_boundary; ///< 1 on a vertex of an edge used by one triangle
};

/// Builds the graph; triangles with a repeated index are left out.
/// Deterministic (sorted rows).
MeshGraph build_mesh_graph(const Mesh &mesh);

} // namespace isocurv::features::detail
