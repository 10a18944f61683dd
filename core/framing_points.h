#pragma once
// What a picture of a mesh is framed on: the mesh's vertices without its specks.
// Tested in tests/core/test_framing_points.cpp.
#include <array>
#include <vector>

#include "core/mesh.h"

namespace isocurv {

/// A connected component is a speck when its area is under this fraction of the largest one's,
/// unless it is long and thick: its extent (box diagonal) at least kSpeckExtentFraction of the
/// largest one's and its area over its extent (about its girth) at least kThickPartEdges mean
/// edge lengths. So an MR's fiducial rods are framed (BrainWeb's: 0.2-0.9% of the head's area,
/// 19-56% of its extent, girth 28-41 edges), and neither noise specks (BrainWeb's: at most 10% of
/// the head's extent) nor the one-voxel streaks a CT has along its box's edges (the lobster's:
/// 19% of its extent, girth 2.5-6 edges).
inline constexpr double kSpeckAreaFraction = 0.01;
inline constexpr double kSpeckExtentFraction = 0.15;
inline constexpr double kThickPartEdges = 12;

/// The vertices (world units) of the mesh's connected components (triangles sharing a vertex)
/// that are not specks (see kSpeckAreaFraction), for fit_camera_to_points; the largest
/// component is the one of largest area.
/// A few stray specks of noise far from the object (CT and MR volumes have them at most
/// isovalues) would otherwise pull the framing off the object; the specks stay drawn, only the
/// framing ignores them. A mesh without triangles (or of zero area) gives all its vertices; one
/// without vertices none. Triangles with an index out of range are skipped.
std::vector<std::array<double, 3>> framing_points(const Mesh& mesh);

}  // namespace isocurv
