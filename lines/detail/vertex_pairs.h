#pragma once
// lines::detail::VertexPairs: what the smoothing passes average over, per vertex.
#include <cstdint>
#include <vector>

#include "core/mesh.h"

namespace isocurv::lines::detail {

/// Compressed rows, one per vertex: for each triangle of vertex v, in triangle order, the pair of
/// its two other vertices (the corner's next and previous), pairs[offsets[v] .. offsets[v + 1]).
/// Triangles with a repeated vertex index are left out. The smoothing's mean over a vertex's
/// 1-ring (reference.cpp: the vertex and every corner's two other vertices) reads these rows.
struct VertexPairs {
  std::vector<std::uint32_t> offsets;               ///< vertex_count + 1 entries
  std::vector<std::uint32_t> pairs;                 ///< 2 * offsets.back() entries: next, previous
  std::vector<std::vector<std::uint32_t>> cursors;  ///< the build's scratch, kept for the next
};

/// Builds the rows of `mesh` into `out` (reusing its storage) by a counting sort over the
/// triangles, in parallel over blocks of triangles. The result does not depend on the number of
/// threads. Assumes the triangles' indices are below the vertex count (lines::check_input).
void build_vertex_pairs(const Mesh& mesh, VertexPairs& out);

}  // namespace isocurv::lines::detail
