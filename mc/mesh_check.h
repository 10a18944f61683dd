#pragma once
// Fusion and topology checks any user can run on any mesh (isocurv check).
#include <cstdint>

#include "core/mesh.h"

namespace isocurv::mc {

struct MeshCheck {
  std::size_t vertices = 0, triangles = 0;
  std::size_t duplicate_vertices = 0;     ///< vertices at exactly the position of an earlier one
  std::size_t unreferenced_vertices = 0;  ///< vertices no triangle uses
  std::size_t degenerate_triangles = 0;   ///< a repeated index or zero area
  std::size_t edges = 0;                  ///< distinct undirected edges
  std::size_t boundary_edges = 0;         ///< edges in exactly one triangle
  std::size_t non_manifold_edges = 0;     ///< edges in more than two triangles
  std::size_t misoriented_edges = 0;      ///< edges whose two triangles traverse it the same way
  std::size_t components = 0;             ///< connected components (over triangles)
  long long euler = 0;                    ///< V - E + F over referenced vertices
  double area = 0;                        ///< total surface area (world units^2)
  bool watertight() const { return boundary_edges == 0 && non_manifold_edges == 0; }
  bool oriented() const { return misoriented_edges == 0; }
  /// Total genus when closed and oriented: components - euler / 2; -1 otherwise.
  long long genus() const { return watertight() && oriented() ? (long long)components - euler / 2 : -1; }
};

/// Counts everything in MeshCheck. O(T log T); exact (positions compared bit for bit).
MeshCheck check_mesh(const Mesh& mesh);

}  // namespace isocurv::mc
