#pragma once
// Ray-cast ambient occlusion from the volume: the reference the curvature formulas are judged by
// (SEEDS-SPEC.md R-AORAY, volume mode).
// Tested in tests/ao/test_ao.cpp.
#include <vector>

#include "core/mesh.h"
#include "volume/volume.h"

namespace isocurv::ao {

struct RaycastOptions {
  double radius = 1;    ///< rho: ray length, world units (> 0, finite)
  int strata = 16;      ///< g: g x g stratified rays per point (256 by default), 1..64
  bool cosine = false;  ///< cosine-weighted directions (eq. 9's measure) instead of uniform
};

/// Per point, the fraction of hemisphere rays of length rho that stay outside the object:
/// rays start at p + eps n (eps = 1e-3 of the finest voxel spacing: marching-cubes vertices lie
/// on the trilinear isosurface, and a larger offset lets grazing rays in a concavity of radius R
/// run sqrt(2 R eps) before meeting the wall, a bias) and march in equal steps of at most half
/// that spacing, the last at rho; a ray is
/// occluded when a sample of the trilinear field is inside (volume.inside's side of `isovalue`;
/// equal counts as outside, as everywhere). Directions: ao/detail/hemisphere.h, seeded by the
/// point's index, so the result is deterministic. Inside a spherical cavity of radius R:
/// 1 - rho / 2R (uniform) or 1 - (rho / 2R)^2 (cosine). Disconnected geometry occludes too (what
/// the curvature formulas cannot see); outside the volume's data the grid's background counts.
/// @param positions world points (mesh vertices), @param normals unit outward normals, as many
/// @return one AO in [0, 1] per point
/// @throw Error for a radius that is not positive and finite, strata outside 1..64, or sizes that
/// differ. Threading: parallel over points (TBB), one grid accessor per task. C++ only (no OpenCL
/// kernel yet); cost: points x g^2 x (rho / step) trilinear samples, less where rays stop early.
std::vector<float> raycast(const volume::Volume& volume, float isovalue, const Positions& positions,
                           const std::vector<Vec3f>& normals, const RaycastOptions& options);

}  // namespace isocurv::ao
