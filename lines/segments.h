#pragma once
// The lines stage's per-face output: unconnected segments, one per face and
// line type at most.
// Tested in tests/lines/test_bad_input.cpp, tests/lines/test_contours.cpp (through its users).
#include <cstdint>
#include <vector>

#include "core/camera.h"
#include "core/mesh.h"
#include "curvature/curvature_field.h"
#include "lines/line_types.h"
#include "lines/options.h"

namespace isocurv::lines {

/// An endpoint not on a mesh edge (a suggestive contour clipped inside its
/// face).
constexpr std::uint64_t kInsideFace = ~std::uint64_t(0);

/// A zero crossing closer to an edge's end than this fraction of the edge is
/// moved onto that vertex (so float and double, and neighbouring faces, agree
/// on where a line passes a vertex).
constexpr double kVertexSnap = 1e-5;

/// The key of the mesh edge between vertices a and b: (min << 32) | max.
inline std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
  return a < b ? (std::uint64_t(a) << 32 | b) : (std::uint64_t(b) << 32 | a);
}

/// One straight piece of a feature line inside one triangle, in world space.
struct Segment {
  Vec3f a{}, b{}; ///< endpoints
  /// edge_key of the mesh edge `a` lies on (edge_key(v, v) when it is vertex
  /// v), or kInsideFace
  std::uint64_t edge_a = kInsideFace;
  std::uint64_t edge_b = kInsideFace; ///< the same for `b`
  float strength = 1;     ///< in [0, 1]: 1 for contours; the fade of the others
  std::uint32_t face = 0; ///< the triangle it lies in
  LineType type = LineType::contour;
};

/// Every segment of a mesh, ordered by face, then by type (contour, suggestive,
/// ridge, valley).
using Segments = std::vector<Segment>;

/// Throws Error unless `field` fits `mesh` (normals, k1, k2 one per vertex;
/// dir1, dir2 too, except that contours alone accept them empty; dcurv too when
/// the selection needs it; a missing array the selection needs gets a message
/// saying which lines need it) and every triangle index is a vertex.
void check_input(const Mesh &mesh, const curvature::CurvatureField &field,
                 const Options &options);

} // namespace isocurv::lines
