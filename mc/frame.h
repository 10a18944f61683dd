#pragma once
// What an extraction reads from a volume: which cells, how a voxel becomes a signed value, and
// the index-to-world map. Shared by the reference mesher and the device mesher so both agree.
// Tested in tests/mc/bricks_test.cpp, tests/dist/test_distributed.cpp.
#include <array>
#include <cmath>
#include <cstdint>

#include "mc/options.h"
#include "volume/volume.h"

namespace isocurv::mc {

struct Frame {
  openvdb::CoordBBox cells;   ///< index-space cells to visit (a cell's lower corner), inclusive
  openvdb::CoordBBox domain;  ///< voxels that hold data; others read as outside when `clip`
  bool clip = false;          ///< voxels outside `domain` read as outside (dense volumes)
  float isovalue = 0;
  float sign = 1;             ///< +1: inside is above the isovalue; -1: below
  float outside = -1;         ///< signed value given to non-finite voxels (< 0)
  /// Signed value of voxels outside `domain` when `clip`: so far below any sample that a vertex
  /// between a domain voxel and one outside lies on the domain voxel (kMinEdgeFraction off it at
  /// most), so capped surfaces close on the volume's box.
  float clipped = -1e30f;
  openvdb::Coord key_origin;  ///< edge keys count from here (the whole volume's cells.min() - 1)
  std::array<float, 12> world;  ///< row-major 3x4 affine map: world = A * index + b

  /// Signed insideness of a raw voxel value at `ijk`: > 0 inside the object, <= 0 outside.
  float signed_value(const openvdb::Coord& ijk, float v) const {
    if (clip && !domain.isInside(ijk)) return clipped;
    if (!std::isfinite(v)) return outside;
    return sign * (v - isovalue);
  }
};

/// The frame for extracting `iso` from `v`: dense volumes visit the cells inside their domain
/// (open surfaces at the box) or, with options.cap, one more cell layer around it read as
/// outside (closed surfaces); sparse grids visit their active box grown by one voxel.
/// Throws Error when the volume is empty, too large to key, or its transform is not affine.
Frame make_frame(const volume::Volume& v, float iso, const Options& options);

/// Position along an edge from its lower sample s0 to its upper sample s1 (opposite signs), as a
/// fraction of the edge, kept inside [kMinEdgeFraction, 1 - kMinEdgeFraction].
inline float edge_fraction(float s0, float s1) {
  float t = s0 / (s0 - s1);
  return std::fmin(std::fmax(t, kMinEdgeFraction), 1.0f - kMinEdgeFraction);
}

}  // namespace isocurv::mc
