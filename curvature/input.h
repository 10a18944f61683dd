#pragma once
// Validation of the curvature stage's input, shared by the kernels' host code and the reference.
#include "core/mesh.h"
#include "curvature/options.h"

namespace isocurv::curvature {

/// Throws isocurv::Error (one line naming the problem) when the mesh or options cannot be used:
/// a triangle index out of range, a non-finite vertex coordinate, more than 2^32 - 1 corners,
/// options.vertex_normals of the wrong size, or a non-finite options.ao_scale. Degenerate but
/// valid input (zero-area or repeated-index triangles, isolated or duplicate vertices) passes.
void check_input(const Mesh& mesh, const Options& options);

}  // namespace isocurv::curvature
