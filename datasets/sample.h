#pragma once
// Sampling an analytic field on a regular grid into a Volume.
#include <Eigen/Core>

#include "datasets/field.h"
#include "volume/volume.h"

namespace isocurv::datasets {

/// Grid options beyond the resolution, mainly for tests of spacing and origin handling.
struct SampleOptions {
  Eigen::Vector3d anisotropy = Eigen::Vector3d::Ones();   ///< per-axis factor on the voxel size
  Eigen::Vector3d origin_offset = Eigen::Vector3d::Zero();  ///< world shift of index (0,0,0) from box min
};

/// Samples `field` densely: voxel size h = (longest side of field.box()) / (resolution - 1), spacing
/// h * anisotropy, index (i,j,k) at world origin + (i,j,k) * spacing with origin = box min +
/// origin_offset, and per axis the fewest voxels reaching the box max. The Volume (format
/// "generated", path "generated:<name>", grid name "levelset" for Inside::Below fields, else
/// "density"; grid class level set / fog volume (values >= 0) / unknown) has the field's inside
/// side and its voxels equal field.value at their centres (as float). Parallel (TBB).
/// Throws isocurv::Error when resolution < 2 or anisotropy is not positive.
volume::Volume sample(const Field& field, int resolution, const SampleOptions& options = {});

}  // namespace isocurv::datasets
