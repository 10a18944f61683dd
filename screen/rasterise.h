#pragma once
// G-buffer producer (ii): a mesh rasterised in software (SEEDS-SPEC 4.4), so that meshes from
// files give screen-space curvature too.
#include <vector>

#include "core/mesh.h"
#include "screen/gbuffer.h"

namespace isocurv::screen {

/// Per pixel of `frame`, the nearest triangle of `mesh` its ray crosses (exact ray-triangle
/// intersection at the pixel centre, so positions lie on the triangles for perspective and
/// orthographic cameras alike; both sides of a triangle count); the position is that point, the
/// normal the barycentric interpolation of `normals` (unit, one per vertex) renormalised, the
/// depth its eye depth (a z-buffer; equal depths keep the lower triangle index). Points nearer
/// than near (perspective) are clipped. near/far from the mesh's bounds. Deterministic (TBB
/// over image bands, every band visits the triangles in order).
/// @throw Error when normals.size() != the vertex count or an index is out of range
GBuffer rasterise(const Mesh& mesh, const std::vector<Vec3f>& normals, const ViewFrame& frame);

}  // namespace isocurv::screen
