#pragma once
// Internals the volume estimator's device path and its reference share
// (curvature/volume_estimate.h).
#include <cstdint>
#include <functional>
#include <vector>

#include "core/mesh.h"
#include "curvature/curvature_field.h"
#include "curvature/volume_estimate.h"
#include "volume/gaussian_jet.h"
#include "volume/volume.h"

namespace isocurv::curvature::detail {

/// The checked inputs of one volume estimate.
struct VolumeSetup {
  volume::GridFrame frame;
  double sigma = 0;      ///< world units
  double voxel = 0;      ///< the largest spacing, world units
  double max_shift = 0;  ///< kMaxShiftVoxels * voxel
  volume::Inside inside = volume::Inside::Above;
};

/// Checks mesh, sigma and the grid (see volume_estimate) and derives the setup.
VolumeSetup volume_setup(const Mesh& mesh, const volume::Volume& volume, double sigma);

/// How far from a vertex (index units per axis, beyond the B-spline's own support) the estimator
/// may evaluate the field: the largest Newton move plus a voxel.
openvdb::Vec3d spline_reach(const VolumeSetup& setup);

/// Per-vertex results before the reliability pass: |g| at the evaluation point (0 where the
/// gradient vanished) and whether the reconstructed surface was missed.
struct RawVertex {
  std::vector<float> gradient_norm;
  std::vector<std::uint8_t> missed;
};

/// One evaluation of the estimator at setup.sigma for some positions: the field's per-vertex
/// arrays (Normals, k1, k2, dir1, dir2, H, K, dcurv, ShapeIndex, Curvedness, AO), one entry per
/// position, and the raw flags.
struct VolumeEvaluation {
  CurvatureField field;
  RawVertex raw;
  std::size_t bricks = 0;  ///< bricks of every stage summed over the evaluations (device path)
  VolumeStepTimes steps;   ///< summed over the evaluations (device path)
};
using VolumeEvaluate =
    std::function<VolumeEvaluation(const Positions& positions, const VolumeSetup& setup)>;

/// Evaluates every vertex of `mesh` at setup.sigma; then, when `finer_scales`, the vertices whose
/// smoothed surface was missed (a structure thinner than about twice the scale: its peak sinks
/// below the isovalue when smoothed) again at half the scale, and so on down to one voxel
/// (setup.voxel), each keeping the first scale at which its surface is found. `refined` counts
/// the vertices that took a finer scale.
VolumeEvaluation evaluate_with_finer_scales(const Mesh& mesh, VolumeSetup setup, bool finer_scales,
                                            const VolumeEvaluate& evaluate, std::size_t& refined);

/// Fills Area, Boundary and Unreliable, and resets the unreliable vertices (see volume_estimate.h).
/// Returns the number of unreliable vertices.
std::size_t finish_volume_field(const Mesh& mesh, const RawVertex& raw, float ao_scale,
                                CurvatureField& field);

}  // namespace isocurv::curvature::detail
