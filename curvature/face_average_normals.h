#pragma once
// Vertex normals as the plain average of the unit face normals (Prantl's report eq. 2.2; the
// normals of Batagelo & Wu's Fig. 2 protocol).
// Tested in tests/curvature/face_average_normals_test.cpp.
#include <vector>

#include "core/mesh.h"

namespace isocurv::curvature {

/// Per vertex, the normalised sum of the unit normals of its triangles (those without a repeated
/// index and with non-zero area); zero for a vertex with none. Pass the result as
/// Options::vertex_normals to use it with any mesh estimator.
/// @throw nothing; indices must be in range (check_input)
std::vector<Vec3f> face_average_normals(const Mesh& mesh);

}  // namespace isocurv::curvature
