#pragma once
// The plain indexed triangle mesh passed between stages.
#include <array>
#include <cstdint>
#include <vector>

namespace isocurv {

using Vec3f = std::array<float, 3>;
using Tri = std::array<std::uint32_t, 3>;

/// Indexed triangle mesh in world space. Triangles wind counter-clockwise seen from outside the
/// object, so (b - a) x (c - a) points out of it (DESIGN.md: normals point out of the object).
struct Mesh {
  std::vector<Vec3f> positions;  ///< world-space vertex positions
  std::vector<Tri> triangles;    ///< vertex index triples
  /// Marching cubes only (else empty): per vertex, the key of the cube edge it lies on
  /// (mc/edge_key.h). Lets tests match vertices of two meshers by edge identity.
  std::vector<std::uint64_t> edge_keys;

  std::size_t vertex_count() const { return positions.size(); }
  std::size_t triangle_count() const { return triangles.size(); }
};

}  // namespace isocurv
