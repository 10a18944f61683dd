#pragma once
// CT-like test volumes with known curvature: the classes of volume people really have (thin
// parts, thick slices, binary masks, surfaces cut by the box, saddle sheets), made from analytic
// solids. Shared by the accuracy tests (tests/curvature/ct_classes_test.cpp) and
// bench/bench_accuracy, so both measure the same volumes.
//
// A grey-level class samples lo + (hi - lo) * erfc(-d / (sqrt 2 b)) / 2 + noise at each voxel
// centre, rounded and clamped to the voxel type: d the (first-order) signed distance to the
// solid's surface (positive inside), b the scanner's blur along the surface normal (one world
// unit in-plane; half the slice spacing along a thick-slice axis, as a slice integrates over
// it), noise Gaussian. A binary class is 255 inside, 0 outside (voxel centres), no noise. The
// isosurface at (lo + hi) / 2 then lies on the solid's surface.
#include <Eigen/Core>

#include <functional>
#include <string>
#include <vector>

#include "volume/volume.h"

namespace isocurv::datasets {

/// One class: the volume, its isovalue, and the exact curvature of the solid's surface.
struct CtCase {
  std::string name;
  volume::Volume volume;
  float iso = 0;
  /// H and K (outward normals: a solid sphere of radius R has H = 1/R, K = 1/R^2, world units) at
  /// the surface point nearest world point p.
  std::function<void(const Eigen::Vector3d& p, double& H, double& K)> exact;
  bool binary = false;  ///< a mask: errors are compared in absolute terms (published figures)
};

/// The classes' names: sphere_u8, torus_u8, tube_u8 (a torus of tube radius 3.5 voxels),
/// ellipsoid_u16_thick (rotated, on a 1 x 1 x 2.5 grid), gyroid_u8 (a thick gyroid sheet, saddles),
/// sphere_box_u8 (a sphere cut by two faces of the box), torus_binary (R 6, r 2 at grid step
/// 0.5: the torus of Lachaud et al.'s corrected normal currents), sphere_binary, part_binary (a
/// box with rounded edges: flat faces where H = K = 0).
std::vector<std::string> ct_like_names();

/// The class called `name` at test size (`small`, 10-40k vertices) or bench size. Deterministic
/// (fixed seeds). `refine` (1 to 8): the same object and the same scan sampled `refine` times
/// finer along every axis (the same world extent and blur, the same noise per voxel), as a finer
/// scanner or segmentation gives it. Throws isocurv::Error for an unknown name or refine.
CtCase ct_like_case(const std::string& name, bool small, int refine = 1);

}  // namespace isocurv::datasets
