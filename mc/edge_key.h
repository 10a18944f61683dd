#pragma once
// Identity of a cube edge (the key vertex fusion compares) and its hash. Mirrored in mc/*.cl.
#include <cstdint>

namespace isocurv::mc {

/// Key of the voxel-grid edge starting at index (x, y, z) (relative to the extraction's key
/// origin, each 0 .. 2^20-1) along axis 0/1/2: 20 bits a coordinate, then 2 bits of axis.
inline std::uint64_t edge_key(std::uint32_t x, std::uint32_t y, std::uint32_t z, std::uint32_t axis) {
  return (std::uint64_t(x) << 42) | (std::uint64_t(y) << 22) | (std::uint64_t(z) << 2) | axis;
}

/// Edge slots a hash gives each 8^3-voxel block (8^3 lower corners, 3 axes).
constexpr std::uint32_t kEdgeSlotsPerBlock = 8 * 8 * 8 * 3;

/// The mask keeping the low `bits` (1..32) bits of a hash.
inline std::uint32_t hash_mask(int bits) { return bits >= 32 ? 0xffffffffu : ((1u << bits) - 1u); }

/// 32-bit hash of the edge at key coordinates (x, y, z) along `axis`, spatially coherent:
/// 8^3-voxel blocks in order, z fastest like the bricks (`blocks_z` a column, `blocks_y` columns
/// a layer), 1536 edge slots each (z fastest too), wrapping past 2^32, then keeping the low
/// `bits` bits. Sorting by it keeps neighbouring edges together, and a walk over the bricks in
/// their order looks its seam vertices up in a few ascending streams.
inline std::uint32_t edge_hash(std::uint32_t x, std::uint32_t y, std::uint32_t z, std::uint32_t axis,
                               std::uint32_t blocks_z, std::uint32_t blocks_y, int bits) {
  const std::uint32_t block = (z >> 3) + blocks_z * ((y >> 3) + blocks_y * (x >> 3));
  const std::uint32_t slot = (((x & 7u) << 6) | ((y & 7u) << 3) | (z & 7u)) * 3u + axis;
  return (block * kEdgeSlotsPerBlock + slot) & hash_mask(bits);
}

/// Largest coordinate span (voxels) an extraction can key.
constexpr std::int64_t kMaxKeySpan = (1 << 20) - 2;

}  // namespace isocurv::mc
