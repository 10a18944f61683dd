#pragma once
// Internals the volume estimator's device path and its reference share
// (curvature/volume_estimate.h).
#include <cstdint>
#include <vector>

#include "core/mesh.h"
#include "curvature/curvature_field.h"
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

/// Per-vertex results before the reliability pass: |g| at the evaluation point (0 where the
/// gradient vanished) and whether the reconstructed surface was missed.
struct RawVertex {
  std::vector<float> gradient_norm;
  std::vector<std::uint8_t> missed;
};

/// Fills Area, Boundary and Unreliable, and resets the unreliable vertices (see volume_estimate.h).
/// Returns the number of unreliable vertices.
std::size_t finish_volume_field(const Mesh& mesh, const RawVertex& raw, float ao_scale,
                                CurvatureField& field);

}  // namespace isocurv::curvature::detail
