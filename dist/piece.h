#pragma once
// One rank's piece of a distributed isosurface: the triangles its slab owns, one ring of ghost
// triangles around them (owned by neighbouring ranks, marked so ParaView and the mesh estimators
// know), and every vertex they use with its global id (the edge key: the same on every rank and
// at every rank count) and whether this piece owns it.
//
// Ownership, so that nothing is counted twice or lost:
//   a triangle belongs to the slab of the lowest z among its vertices' edge keys (the cell it was
//   made in; a snapped vertex keeps one of its group's keys, the same wherever it is made);
//   a vertex, and an edge, to the lowest rank owning a triangle around it.
// Each rank decides this alone from its local extraction, which reaches kExtractGhostCells past its
// slab so that every triangle around its vertices is there exactly as the whole extraction makes it.
// Tested in tests/dist/test_distributed.cpp.
#include <cstdint>
#include <vector>

#include "core/mesh.h"
#include "dist/slabs.h"

namespace isocurv::dist {

/// vtkGhostType's flags (vtkDataSetAttributes::DUPLICATEPOINT / DUPLICATECELL).
constexpr std::uint8_t kDuplicate = 1;

struct Piece {
  int rank = 0;
  /// The piece's vertices in increasing global id, and its triangles: the owned ones first (in
  /// increasing order of their sorted global ids), then the ghost ring.
  Mesh mesh;
  std::vector<std::int64_t> global_ids;    ///< per vertex: its edge key (vtkGlobalPointIds)
  std::vector<std::uint8_t> point_ghost;   ///< per vertex: kDuplicate where another rank owns it
  std::vector<std::uint8_t> cell_ghost;    ///< per triangle: kDuplicate for the ghost ring
  std::vector<int> triangle_owner;         ///< per triangle: the rank owning it
  std::vector<int> vertex_owner;           ///< per vertex: the rank owning it
  std::vector<std::uint32_t> local_vertex; ///< per vertex: its index in the local extraction
  std::size_t owned_triangles = 0;         ///< the first triangles, owned by this rank
};

/// Per triangle of the local extraction `local` (edge keys filled): the rank owning it, the slab
/// of the lowest z among its vertices' edge keys. @throw Error when `local` has no edge keys.
std::vector<int> triangle_owners(const Mesh& local, const Slabs& slabs);

/// Cuts rank `rank`'s piece out of its local extraction `local` (whose edge_keys are filled:
/// mc::Options::keep_edge_keys, and which covers Slabs::extract_range(rank, kExtractGhostCells)).
/// @throw Error when `local` has no edge keys.
Piece cut_piece(const Mesh& local, const Slabs& slabs, int rank);

/// The per-vertex values `values` of the local extraction, carried onto the piece's vertices.
template <class T, class A>
std::vector<T> on_piece(const Piece& p, const std::vector<T, A>& values) {
  std::vector<T> out(p.local_vertex.size());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = values[p.local_vertex[i]];
  return out;
}

}  // namespace isocurv::dist
