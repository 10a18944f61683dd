#pragma once
// Sparse brick selection: only 8^3-cell bricks (aligned with VDB leaf nodes) whose samples,
// with a one-voxel apron, straddle the isovalue are sent to the device.
// Tested in tests/mc/bricks_test.cpp, tests/mc/extract_test.cpp.
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "mc/frame.h"
#include "volume/volume.h"

namespace isocurv::mc {

constexpr int kBrick = 8;                           ///< cells per brick edge
constexpr int kApron = kBrick + 1;                  ///< samples per brick edge
constexpr int kBrickSamples = kApron * kApron * kApron;

/// Per-block value ranges of a volume, independent of the isovalue: built once, then any number
/// of isovalues select and gather bricks from it without searching the tree again. Holds
/// pointers into the volume's leaf buffers: the volume must outlive it, unchanged. Const
/// members may be called from several threads at once.
///
/// Two layouts give the same candidates and samples. Dense: every block of the volume's box, for
/// dense volumes and for sparse grids whose box holds few blocks more than their leaves. Sparse:
/// only the blocks a brick near a leaf or near the face of a constant region (a tile unlike its
/// neighbour) reads, so that memory and time follow the leaves and tiles, not the bounding box
/// (a .vdb with two small objects far apart is legal): at most 27 blocks and 8 bricks for each
/// leaf and each block on such a face.
class BrickIndex {
 public:
  enum class Layout { automatic, dense, sparse };

  /// Scans every 8^3 block (leaf or tile) covering the volume's cells once (TBB, parallel); with
  /// the sparse layout, only the leaves, the tiles whose value is not the background, and the
  /// blocks around them. `layout` forces one layout (tests compare them).
  /// @throw Error when the volume's box spans more than 2^24 voxels along an axis (sparse layout).
  explicit BrickIndex(const volume::Volume& v, Layout layout = Layout::automatic);

  /// Whether the sparse layout was chosen.
  bool sparse() const { return sparse_; }
  /// Blocks held (about 90 bytes each; the sparse layout adds a hash-map entry a block and 12
  /// bytes a possible brick).
  std::size_t blocks() const { return blocks_.size(); }

  /// Origins (index space, multiples of 8) of the bricks of `f` that may hold surface (of a
  /// volume read in part, volume::Volume::slab, only those of its part), in a fixed
  /// order (x, y, z; z fastest). A superset of the straddling bricks, nearly exact: a brick's
  /// apron is judged by the ranges of just the neighbour blocks' samples it uses.
  std::vector<openvdb::Coord> candidates(const Frame& f) const;

  /// Writes the samples of the given bricks to `out` (room for origins.size() * kBrickSamples
  /// floats): kBrickSamples signed values each (Frame::signed_value), z fastest (sample z + 9 y
  /// + 81 x, as in a VDB leaf), from the brick origin. Bricks whose samples turn out not to
  /// straddle are dropped from `origins` and from `out` (which stays packed). Parallel (TBB);
  /// deterministic order. `f` must come from the volume this index was built on.
  void gather(const Frame& f, std::vector<openvdb::Coord>& origins, float* out) const;

 private:
  struct Range {
    float min, max;  ///< finite value range (min > max when there is none)
  };
  struct Block {
    /// part[d] (d = dx + 2 dy + 4 dz): the range of the samples a brick reads from this block
    /// when the block lies d above it. d = 0: the whole block; 1: its face x = 0; 2: face y = 0;
    /// 3: line x = y = 0 (along z); 4: face z = 0; 5: line x = z = 0 (along y); 6: line
    /// y = z = 0 (along x); 7: the corner (0, 0, 0).
    Range part[8];
    bool nonfinite;   ///< holds a NaN or Inf voxel
    bool clipped;     ///< partly or wholly outside the data domain of a dense volume
    const float* leaf;  ///< the leaf's 512 values (VDB order, z fastest), or null for a tile
    float tile;       ///< the constant value of a block without a leaf
  };
  static Block leaf_block(const float* values);            ///< ranges of a leaf's 512 values
  static Block leaf_block_nonfinite(const float* values);  ///< the same, for leaves with NaN/Inf
  /// The block at `o` (a leaf, or constant: a tile or the background); `dense`: flag it clipped
  /// where it leaves `domain`.
  static Block make_block(const openvdb::FloatGrid::ConstAccessor& acc, const openvdb::Coord& o, bool dense,
                          const openvdb::CoordBBox& domain);
  /// Whether a brick whose eight blocks (its own, then d = dx + 2 dy + 4 dz above; null past the
  /// index) are `blk` may straddle `iso`, judged by the ranges of just the samples it reads.
  static bool may_straddle(const Block* const* blk, bool above, float iso);
  std::size_t block_at(int bx, int by, int bz) const {  ///< z fastest, the bricks' order
    return (std::size_t(bx) * ny_ + by) * nz_ + bz;
  }
  /// The block at (bx, by, bz) (blocks from first_), or null past the index (reads as the
  /// background; bricks reading it may straddle).
  const Block* find(int bx, int by, int bz) const;
  void build_dense(const volume::Volume& v);
  void build_sparse(const volume::Volume& v);
  openvdb::Coord first_;  ///< origin of block (0,0,0)
  int nx_ = 0, ny_ = 0, nz_ = 0;
  float background_ = 0;  ///< the grid's background value (blocks past the index)
  std::vector<Block> blocks_;  ///< dense: every block, block_at order; sparse: those indexed
  bool sparse_ = false;
  /// Sparse layout: where each indexed block is in blocks_ (key: detail::block_key), and the
  /// bricks that may straddle (block coordinates from first_, in the candidates' order).
  std::unordered_map<std::uint64_t, std::uint32_t> slot_;
  std::vector<openvdb::Coord> bricks_;
};

}  // namespace isocurv::mc
