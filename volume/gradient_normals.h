#pragma once
// Surface normals from the volume itself (`--normals volume` in curvature).
#include <vector>

#include "core/mesh.h"
#include "volume/volume.h"

namespace isocurv::volume {

/// Unit outward normals at world positions: the gradient by central differences at the voxels
/// (one-sided at the border of a dense volume's domain, which is never read past), interpolated
/// trilinearly and carried to world space through the transform's inverse-transpose Jacobian;
/// outward is the direction of decreasing "insideness": -gradient for Inside::Above, +gradient for
/// Inside::Below. A zero gradient gives a zero vector. Parallel (TBB), deterministic.
std::vector<Vec3f> gradient_normals(const Volume& volume, const Positions& world_positions);

}  // namespace isocurv::volume
