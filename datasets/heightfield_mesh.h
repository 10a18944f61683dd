#pragma once
// A heightfield field (f1, f2: F = h(x, y) - z) triangulated on a regular grid: the function
// meshes of Prantl et al.'s evaluation (their section 4.1 uses a Delaunay triangulation of random
// points over x, y in [-10, 10]; f1 with 15,000 vertices in the screen-space protocol).
#include "core/mesh.h"
#include "datasets/field.h"

namespace isocurv::datasets {

/// The surface of `field` over its box's x-y extent on an n x n grid of vertices (row-major, x
/// fastest), each at the height where the field crosses its isovalue along z (bisected to 1e-12
/// of the box's height), two triangles per cell, wound so that the normal points up (+z, out of
/// a heightfield's solid below).
/// @throw Error for n < 2, or a field that does not cross its isovalue once along z inside its
/// box (not a heightfield)
Mesh heightfield_mesh(const Field& field, int n);

}  // namespace isocurv::datasets
