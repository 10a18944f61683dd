#pragma once
// Building a Volume from a dense array in memory (every dense loader and the dataset generators use it).
// Tested in tests/volume/test_from_dense.cpp, tests/volume/test_gradient_normals.cpp.
#include <array>
#include <optional>
#include <string>

#include "volume/volume.h"

namespace isocurv::volume {

/// Describes where a dense array came from, for the Volume's bookkeeping fields.
struct DenseSource {
  std::string path;                  ///< file (or a descriptive name for generated data)
  std::string format;                ///< see Volume::format
  std::string voxel_type;            ///< type on disk
  std::string grid_name;             ///< optional
  Inside inside = Inside::Above;
};

/// Part of a volume (LoadOptions::z_slab): the data are index-z slices [first_z, first_z +
/// dims[2]) of a volume `full_z` slices deep (first_z a multiple of 8); full_z 0: the whole volume.
struct DensePart {
  int first_z = 0, full_z = 0;
  std::optional<float> outside;  ///< LoadOptions::outside
};

/// Copies `data` (dims[0]*dims[1]*dims[2] floats, X fastest) into a FloatGrid with transform
/// `xform` (index -> world), domain [0, dims-1]. Counts NaN/Inf voxels and replaces them, and sets
/// the background, with the outside value (finite min for Inside::Above, finite max for Below);
/// computes stats (range, mean, 256-bin histogram, suggested isovalue). Throws Error(path, ...)
/// when dims are not positive or no voxel is finite.
Volume from_dense(const float* data, const std::array<int, 3>& dims, openvdb::math::Transform::Ptr xform,
                  const DenseSource& source, const DensePart& part = {});

/// Recomputes v.stats from v.grid over v.domain (used after editing a grid, and for sparse grids).
void compute_stats(Volume& v);

/// The exact percentiles (fractions in [0, 1]) of a volume whose finite values are all integers
/// (an integer voxel type) spanning at most 2^20 values: for each fraction f the smallest value v
/// with at least f of the finite voxels <= v, a value the volume holds. One counting pass over
/// the data domain (dense) or the active voxels (sparse). Empty when the volume's values are not
/// such integers (then the histogram's interpolated percentiles are what there is).
std::vector<double> exact_integer_percentiles(const Volume& v, const std::vector<double>& fractions);

}  // namespace isocurv::volume
