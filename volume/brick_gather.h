#pragma once
// The samples a set of filter windows read, gathered into 8^3 bricks for a device: what the volume
// curvature estimator sends instead of the dense volume (cost grows with the surface).
#include <cstdint>
#include <vector>

#include "core/mesh.h"
#include "volume/gaussian_jet.h"
#include "volume/volume.h"

namespace isocurv::volume {

/// Bricks of samples over a region of index space. Voxel coordinates relative to `origin` (a
/// multiple of 8); brick (bx, by, bz) of the region is table[(bz * dims.y + by) * dims.x + bx]:
/// its number in `samples` (512 floats each, voxel (x, y, z) of the brick at (z * 8 + y) * 8 + x),
/// or -1 when no window reaches it.
struct BrickGather {
  openvdb::Coord origin{0, 0, 0};
  openvdb::Coord dims{0, 0, 0};
  std::vector<std::int32_t> table;
  std::vector<float> samples;
  std::size_t bricks() const { return samples.size() / 512; }
};

/// Gathers the bricks holding every voxel within `reach` (index units per axis) of the index
/// position of each world point (clamped to the domain for dense volumes, as frame.clamp says).
/// Values are the grid's (a sparse grid's background where inactive). Parallel (TBB),
/// deterministic. Throws isocurv::Error when the region's table would exceed 2^31 bricks.
BrickGather gather_bricks(const openvdb::FloatGrid& grid, const GridFrame& frame,
                          const Positions& world_points, const openvdb::Vec3d& reach);

}  // namespace isocurv::volume
