#pragma once
// Welding exact duplicate vertices, so the estimator sees the connectivity of a mesh whose
// triangles were stored each with its own corners (other tools' PLY and OBJ files).
// Tested in tests/curvature/weld_test.cpp.
#include <cstddef>

#include "core/mesh.h"

namespace isocurv::curvature {

/// Merges every vertex into the first one at exactly the same position (compared by value, so -0
/// equals +0; NaN positions are never merged): the mesh keeps one vertex per distinct position,
/// in the order of first appearance, and the triangles are renumbered. Triangles are kept as they
/// are, even those that become degenerate. Mesh::edge_keys are dropped when anything merges.
/// Returns the number of vertices removed (0: the mesh is unchanged).
std::size_t weld_duplicates(Mesh& mesh);

}  // namespace isocurv::curvature
