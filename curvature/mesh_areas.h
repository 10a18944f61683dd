#pragma once
// What every curvature estimator takes from the mesh itself, whatever gives the curvature: the
// mixed Voronoi areas ("Area") and the open-boundary flags ("Boundary").
// Tested through the Area and Boundary arrays: tests/curvature/closed_form_test.cpp, tests/measure.
#include <array>
#include <cstdint>
#include <vector>

#include "core/mesh.h"
#include "curvature/vertex_corners.h"

namespace isocurv::curvature {

/// Meyer et al.'s mixed area of each corner of a triangle with corners p[0..2] (world units
/// squared): the Voronoi region of a non-obtuse triangle (from the circumcentre's barycentric
/// coordinates); else half the area to the obtuse corner and a quarter to each other one. Zero for
/// a zero-area triangle.
std::array<double, 3> mixed_corner_areas(const std::array<std::array<double, 3>, 3>& p);

/// Per vertex, the sum of its corners' mixed areas (each computed in double and kept as float,
/// summed in double in triangle order, stored as float). Triangles with a repeated index contribute
/// nothing. Indices must be in range (curvature::check_input). Parallel (TBB), deterministic.
std::vector<float> mixed_vertex_areas(const Mesh& mesh);
/// The same with the mesh's vertex -> corner adjacency already built.
std::vector<float> mixed_vertex_areas(const Mesh& mesh, const VertexCorners& corners);

/// Per vertex, 1 when it lies on an edge that only one triangle (without a repeated index) uses,
/// else 0. Indices must be in range. Parallel (TBB), deterministic.
std::vector<std::uint8_t> boundary_vertices(const Mesh& mesh);
/// The same with the mesh's vertex -> corner adjacency already built.
std::vector<std::uint8_t> boundary_vertices(const Mesh& mesh, const VertexCorners& corners);

}  // namespace isocurv::curvature
