#pragma once
// What a picture of a mesh is framed on: the mesh's vertices without its specks.
// Tested in tests/core/test_framing_points.cpp.
#include <array>
#include <vector>

#include "core/mesh.h"

namespace isocurv {

/// A connected component is a speck when its area is under this fraction of the largest one's.
inline constexpr double kSpeckAreaFraction = 0.01;

/// The vertices (world units) of the mesh's connected components (triangles sharing a vertex)
/// whose area is at least kSpeckAreaFraction of the largest component's, for fit_camera_to_points.
/// A few stray specks of noise far from the object (CT and MR volumes have them at most
/// isovalues) would otherwise pull the framing off the object; the specks stay drawn, only the
/// framing ignores them. A mesh without triangles (or of zero area) gives all its vertices; one
/// without vertices none. Triangles with an index out of range are skipped.
std::vector<std::array<double, 3>> framing_points(const Mesh& mesh);

}  // namespace isocurv
