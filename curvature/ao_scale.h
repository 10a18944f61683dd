#pragma once
// The default ambient-occlusion radius for a mesh.
#include "core/mesh.h"

namespace isocurv::curvature {

/// 4 mean edge lengths (world units): occlusion gathered over a few triangles, so the shading
/// shows creases at the mesh's own scale whatever the units. 1 for a mesh without triangles.
float default_ao_scale(const Mesh& mesh);

}  // namespace isocurv::curvature
