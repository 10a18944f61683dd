#pragma once
// The plain indexed triangle mesh passed between stages.
// Tested in tests/app/mesh_compare.h, tests/curvature/test_meshes.h.
#include <array>
#include <cstdint>
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

namespace isocurv {

using Vec3f = std::array<float, 3>;
using Tri = std::array<std::uint32_t, 3>;

/// std::allocator whose resize() leaves new elements default-initialised (for these trivial types:
/// not zeroed), so an array its producer then writes whole (a kernel writing the mesh) is not
/// written twice. Elements added with values (push_back, assign, copies) are unaffected; after
/// resize(n), vector(n) or emplace_back() the new elements hold garbage until written.
template <class T>
struct NoZeroAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = NoZeroAllocator<U>;
  };
  NoZeroAllocator() = default;
  template <class U>
  NoZeroAllocator(const NoZeroAllocator<U>&) noexcept {}
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

using Positions = std::vector<Vec3f, NoZeroAllocator<Vec3f>>;  ///< a mesh's vertex positions
using Triangles = std::vector<Tri, NoZeroAllocator<Tri>>;      ///< a mesh's index triples

/// Indexed triangle mesh in world space. Triangles wind counter-clockwise seen from outside the
/// object, so (b - a) x (c - a) points out of it (DESIGN.md: normals point out of the object).
struct Mesh {
  Positions positions;  ///< world-space vertex positions
  Triangles triangles;  ///< vertex index triples
  /// Marching cubes only (else empty): per vertex, the key of the cube edge it lies on
  /// (mc/edge_key.h). Lets tests match vertices of two meshers by edge identity.
  std::vector<std::uint64_t, NoZeroAllocator<std::uint64_t>> edge_keys;

  std::size_t vertex_count() const { return positions.size(); }
  std::size_t triangle_count() const { return triangles.size(); }
};

}  // namespace isocurv
