#pragma once
// Sparse brick selection: only 8^3-cell bricks (aligned with VDB leaf nodes) whose samples,
// with a one-voxel apron, straddle the isovalue are sent to the device.
#include <cstdint>
#include <vector>

#include "mc/frame.h"
#include "volume/volume.h"

namespace isocurv::mc {

constexpr int kBrick = 8;                           ///< cells per brick edge
constexpr int kApron = kBrick + 1;                  ///< samples per brick edge
constexpr int kBrickSamples = kApron * kApron * kApron;

/// Per-block value ranges of a volume, independent of the isovalue: built once, then any number
/// of isovalues select bricks from it without touching the voxels again.
class BrickIndex {
 public:
  /// Scans every 8^3 block (leaf or tile) covering the volume's cells once (TBB, parallel).
  explicit BrickIndex(const volume::Volume& v);

  /// Origins (index space, multiples of 8) of the bricks of `f` that may hold surface: a superset
  /// of the straddling bricks, in a fixed order (x, y, z; z fastest).
  std::vector<openvdb::Coord> candidates(const Frame& f) const;

 private:
  struct Block {
    float min, max;   ///< finite value range of the block (min > max when none)
    bool nonfinite;   ///< holds a NaN or Inf voxel
    bool clipped;     ///< partly or wholly outside the data domain of a dense volume
  };
  static Block leaf_range(const float* values);  ///< range of a leaf's 512 values
  const Block& block(int bx, int by, int bz) const;
  openvdb::Coord first_;  ///< origin of block (0,0,0)
  int nx_ = 0, ny_ = 0, nz_ = 0;
  std::vector<Block> blocks_;
};

/// Writes the samples of the given bricks to `out` (room for origins.size() * kBrickSamples
/// floats): kBrickSamples signed values each (Frame::signed_value), z fastest (sample z + 9 y +
/// 81 x, as in a VDB leaf), from the brick origin. Bricks whose samples turn out not to straddle
/// are dropped from `origins` and from `out` (which stays packed). Parallel (TBB); deterministic
/// order.
void gather_bricks(const volume::Volume& v, const Frame& f, std::vector<openvdb::Coord>& origins, float* out);

}  // namespace isocurv::mc
