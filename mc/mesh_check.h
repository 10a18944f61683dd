#pragma once
// Fusion and topology checks any user can run on any mesh (isocurv check).
// Tested in tests/mc/mesh_check_test.cpp, tests/mc/extract_test.cpp.
#include <array>
#include <cstdint>
#include <vector>

#include "core/mesh.h"

namespace isocurv::mc {

using VertexPair = std::array<std::uint32_t, 2>;

/// A connected component (over triangles) and its orientation.
struct ComponentCheck {
  std::size_t triangles = 0;
  std::uint32_t first_vertex = 0;  ///< its lowest vertex id, to find it again
  /// Every edge of the component is used as often in one direction as in the other (so it is
  /// closed and consistently oriented, and its signed volume does not depend on the origin).
  bool closed = false;
  double signed_volume = 0;  ///< sum of a . (b x c) / 6 over its triangles; > 0: faces outward
};

struct MeshCheck {
  std::size_t vertices = 0, triangles = 0;
  std::size_t duplicate_vertices = 0;     ///< vertices at exactly the position of an earlier one
  /// With vertex labels: vertices at the position of an earlier vertex of another label only (the
  /// coincident walls of touching labels, each label's surface closed on its own): not problems,
  /// and not counted in duplicate_vertices.
  std::size_t label_wall_vertices = 0;
  std::size_t unreferenced_vertices = 0;  ///< vertices no triangle uses
  std::size_t degenerate_triangles = 0;   ///< a repeated index or zero area
  std::size_t edges = 0;                  ///< distinct undirected edges
  std::size_t boundary_edges = 0;         ///< edges in exactly one triangle
  std::size_t non_manifold_edges = 0;     ///< edges in more than two triangles
  /// Edges whose uses do not pair up in opposite directions (as many one way as the other): two
  /// triangles traversing it the same way, or an odd number of uses above one. Non-manifold
  /// edges are judged too. Boundary edges are not counted.
  std::size_t misoriented_edges = 0;
  std::size_t components = 0;  ///< connected components (over triangles)
  long long euler = 0;         ///< V - E + F over referenced vertices
  double area = 0;             ///< total surface area (world units^2)

  /// The offenders, in increasing id order: (vertex, the earlier vertex at its position) for each
  /// duplicate; edges as (lower, higher) vertex id.
  std::vector<VertexPair> duplicates, non_manifold, misoriented;
  /// Per component, in the order of their lowest vertex id.
  std::vector<ComponentCheck> component_list;

  bool watertight() const { return boundary_edges == 0 && non_manifold_edges == 0; }
  bool oriented() const { return misoriented_edges == 0; }
  /// Total genus when closed and oriented: components - euler / 2; -1 otherwise.
  long long genus() const {
    return watertight() && oriented() ? (long long)components - euler / 2 : -1;
  }
  std::size_t closed_components() const;
  std::size_t inward_components() const;  ///< closed components with a negative signed volume
  /// Sum of the closed components' signed volumes: negative when the closed part of the mesh is
  /// oriented inward as a whole (an inward component inside an outward one is a cavity).
  double closed_signed_volume() const;
};

/// Counts and lists everything in MeshCheck. O(T log T); exact (positions compared by value, so
/// -0 equals +0). `vertex_labels` (one per vertex, e.g. the "Label" array of isocurv's --labels
/// meshes) makes duplicates those of one label; coincident vertices of different labels are
/// label_wall_vertices. nullptr, or a size other than the vertex count: no labels.
MeshCheck check_mesh(const Mesh& mesh, const std::vector<float>* vertex_labels = nullptr);

}  // namespace isocurv::mc
