#pragma once
// Simple measures of a Mesh shared by several stages.
// Tested in tests/curvature/request_test.cpp, tests/curvature/volume_normals_test.cpp.
#include <array>
#include <cstdint>
#include <vector>

#include "core/mesh.h"

namespace isocurv {

/// The mean length of the mesh's triangle edges (shared edges counted once per triangle), in
/// world units; 0 for a mesh without triangles.
double mean_edge_length(const Mesh& mesh);

/// The sum of the lengths of the triangles' edges (each triangle's three, world units) and the
/// number of edges summed, over the triangles t with (*only)[t] set, or all of them when `only` is
/// nullptr (a triangle past the end of `only` is left out): mean_edge_length's terms, for a
/// surface divided among processes to reduce.
std::array<double, 2> edge_length_sum(const Mesh& mesh,
                                      const std::vector<std::uint8_t>* only = nullptr);

/// The length of the diagonal of the axis-aligned box around the mesh's vertices, in world
/// units; 0 for a mesh without vertices.
double bounding_box_diagonal(const Mesh& mesh);

/// (b - a) x (c - a) in double precision for the triangle t = (a, b, c) of `mesh` (indices in
/// range): twice its area, along its outward normal.
std::array<double, 3> triangle_area_vector(const Mesh& mesh, const Tri& t);

/// The signed volume a . (b x c) / 6 of the tetrahedron (origin, a, b, c) for the triangle
/// t = (a, b, c) of `mesh` (indices in range), in double precision relative to `origin`: summed
/// over a closed, outward-facing surface, the volume it encloses, whatever the origin (one near
/// the surface keeps far-from-origin meshes precise).
double signed_volume_term(const Mesh& mesh, const Tri& t, const Vec3f& origin);

/// Per vertex, the sum of (b - a) x (c - a) over the triangles (a, b, c) using it: the
/// area-weighted face normal (twice the area), pointing out of the object for the winding Mesh
/// documents. Not normalised; zero for a vertex no triangle with a non-zero area uses. Triangles
/// with an index out of range are skipped.
std::vector<Vec3f> area_weighted_normals(const Mesh& mesh);

}  // namespace isocurv
