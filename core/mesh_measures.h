#pragma once
// Simple measures of a Mesh shared by several stages.
#include "core/mesh.h"

namespace isocurv {

/// The mean length of the mesh's triangle edges (shared edges counted once per triangle), in
/// world units; 0 for a mesh without triangles.
double mean_edge_length(const Mesh& mesh);

}  // namespace isocurv
