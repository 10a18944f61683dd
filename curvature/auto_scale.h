#pragma once
// --scale auto: the volume estimator's Gaussian scale chosen from the data.
#include <string>

#include "core/mesh.h"
#include "volume/volume.h"

namespace isocurv::curvature {

/// The noise level (noise / edge step per voxel) that kAutoScaleExponent maps to one voxel
/// (before the clamp below);
/// chosen on the CT-like test volumes (bench/bench_accuracy) as the value whose choice lands
/// nearest the best fixed scale there.
inline constexpr double kAutoReferenceNoise = 0.004;
/// The scale grows as (noise level / kAutoReferenceNoise)^(2/7): with Gaussian derivative
/// filters the noise in the Hessian falls as sigma^-7/2 (3-D, second derivatives), so this keeps
/// the noise in the curvature near what it is at one voxel for kAutoReferenceNoise.
inline constexpr double kAutoScaleExponent = 2.0 / 7.0;
/// The chosen scale stays within [kAutoMinVoxels, kAutoMaxVoxels] voxels (the largest spacing).
/// On smooth fields the error is the smoothing's own bias, about (sigma k)^2 (bench_accuracy,
/// torus 128^3: H 0.27% at one voxel, 0.13% at 0.7), and the B-spline reconstruction does not
/// alias at 0.7 voxel (sphere H 0.03%), so smooth fields get 0.8 voxel.
inline constexpr double kAutoMinVoxels = 0.8, kAutoMaxVoxels = 4.0;

/// How the scale was chosen (reported in the JSON).
struct ScaleChoice {
  double scale = 0;           ///< the chosen sigma, world units
  double voxel = 0;           ///< the largest spacing, world units
  double noise = 0;           ///< voxel noise, value units: max(measured, quantisation)
  double measured_noise = 0;  ///< volume::estimate_noise's
  double quantisation = 0;    ///< step / sqrt(12) for integer voxel types (step 1), else 0
  double edge_step = 0;       ///< median over the vertices of |gradient| per voxel, value units
  double noise_level = 0;     ///< noise / edge_step
};

/// The scale for the volume estimator on `mesh` (extracted from `volume` at `isovalue`):
/// sigma = voxel * clamp((noise_level / kAutoReferenceNoise)^kAutoScaleExponent, kAutoMinVoxels,
/// kAutoMaxVoxels), with noise_level the voxel noise (measured near the surface by
/// volume::estimate_noise, at least the quantisation noise of an integer voxel type) over the
/// step the field makes per voxel across the surface (the median index-space gradient, Gaussian
/// at one voxel, over up to 4096 vertices taken evenly). A smooth float field thus gets 0.8 voxel,
/// noisy 8-bit data about 2. Deterministic. Throws what volume::grid_frame throws.
ScaleChoice auto_scale(const volume::Volume& volume, const Mesh& mesh, float isovalue);

}  // namespace isocurv::curvature
