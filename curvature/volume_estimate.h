#pragma once
// The volume estimator: curvature of the volume itself at each mesh vertex, from derivatives of
// the volume reconstructed at scale sigma: the samples smoothed once by a separable Gaussian
// prefilter (volume/prefilter.h), then a quartic B-spline through them (volume/spline_jet.h),
// together a smoothing of variance sigma^2 in world space.
//
// At each vertex x0 (on the mesh, which is not moved): the gradient g0 there gives the line
// x0 + t g0/|g0|; kNewtonSteps Newton steps on the value and gradient find where it meets the
// reconstructed isosurface (|t| capped at kMaxShiftVoxels voxels), then one last step on the full
// jet's Taylor expansion; there the gradient, Hessian and third derivatives give the curvature by
// curvature/implicit_curvature.h (Normals, k1 >= k2, dir1, dir2, H, K, dcurv, ShapeIndex,
// Curvedness, AO). Area and Boundary come from the mesh (curvature/mesh_areas.h).
// A vertex is Unreliable (flag 1, its curvature zero, AO that of a plane, its normal the
// area-weighted face normal) where the gradient is at most volume::kWeakGradientFraction of its
// median over the vertices, or the reconstructed surface was not found within the cap at sigma
// nor at any finer scale down to one voxel (see finer_scales below).
//
// Cost follows the surface: only the 8^3 bricks the vertices' B-splines read, and what the
// prefilter's three passes need for them, are gathered and filtered; a vertex then reads 5^3
// smoothed samples per evaluation, whatever the scale.
#include <cstddef>

#include "core/cl_device.h"
#include "core/mesh.h"
#include "curvature/curvature_field.h"
#include "volume/volume.h"

namespace isocurv::curvature {

/// Newton steps along each vertex's gradient line (a fixed count: deterministic, and from a
/// marching-cubes vertex, within a fraction of a voxel of the surface, two leave it within
/// 1e-3 voxel; the check kOnSurfaceVoxels flags the rest).
inline constexpr int kNewtonSteps = 2;
/// The largest move along the gradient line, in voxels (the largest spacing).
inline constexpr double kMaxShiftVoxels = 1.5;
/// The reconstructed surface counts as found when the field there is within this many voxels
/// (|F - iso| / |g|, in the largest spacing) of the isovalue.
inline constexpr double kOnSurfaceVoxels = 0.05;
/// The last Newton step, taken on the full jet's Taylor expansion, moves at most this many voxels.
inline constexpr double kMaxFinalStepVoxels = 0.1;

/// Wall time of the volume estimator's steps in ms (device path, summed over the finer scales;
/// the queue is drained between steps): planning the bricks, gathering the samples, the
/// prefilter's passes (with the padded copy), the per-vertex kernel with the downloads, and the
/// host's Area, Boundary and Unreliable pass.
struct VolumeStepTimes {
  double plan = 0, gather = 0, smooth = 0, vertices = 0, finish = 0;
};

/// What one volume estimate did.
struct VolumeEstimateStats {
  std::size_t unreliable = 0;  ///< vertices flagged Unreliable
  std::size_t bricks = 0;      ///< 8^3 bricks filtered or gathered (device path), all scales
  std::size_t finer_scale = 0;  ///< vertices whose surface was found only at a finer scale
  VolumeStepTimes steps;        ///< device path only
};

/// The volume estimator on `device` (float; the same steps as volume_estimate_reference), at
/// scale `sigma` (world units) for the surface at `isovalue` of `volume` from which `mesh` was
/// extracted. Only the bricks the vertices need are gathered and sent to the device, where the
/// prefilter's passes (curvature/volume_kernels.cl, smooth_axis) run before the per-vertex kernel.
/// `ao_scale`: Options::ao_scale. Deterministic. Throws isocurv::Error when sigma is not positive
/// and finite, larger than the volume, under volume::kMinScaleVoxels voxels of the coarsest axis,
/// or so large against a spacing that it would exceed volume::kMaxDeviation voxels; when the grid
/// transform is not affine with
/// orthogonal axes; for invalid meshes (check_input); or on an OpenCL failure.
/// `finer_scales` (the default): a vertex whose smoothed surface is missed at sigma (a structure
/// thinner than about twice the scale) is evaluated again at sigma / 2, sigma / 4, ... down to
/// one voxel (the largest spacing) and keeps the first scale at which its surface is found; only
/// the vertices missed at every scale are Unreliable. Off, they are all Unreliable (the
/// multi-scale arrays use that, so that each scale shows only what it resolves).
CurvatureField volume_estimate(const Mesh& mesh, const volume::Volume& volume, float isovalue,
                               double sigma, float ao_scale, Device& device,
                               VolumeEstimateStats* stats = nullptr, bool finer_scales = true);

/// The specification: the same in double precision on the host (volume::smooth_reference and
/// volume::spline_jet), parallel over vertex batches (TBB).
CurvatureField volume_estimate_reference(const Mesh& mesh, const volume::Volume& volume,
                                         float isovalue, double sigma, float ao_scale,
                                         VolumeEstimateStats* stats = nullptr,
                                         bool finer_scales = true);

}  // namespace isocurv::curvature
