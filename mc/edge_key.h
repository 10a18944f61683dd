#pragma once
// Identity of a cube edge (the key vertex fusion compares) and its hash. Mirrored in mc/*.cl.
// Tested in tests/mc/edge_hash_test.cpp.
#include <cstdint>

namespace isocurv::mc {

/// Key of the voxel-grid edge starting at index (x, y, z) (relative to the extraction's key
/// origin, each 0 .. 2^20-1) along axis 0/1/2: 20 bits a coordinate, then 2 bits of axis.
inline std::uint64_t edge_key(std::uint32_t x, std::uint32_t y, std::uint32_t z, std::uint32_t axis) {
  return (std::uint64_t(x) << 42) | (std::uint64_t(y) << 22) | (std::uint64_t(z) << 2) | axis;
}

/// Edge slots a hash gives each 8^3-voxel block (8^3 lower corners, 3 axes).
constexpr std::uint32_t kEdgeSlotsPerBlock = 8 * 8 * 8 * 3;

/// Order of the point (x, y, z) (each 0..7) among its block's 512, the points on the block's
/// lower faces first so that each face, and each line where two meet, is one or two runs:
/// face x = 0 is points [0, 64), face y = 0 [56, 120), face z = 0 [49, 57) and [113, 169); line
/// x = y = 0 [56, 64), line x = z = 0 [49, 57), line y = z = 0 [56, 57) and [113, 120); the
/// corner 56. (Runs: face x interior, line y, corner, line z, face y interior, line x, face z
/// interior, then the block's interior.)
inline std::uint32_t block_point(std::uint32_t x, std::uint32_t y, std::uint32_t z) {
  if (x == 0) return y == 0 ? 56 + z : z == 0 ? 48 + y : (y - 1) * 7 + (z - 1);
  if (y == 0) return z == 0 ? 112 + x : 64 + (x - 1) * 7 + (z - 1);
  if (z == 0) return 120 + (x - 1) * 7 + (y - 1);
  return 169 + ((x - 1) * 7 + (y - 1)) * 7 + (z - 1);
}

/// The mask keeping the low `bits` (1..32) bits of a hash.
inline std::uint32_t hash_mask(int bits) { return bits >= 32 ? 0xffffffffu : ((1u << bits) - 1u); }

/// 32-bit hash of the edge starting at (x, y, z) along `axis`, in coordinates from a
/// brick-aligned origin (a multiple of 8 in index space), spatially coherent: the bricks' 8^3
/// blocks in order, z fastest like the bricks (`blocks_z` a column, `blocks_y` columns a layer),
/// 1536 edge slots each (3 axes a point, points in block_point order), wrapping past 2^32, then
/// keeping the low `bits` bits. The edges on one face of a block hash into one or two runs, so a
/// brick finds the vertices its upper neighbours own on their shared faces in a few ranges of the
/// sorted hashes.
inline std::uint32_t edge_hash(std::uint32_t x, std::uint32_t y, std::uint32_t z, std::uint32_t axis,
                               std::uint32_t blocks_z, std::uint32_t blocks_y, int bits) {
  const std::uint32_t block = (z >> 3) + blocks_z * ((y >> 3) + blocks_y * (x >> 3));
  const std::uint32_t slot = block_point(x & 7u, y & 7u, z & 7u) * 3u + axis;
  return (block * kEdgeSlotsPerBlock + slot) & hash_mask(bits);
}

/// Largest coordinate span (voxels) an extraction can key.
constexpr std::int64_t kMaxKeySpan = (1 << 20) - 2;

}  // namespace isocurv::mc
