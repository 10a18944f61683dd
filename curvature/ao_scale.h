#pragma once
// The default ambient-occlusion radius for a mesh.
// Tested through the commands that default to it: tests/app/test_ao_cli.cpp.
#include "core/mesh.h"
#include "core/surface_piece.h"

namespace isocurv::curvature {

/// 4 mean edge lengths (world units): occlusion gathered over a few triangles, so the shading
/// shows creases at the mesh's own scale whatever the units. 1 for a mesh without triangles.
/// With a `piece` (core/surface_piece.h), collective: the whole surface's mean, over every
/// piece's own triangles (summed in another order than one process sums them: equal to the
/// last bits of a double, so nearly always to the float).
float default_ao_scale(const Mesh& mesh, const SurfacePiece* piece = nullptr);

}  // namespace isocurv::curvature
